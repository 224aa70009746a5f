"""Dataset recipes: a TOML recipe -> a validated recipe -> the list of cases it describes.

A recipe (TOML, see ``datasets/small.toml``) names bearings, an operating grid or random ranges,
conditions with their waviness ranges and counts, the model and integrator, the sensor
(quantity, direction, sample rate, duration, noise, optional resonance) and a seed. Everything
is validated before any simulation starts (errors name the key and the value).

Reproducibility: every case gets its own seed from ``numpy.random.SeedSequence(recipe seed)``
spawned in case order, so a case's signal depends only on the recipe and its index, never on
the number of workers or the order they finish in. Each case is simulated by
:mod:`generators.synthesis`.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Any

from ._validate import ParameterError
from .catalog import BEARINGS, bearing
from .content import fault_rates_outside_record, odd_ball_waviness
from .params import (
    INTEGRATORS,
    MAX_SHAFT_SPEED_RPM,
    SCENE_LEVELS,
    OperatingCondition,
    operating_range_warnings,
)

__all__ = [
    "validate_recipe",
    "recipe_rating_warnings",
    "recipe_content_warnings",
    "schema_table",
    "RECIPE_SCHEMA",
    "Key",
    "QUANTITIES",
    "DIRECTIONS",
    "DEFAULT_CHUNK_SIZE",
    "TRAINING_CLASSIFIERS",
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
    name), ``text`` and ``any`` (checked where it is used: ``model.step_s`` and ``model.rtol``
    by :class:`~generators.params.SimulationSettings`).
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
    Key("model.step_s", "any", unit="s", doc="RK4 step (default: the scene's own)"),
    Key(
        "model.error_bound",
        "number",
        1e-6,
        0.5,
        doc="RK4 step per bearing, rate and condition for this relative error (no step_s)",
    ),
    Key("model.rtol", "any", doc="DOPRI5 relative tolerance"),
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
        "number",
        0.0,
        1.0,
        doc="the film's load at light load, as a share of a flooded contact's "
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
_SECTIONS = ("operating", "model", "sensor", "background", "training")
#: Keys of [sensor] that describe the realistic measurement chain (docs/realism.md).
_CHAIN_SENSOR_KEYS = (
    "modes",
    "mode_hz",
    "mode_damping",
    "mode_gain_db",
    "sensor_resonance_hz",
    "sensor_damping",
    "electronic_floor_db",
    "anti_alias",
    "anti_alias_order",
    "adc_bits",
    "adc_headroom_db",
)
#: Keys of a [[conditions]] table per defect kind.
_KIND_KEYS = {
    "waviness": ("order", "amplitude_m"),
    "localized": ("length_m", "depth_m", "position_rad", "axis_drift_rad_s"),
}
#: Keys of a [[conditions]] table that describe its defect.
_DEFECT_KEYS = frozenset({"defect", *_KIND_KEYS["waviness"], *_KIND_KEYS["localized"]})


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
            span = f"{opening}{key.low:g}, {key.high:g}{closing}{_unit(key)}"
        else:
            span = "-"
        default = "required" if key.required else ("" if key.default is None else key.default)
        default = f"`{default}`" if default not in ("", "required") else default
        kind = key.kind + (" (integers)" if key.integer else "")
        rows.append(f"| `{path}` | {kind} | {span} | {default} | {key.doc} |")
    return "\n".join(rows) + "\n"


def _keys(section: str) -> dict[str, Key]:
    return {k.name: k for k in RECIPE_SCHEMA if k.section == section}


def _fail(key: str, value: Any, why: str) -> ParameterError:
    return ParameterError(f"recipe key {key} = {value!r}: {why}")


def _range_or_grid(
    key: str, value: Any, *, low: float, high: float, unit: str, low_inclusive: bool = True
) -> dict:
    """A list of numbers (grid) or a table {min, max} (random uniform per case)."""
    given = value
    interval = f"{'[' if low_inclusive else '('}{low:g}, {high:g}] {unit}"

    def inside(v: object) -> bool:
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            return False
        return (low <= v if low_inclusive else low < v) and v <= high

    if isinstance(value, (int, float)) and not isinstance(value, bool):
        value = [value]
    if isinstance(value, list):
        if not value:
            raise _fail(key, given, "the list is empty")
        for v in value:
            if not inside(v):
                raise _fail(key, given, f"every value must be a number in {interval}")
        return {"grid": [float(v) for v in value]}
    if isinstance(value, dict):
        if set(value) != {"min", "max"}:
            raise _fail(key, value, "a range is a table with exactly 'min' and 'max'")
        lo, hi = value["min"], value["max"]
        for v in (lo, hi):
            if not inside(v):
                raise _fail(key, value, f"min and max must be numbers in {interval}")
        if lo > hi:
            raise _fail(key, value, "min is larger than max")
        return {"range": (float(lo), float(hi))}
    raise _fail(key, value, "expected a number, a list of numbers or {min, max}")


def _value(key: Key, where: str, value: Any) -> Any:
    """One key's value checked and normalised as its kind says (raises ParameterError)."""
    if key.kind in ("values", "grid"):
        out = _range_or_grid(
            where,
            value,
            low=key.low,
            high=key.high,
            unit=key.unit,
            low_inclusive=key.low_inclusive,
        )
        if key.kind == "grid" and "grid" not in out:
            raise _fail(where, value, "a value or a list of them is required")
        if key.integer and any(v != int(v) for v in out.get("grid", out.get("range", ()))):
            raise _fail(where, value, "integers are required")
        return out
    if key.kind in ("number", "integer"):
        number = isinstance(value, (int, float)) and not isinstance(value, bool)
        if key.kind == "integer":
            number = number and isinstance(value, int)
        above = number and (key.low <= value if key.low_inclusive else key.low < value)
        below = number and (value <= key.high if key.high_inclusive else value < key.high)
        if not (above and below):
            what = "an integer" if key.kind == "integer" else "a number"
            low, high = (
                (f"{key.low:.0f}", f"{key.high:.0f}")
                if key.kind == "integer"
                else (f"{key.low:g}", f"{key.high:g}")
            )
            opening = "[" if key.low_inclusive else "("
            closing = "]" if key.high_inclusive else ")"
            interval = f"{opening}{low}, {high}{closing}"
            raise _fail(where, value, f"{what} in {interval}{_unit(key)} is required")
        return value
    if key.kind == "choice":
        if value not in key.choices:
            raise _fail(where, value, f"allowed: {', '.join(key.choices)}")
        return value
    if key.kind == "flag":
        if not isinstance(value, bool):
            raise _fail(where, value, "true or false")
        return value
    if key.kind == "name":
        if not isinstance(value, str) or not value.replace("-", "").replace("_", "").isalnum():
            raise _fail(where, value, "a name of letters, digits, - and _ is required")
        return value
    if key.kind == "bearings":
        names = [value] if isinstance(value, str) else value
        if not isinstance(names, list) or not names:
            raise _fail(where, value, "a non-empty list of catalog names is required")
        for b in names:
            if str(b).lower() not in BEARINGS:
                raise _fail(where, value, f"{b!r} is not in the catalog {sorted(BEARINGS)}")
        return [str(b).lower() for b in names]
    if key.kind == "bearing":
        if str(value).lower() not in BEARINGS:
            raise _fail(where, value, f"not in {sorted(BEARINGS)}")
        return str(value).lower()
    if key.kind == "text":
        if not isinstance(value, str) or not value:
            raise _fail(where, value, "a text is required")
        return value
    return value  # "any"


