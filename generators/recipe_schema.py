"""The recipe schema: every key a dataset recipe may hold, its kind, range, unit and default.

:mod:`generators.recipe` validates a recipe by walking :data:`RECIPE_SCHEMA` and adds the rules
that tie keys together; ``datasets/README.md`` shows :func:`schema_table` (a test keeps them
equal). The table lives here, apart from the validator (stop 80: a restructuring, no change in
behaviour), so that neither grows past the project's module size.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from .params import INTEGRATORS, MAX_SHAFT_SPEED_RPM, SCENE_LEVELS

__all__ = [
    "RECIPE_SCHEMA",
    "Key",
    "QUANTITIES",
    "DIRECTIONS",
    "DEFECT_KINDS",
    "CONDITION_SURFACES",
    "DEFAULT_CHUNK_SIZE",
    "TRAINING_CLASSIFIERS",
    "schema_table",
    "unit_text",
]

#: cases per parquet file (and per worker task) when a recipe does not say: four 32-signal SIMD
#: blocks (measured: 64-signal chunks ran 3-14 % slower than 128 or 256 on two workers)
DEFAULT_CHUNK_SIZE = 128

QUANTITIES = ("displacement", "velocity", "acceleration")
#: The classifiers ``cmtool train`` compares (``cmtool.classifier.candidate_classifiers``): a
#: recipe's ``[training] classifier`` names the one to keep on its datasets.
TRAINING_CLASSIFIERS = ("extra_trees", "random_forest", "gradient_boosting", "logistic_regression")
DIRECTIONS = ("x", "y")
DEFECT_KINDS = ("waviness", "localized")
CONDITION_SURFACES = {"healthy": None, "inner": "inner", "outer": "outer", "ball": "ball"}


@dataclass(frozen=True)
class Key:
    """One recipe key: where it lives, what it holds, its range, unit and default.

    ``kind`` is one of ``values`` (a number, a list of numbers or ``{min, max}``: a grid or a
    uniform range drawn per case), ``grid`` (a number or a list only), ``number`` (one number),
    ``integer`` (one integer), ``choice`` (one of ``choices``), ``flag`` (true or false),
    ``name`` (letters, digits, - and _), ``bearings`` (catalog names), ``bearing`` (one catalog
    name) and ``text`` (until stop 85 ``model.step_s`` and ``model.rtol`` were ``any``, checked
    only where :class:`~generators.params.SimulationSettings` took them, under its own names).
    """

    path: str  # "key" at the top, "section.key", or "conditions.key" for every condition
    kind: str
    low: float = -math.inf
    high: float = math.inf
    unit: str = ""
    default: Any = None  # filled in when the key is absent (None: optional, or required)
    required: bool = False
    choices: tuple = ()
    low_inclusive: bool = True
    high_inclusive: bool = True  # ``number`` keys only
    integer: bool = False  # ``values`` whose every value must be an integer
    doc: str = ""

    @property
    def section(self) -> str:
        """The table the key lives in ("" at the top, "conditions" in every condition)."""
        return self.path.rpartition(".")[0]

    @property
    def name(self) -> str:
        """The key's own name within its table."""
        return self.path.rpartition(".")[2]