def _walk(table: dict, section: str, where: str, *, only: set[str] | None = None) -> None:
    """Check every key of ``table`` against the schema's ``section`` (in place, in order)."""
    schema = _keys(section)
    unknown = sorted(set(table) - set(schema))
    if unknown:
        name = unknown[0]
        allowed = f"; allowed: {sorted({*schema, *_SECTIONS, 'conditions'})}" if not section else ""
        raise _fail(f"{where}{name}", table[name], f"unknown key{allowed}")
    for name, key in schema.items():
        if only is not None and name not in only:
            continue
        if name in table:
            table[name] = _value(key, f"{where}{name}", table[name])
        elif key.default is not None:
            table[name] = copy.deepcopy(key.default)
        elif key.required:
            raise _fail(f"{where}{name}", None, f"required ({key.kind}{_unit(key)})")


def _unit(key: Key) -> str:
    return f" [{key.unit}]" if key.unit else ""


def validate_recipe(recipe: dict) -> dict:
    """Check a recipe completely and return a normalised copy (raises ParameterError).

    Walks :data:`RECIPE_SCHEMA` (every key's kind, range, unit and default), then the rules
    that tie keys together: one noise model, the realistic chain's needs, each condition's
    surface and defect kind.

    Parameters
    ----------
    recipe : dict
        Parsed TOML.

    Returns
    -------
    dict
        The recipe with defaults filled in and ranges normalised.
    """
    r = copy.deepcopy(recipe)
    top = {k: v for k, v in r.items() if k not in (*_SECTIONS, "conditions")}
    _walk(top, "", "")
    r.update(top)
    for section in _SECTIONS:
        table = r.setdefault(section, {}) if section == "model" else r.get(section)
        if section in ("background", "training") and table is None:
            continue
        if not isinstance(table, dict):
            raise _fail(section, table, "a table is required")
        _walk(table, section, f"{section}.")
    model = r["model"]
    if model.get("film_entrainment_factor") and (model["scene"] == "full" or not model["ehl"]):
        raise _fail(
            "model.film_entrainment_factor",
            model["film_entrainment_factor"],
            "needs the film (ehl = true) and massless balls (scene shaft or shaft+housing)",
        )
    if model.get("error_bound") is not None:
        if model.get("step_s") is not None:
            raise _fail("model.error_bound", model["error_bound"], "give error_bound or step_s")
        if model.get("integrator") != "rk4":
            raise _fail("model.error_bound", model["error_bound"], "needs integrator = 'rk4'")
    sensor = r["sensor"]
    _noise_rules(sensor)
    _chain_rules(r, min(sensor["fs_hz"]["grid"]))
    conditions = r.get("conditions")
    if not isinstance(conditions, list) or not conditions:
        raise _fail("conditions", conditions, "a non-empty list of [[conditions]] is required")
    labels: set[str] = set()
    for i, c in enumerate(conditions):
        _condition(c, f"conditions[{i}]", labels)
    return r