#: The recipe schema: every key a recipe may hold (docs: datasets/README.md). One validator
#: (:func:`validate_recipe`) walks it; the rules that tie keys together follow the table.
RECIPE_SCHEMA: tuple[Key, ...] = (
    Key("name", "name", required=True, doc="dataset name: ids are <name>-<index>"),
    Key("seed", "integer", 0, math.inf, required=True, doc="seeds every case (one seed each)"),
    Key("description", "text", doc="free text"),
    Key("bearings", "bearings", default=["6205"], doc="catalog bearings, drawn per case"),
    Key(
        "chunk_size",
        "integer",
        1,
        10000,
        default=DEFAULT_CHUNK_SIZE,
        doc="cases per parquet file and worker task (32 per SIMD block)",
    ),
    Key(
        "operating.rpm",
        "values",
        0.0,
        MAX_SHAFT_SPEED_RPM,
        "rpm",
        required=True,
        low_inclusive=False,
        doc="shaft speed",
    ),
    Key("operating.load_n", "values", 0.0, 1e6, "N", required=True, doc="radial load"),
    Key(
        "operating.clearance_m",
        "values",
        -20e-6,
        200e-6,
        "m",
        doc="operating radial clearance (negative: preload)",
    ),
    Key(
        "operating.load_angle_deg",
        "values",
        -360.0,
        360.0,
        "deg",
        doc="direction of the radial load from the x axis (default -90: downward, along the "
        "sensor's y); outer-race pit positions are measured from it",
    ),
    Key(
        "operating.cage_slip",
        "values",
        0.0,
        0.1,
        "",
        doc="mean cage slip: the cage runs at (1 - s) of its kinematic speed (rate columns "
        "stay kinematic)",
    ),
    Key("operating.random_slip", "values", 0.0, 0.1, "", doc="cage speed fluctuation, std"),
    Key("operating.ball_jitter_rad", "values", 0.0, 0.1, "rad", doc="cage pocket play, std"),
    Key(
        "operating.race_form_waviness_m",
        "values",
        0.0,
        2e-6,
        "m",
        doc="form error of each race: waviness at order Z, drawn per race (generators.form)",
    ),
    Key(
        "operating.ball_form_waviness_m",
        "values",
        0.0,
        2e-6,
        "m",
        doc="form error of the balls: waviness at order 2 (generators.form)",
    ),
    Key(
        "model.scene",
        "choice",
        default="shaft+housing",
        choices=SCENE_LEVELS,
        doc="model level (docs/model.md 1.4)",
    ),
    Key("model.ehl", "flag", default=True, doc="lubricant film in the contacts"),
    Key("model.integrator", "choice", default="rk4", choices=INTEGRATORS, doc="time integrator"),
    Key(
        "model.step_s",
        "number",
        1e-9,
        1e-3,
        "s",
        doc="RK4 step (default: the scene's own; the range SimulationSettings allows)",
    ),
    Key(
        "model.error_bound",
        "number",
        1e-6,
        0.5,
        doc="RK4 step per bearing, rate and condition for this relative error (no step_s)",
    ),
    Key("model.rtol", "number", 1e-13, 0.1, doc="DOPRI5 relative tolerance"),
    Key(
        "model.shaft_mass_kg",
        "values",
        1e-3,
        1e4,
        "kg",
        doc="shaft mass at the bearing, drawn per case (default Rig's 1 kg)",
    ),
    Key(
        "model.housing_mass_kg",
        "values",
        1e-3,
        1e5,
        "kg",
        doc="housing mass, drawn per case (default Rig's 2 kg)",
    ),
    Key(
        "model.pedestal_stiffness_n_m",
        "values",
        1e3,
        1e13,
        "N/m",
        doc="housing support stiffness, drawn per case (default Rig's 5e7 N/m)",
    ),
    Key(
        "model.film_damping_factor",
        "values",
        0.0,
        10.0,
        "",
        doc="squeeze-film damping over docs/model.md 4.4's estimate, drawn per case (default 1)",
    ),
    Key(
        "model.film_entrainment_factor",
        "values",
        0.0,
        1.0,
        "",
        doc="the film's load at light load, as a share of a flooded contact's, drawn per case "
        "(docs/model.md 4.6; absent: 0, none; scenes shaft and shaft+housing with ehl only)",
    ),
    Key(
        "model.housing_damping_ratio",
        "values",
        1e-4,
        1.0,
        "",
        doc="damping ratio of the housing on its support: pedestal damping 2 zeta sqrt(k_h M_h), "
        "drawn per case (default: the Rig's 1e3 N s/m)",
    ),
    Key(
        "model.shaft_damping_ratio",
        "values",
        1e-4,
        1.0,
        "",
        doc="damping ratio of the shaft on the bearing: shaft damping 2 zeta sqrt(k_r M_s), k_r "
        "the bearing's static radial stiffness at the case's load (default: the Rig's 600 N s/m)",
    ),
    Key(
        "sensor.quantity",
        "choice",
        default="acceleration",
        choices=QUANTITIES,
        doc="what the signal measures",
    ),
    Key(
        "sensor.direction",
        "choice",
        default="y",
        choices=DIRECTIONS,
        doc="radial direction (y: vertical, along the default load)",
    ),
    Key(
        "sensor.body",
        "choice",
        default="housing",
        choices=("housing", "shaft"),
        doc="where the sensor sits",
    ),
    Key(
        "sensor.fs_hz",
        "grid",
        100.0,
        1e7,
        "Hz",
        required=True,
        doc="sample rates, alternating per pass through the operating grid",
    ),
    Key("sensor.duration_s", "number", 1e-3, 3600.0, "s", required=True, doc="record length"),
    Key(
        "sensor.settle_s",
        "number",
        0.0,
        3600.0,
        "s",
        default=0.1,
        doc="simulated before the record starts",
    ),
    Key("sensor.snr_db", "values", -40.0, 200.0, "dB", doc="white noise over the signal"),
    Key(
        "sensor.background_db",
        "values",
        -40.0,
        60.0,
        "dB",
        doc="broadband machine noise over the healthy bearing",
    ),
    Key(
        "sensor.fault_snr_db",
        "values",
        -60.0,
        200.0,
        "dB",
        doc="fault over everything else in its band (docs/realism.md 4)",
    ),
    Key("sensor.noise_rms", "number", 0.0, math.inf, "signal unit", doc="white noise, absolute"),
    Key(
        "sensor.resonance_hz",
        "values",
        1.0,
        math.inf,
        "Hz",
        doc="single sensor resonance (older model; bounded by 0.45 x the lowest fs)",
    ),
    Key(
        "sensor.resonance_damping",
        "number",
        0.0,
        1.0,
        low_inclusive=False,
        high_inclusive=False,
        doc="damping ratio of resonance_hz",
    ),
    Key("sensor.modes", "values", 1, 12, "", integer=True, doc="structural modes per case"),
    Key("sensor.mode_hz", "values", 1.0, 1e6, "Hz", doc="structural modes' frequencies (chain)"),
    Key("sensor.mode_damping", "values", 1e-3, 0.99, "", doc="their damping ratios (default 0.05)"),
    Key("sensor.mode_gain_db", "values", -60.0, 60.0, "dB", doc="their gains (default 0)"),
    Key(
        "sensor.sensor_resonance_hz",
        "values",
        1.0,
        1e6,
        "Hz",
        doc="accelerometer's mounted resonance (none if absent)",
    ),
    Key("sensor.sensor_damping", "values", 1e-3, 0.99, "", doc="its damping ratio (default 0.03)"),
    Key("sensor.anti_alias", "values", 0.05, 0.49, "x fs", doc="anti-alias cut-off over fs"),
    Key(
        "sensor.anti_alias_order",
        "values",
        1,
        16,
        "",
        integer=True,
        doc="its Butterworth order (default 8)",
    ),
    Key(
        "sensor.sensor_noise_density",
        "values",
        1e-9,
        0.1,
        "m/s^2/sqrt(Hz)",
        doc="accelerometer's own white noise after its resonance, absolute (none if absent;"
        " needs machine_velocity_mm_s and an acceleration; not in fault_snr_db)",
    ),
    Key(
        "sensor.electronic_floor_db",
        "values",
        -120.0,
        0.0,
        "dB",
        doc="sensor's and recorder's white noise over the sensor output's RMS (none if absent;"
        " not in fault_snr_db, which is measured before the sensor)",
    ),
    Key("sensor.adc_bits", "values", 2, 32, "bits", integer=True, doc="converter resolution"),
    Key(
        "sensor.adc_headroom_db",
        "values",
        -20.0,
        60.0,
        "dB",
        doc="full scale over the record's peak (default 6; negative clips)",
    ),
    Key(
        "sensor.machine_velocity_mm_s",
        "values",
        1e-3,
        100.0,
        "mm/s",
        doc="the healthy machine's overall velocity RMS in ISO 10816's band (10-1000 Hz; 2-1000"
        " Hz at 600 rpm or less) before the sensor: the record is scaled to it (its absolute"
        " level; the model's own if absent; the chain's other amplitudes are before it)",
    ),
    Key("sensor.other_bearing", "bearing", doc="the shaft's other bearing (prefer [background])"),
    Key(
        "background.shaft_db",
        "values",
        -80.0,
        80.0,
        "dB",
        doc="1x shaft line over the healthy bearing's RMS",
    ),
    Key(
        "background.shaft_harmonics",
        "values",
        1,
        20,
        "",
        integer=True,
        doc="shaft harmonics (default 3)",
    ),
    Key(
        "background.shaft_decay_db",
        "values",
        0.0,
        40.0,
        "dB per harmonic",
        doc="fall per harmonic (default 6)",
    ),
    Key("background.line_hz", "values", 1.0, 1000.0, "Hz", doc="mains frequency (default 60)"),
    Key("background.line_db", "values", -80.0, 80.0, "dB", doc="2x line (1x is 6 dB lower)"),
    Key("background.other_bearing", "bearing", doc="the shaft's other bearing (catalog name)"),
    Key(
        "background.other_bearing_db",
        "values",
        -80.0,
        80.0,
        "dB",
        doc="its varying-compliance lines",
    ),
    Key("background.floor_db", "values", -80.0, 80.0, "dB", doc="white floor before the sensor"),
    Key(
        "background.form_inner_db",
        "values",
        -80.0,
        80.0,
        "dB",
        doc="the test bearing's inner-race form lines (BPFI, BPFI -/+ fs)",
    ),
    Key(
        "background.form_ball_db",
        "values",
        -80.0,
        80.0,
        "dB",
        doc="the test bearing's ball form lines (2 BSF, 2 BSF -/+ FTF)",
    ),
    Key(
        "background.rotor_force_db",
        "values",
        -80.0,
        80.0,
        "dB",
        doc="broadband force on the rotor over the housing's (default: none)",
    ),
    Key(
        "conditions.label",
        "text",
        required=True,
        doc="class label (healthy/inner/outer/ball imply the surface)",
    ),
    Key("conditions.count", "integer", 1, 10**9, required=True, doc="signals of this condition"),
    Key(
        "conditions.surface",
        "choice",
        choices=("inner", "outer", "ball"),
        doc="defective surface (none: healthy)",
    ),
    Key("conditions.defect", "choice", choices=DEFECT_KINDS, doc="default waviness"),
    Key(
        "conditions.order",
        "values",
        1,
        500,
        "",
        integer=True,
        doc="waviness order (lobes round the circumference)",
    ),
    Key(
        "conditions.amplitude_m",
        "values",
        0.0,
        1e-4,
        "m",
        doc="waviness amplitude (radius deviation)",
    ),
    Key("conditions.length_m", "values", 1e-6, 0.05, "m", doc="pit size in the rolling direction"),
    Key("conditions.depth_m", "values", 0.0, 1e-3, "m", doc="pit depth"),
    Key(
        "conditions.position_rad",
        "values",
        -100.0,
        100.0,
        "rad",
        doc="pit centre (outer race default -pi/2; else drawn)",
    ),
    Key(
        "conditions.axis_drift_rad_s",
        "values",
        0.0,
        1e4,
        "rad/s",
        doc="ball pits: spin-axis turn rate (docs/realism.md 5)",
    ),
    Key(
        "training.classifier",
        "choice",
        choices=TRAINING_CLASSIFIERS,
        doc="classifier cmtool train keeps on this dataset (default: best grouped CV score)",
    ),
)