def recipe_rating_warnings(recipe: dict) -> list[str]:
    """Where a validated recipe's cases go beyond a bearing's catalogue ratings.

    Each bearing at the recipe's largest radial load and its fastest speed, through
    :func:`generators.params.operating_range_warnings` (basic static load rating C0r,
    limiting speed); one message per bearing and rating exceeded, prefixed by the bearing.

    Parameters
    ----------
    recipe : dict
        :func:`validate_recipe`'s result.

    Returns
    -------
    list of str
    """

    def largest(values: dict) -> float:
        return max(values["grid"]) if "grid" in values else values["range"][1]

    operating = OperatingCondition.from_rpm(
        largest(recipe["operating"]["rpm"]), largest(recipe["operating"]["load_n"])
    )
    return [
        f"recipe bearing {name}: {message}"
        for name in recipe["bearings"]
        for message in operating_range_warnings(bearing(name), operating)
    ]


def recipe_content_warnings(recipe: dict) -> list[str]:
    """Where a validated recipe's signals cannot show what their labels name.

    :func:`generators.content.fault_rates_outside_record` for each bearing at the recipe's
    fastest speed and lowest sample rate (fault rates at or above fs / 2), and
    :func:`generators.content.odd_ball_waviness` for each ball waviness condition's orders
    in the recipe's scene (odd orders without ball masses make a healthy bearing's signal);
    one message per bearing or condition, prefixed by it.

    Parameters
    ----------
    recipe : dict
        :func:`validate_recipe`'s result.

    Returns
    -------
    list of str
    """

    def values(spec: dict) -> list[float]:
        return list(spec["grid"]) if "grid" in spec else list(spec["range"])

    fastest = max(values(recipe["operating"]["rpm"])) / 60.0
    lowest_fs = min(values(recipe["sensor"]["fs_hz"]))
    messages = []
    for name in recipe["bearings"]:
        message = fault_rates_outside_record(bearing(name), fastest, lowest_fs)
        if message is not None:
            messages.append(f"recipe bearing {name}: {message}")
    for i, c in enumerate(recipe["conditions"]):
        if c.get("surface") == "ball" and c.get("defect") == "waviness":
            spec = c["order"]
            orders = (
                spec["grid"]
                if "grid" in spec
                else range(math.ceil(spec["range"][0]), math.floor(spec["range"][1]) + 1)
            )
            message = odd_ball_waviness((int(k) for k in orders), recipe["model"]["scene"])
            if message is not None:
                messages.append(f"recipe conditions[{i}] ({c['label']!r}): {message}")
    return messages


def _noise_rules(sensor: dict) -> None:
    """One noise model per recipe; the fault SNR needs the healthy cases' background."""
    given = [k for k in ("snr_db", "background_db", "noise_rms") if k in sensor]
    if len(given) > 1:
        raise _fail(
            f"sensor.{given[1]}",
            _shown(sensor[given[1]]),
            f"give one of snr_db, background_db, noise_rms (also given: {given[0]})",
        )
    if "fault_snr_db" in sensor and "background_db" not in sensor:
        raise _fail(
            "sensor.fault_snr_db",
            _shown(sensor["fault_snr_db"]),
            "needs background_db too (the noise of the healthy cases)",
        )


def _chain_rules(r: dict, fs_min: float) -> None:
    """The sensor models: the older single resonance, or the realistic chain (docs/realism.md)."""
    sensor = r["sensor"]
    if "resonance_hz" in sensor:
        high = 0.45 * fs_min
        values = sensor["resonance_hz"].get("grid", sensor["resonance_hz"].get("range", ()))
        if any(v > high for v in values):
            raise _fail(
                "sensor.resonance_hz",
                recipe_value(sensor["resonance_hz"]),
                f"every value must be a number in [1, {high:g}] Hz (below 0.45 x the lowest "
                "sample rate)",
            )
        sensor.setdefault("resonance_damping", 0.05)
    realistic = "background" in r or "modes" in sensor
    if not realistic:
        for key in set(_CHAIN_SENSOR_KEYS) & set(sensor):
            why = "needs sensor.modes (the transfer path)"
            raise _fail(f"sensor.{key}", _shown(sensor[key]), why)
        return
    if "background_db" not in sensor:
        raise _fail(
            "sensor.background_db",
            None,
            "the realistic chain needs background_db (broadband machine noise over the "
            "healthy bearing)",
        )
    if "resonance_hz" in sensor:
        raise _fail(
            "sensor.resonance_hz",
            recipe_value(sensor["resonance_hz"]),
            "give the structure as modes, mode_hz, mode_damping (resonance_hz is the older "
            "single-resonance sensor model)",
        )
    if "modes" in sensor and "mode_hz" not in sensor:
        raise _fail("sensor.mode_hz", None, "the modes' frequency range is required")
    background = r.setdefault("background", {})
    if "other_bearing_db" in background and "other_bearing" not in background:
        raise _fail("background.other_bearing", None, "other_bearing_db needs other_bearing")
    # mode and sensor frequencies above 0.45 fs are out of band and ignored


def _shown(value: Any) -> Any:
    """A key's value for an error message: as the recipe wrote it when it was normalised."""
    if isinstance(value, dict) and set(value) in ({"grid"}, {"range"}):
        return recipe_value(value)
    return value


def recipe_value(normalised: dict) -> Any:
    """A normalised ``values`` key as the recipe wrote it (for error messages).

    Parameters
    ----------
    normalised : dict
        The key's normalised form, ``{"grid": [...]}`` or ``{"range": (low, high)}``.

    Returns
    -------
    Any
        The value as written in the TOML.
    """
    if "grid" in normalised:
        grid = normalised["grid"]
        return grid[0] if len(grid) == 1 else grid
    low, high = normalised["range"]
    return {"min": low, "max": high}


def _condition(c: Any, where: str, labels: set[str]) -> None:
    """One [[conditions]] table: label, count, and the surface's defect kind and keys."""
    if not isinstance(c, dict):
        raise _fail(where, c, "a table is required")
    _walk(c, "conditions", f"{where}.", only={"label", "count"})
    if c["label"] in labels:
        raise _fail(f"{where}.label", c["label"], "labels must be unique")
    labels.add(c["label"])
    surface = c.get("surface", CONDITION_SURFACES.get(c["label"]))
    if surface is None:
        if _DEFECT_KEYS & set(c):
            why = "a defect condition needs a surface (inner, outer or ball)"
            raise _fail(f"{where}.surface", None, why)
        c["surface"] = None
        c["defect"] = None
        return
    schema = _keys("conditions")
    c["surface"] = _value(schema["surface"], f"{where}.surface", surface)
    kind = c["defect"] = _value(schema["defect"], f"{where}.defect", c.get("defect", "waviness"))
    other = "localized" if kind == "waviness" else "waviness"
    wrong = sorted(set(_KIND_KEYS[other]) & set(c))
    if wrong:
        raise _fail(f"{where}.{wrong[0]}", c[wrong[0]], f"not a key of a {kind} defect")
    if "axis_drift_rad_s" in c and surface != "ball":
        raise _fail(f"{where}.axis_drift_rad_s", c["axis_drift_rad_s"], "only for ball defects")
    required = {"waviness": ("order", "amplitude_m"), "localized": ("length_m", "depth_m")}[kind]
    for name in _KIND_KEYS[kind]:
        if name in c or name in required:
            c[name] = _value(schema[name], f"{where}.{name}", c.get(name))