def schema_table() -> str:
    """The recipe schema as a Markdown table (datasets/README.md shows it; a test keeps them equal).

    Returns
    -------
    str
        A row per key: key, kind, range, default and meaning.

    Examples
    --------
    >>> print(schema_table().splitlines()[2])
    | `name` | name | - | required | dataset name: ids are <name>-<index> |
    """
    rows = ["| key | kind | range | default | meaning |", "|---|---|---|---|---|"]
    for key in RECIPE_SCHEMA:
        path = key.path.replace("conditions.", "[[conditions]] ")
        if key.kind == "choice":
            span = ", ".join(key.choices)
        elif math.isfinite(key.low) or math.isfinite(key.high):
            opening = "[" if key.low_inclusive else "("
            closing = "]" if key.high_inclusive else ")"
            span = f"{opening}{key.low:g}, {key.high:g}{closing}{unit_text(key)}"
        else:
            span = "-"
        default = "required" if key.required else ("" if key.default is None else key.default)
        default = f"`{default}`" if default not in ("", "required") else default
        kind = key.kind + (" (integers)" if key.integer else "")
        rows.append(f"| `{path}` | {kind} | {span} | {default} | {key.doc} |")
    return "\n".join(rows) + "\n"


def unit_text(key: Key) -> str:
    """A key's unit as the errors and the schema table write it: " [unit]", or "" if none.

    Parameters
    ----------
    key : Key
        A key of :data:`RECIPE_SCHEMA`.

    Returns
    -------
    str
        E.g. " [N]" for ``operating.load_n``.
    """
    return f" [{key.unit}]" if key.unit else ""
