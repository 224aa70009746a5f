"""The cases of a recipe: every signal to generate, with all its parameters drawn.

A validated recipe (:func:`generators.recipe.validate_recipe`) expands into :class:`Case`
objects, one per signal, in index order; each gets its own seed from
``numpy.random.SeedSequence(recipe seed)`` spawned in case order, so a case depends only on the
recipe and its index. The columns written for each generated signal are :class:`CaseRecord`'s.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass, field, fields

import numpy as np

__all__ = [
    "Case",
    "CaseRecord",
    "CASE_COLUMNS",
    "DAMPING_RATIO_KEYS",
    "RIG_KEYS",
    "case_count",
    "expand_cases",
    "iter_cases",
]


@dataclass(frozen=True)
class CaseRecord:
    """The metadata columns of one generated signal, in file order (units in the names).

    The dataset files' schema is derived from it (``cmtool.datasets.DATA_SCHEMA``): ``str``
    columns are text, ``bool`` and ``int`` (``unsigned``: the 64-bit seed) integers, the rest
    float64 (NaN where a column does not apply). datasets/README.md describes each column.
    """

    id: str
    index: int
    label: str
    condition: int
    bearing: str
    operating_point_id: int
    rpm: float
    shaft_frequency_hz: float
    radial_load_n: float
    load_angle_rad: float
    shaft_mass_kg: float
    housing_mass_kg: float
    pedestal_stiffness_n_m: float
    film_damping_factor: float
    film_entrainment_factor: float
    housing_damping_ratio: float
    shaft_damping_ratio: float
    radial_internal_clearance_m: float
    surface: str
    waviness_order: int
    waviness_amplitude_m: float
    defect_kind: str
    defect_length_m: float
    defect_depth_m: float
    defect_position_rad: float
    defect_axis_drift_rad_s: float
    seed: int = field(metadata={"unsigned": True})
    scene: str
    ehl: bool
    integrator: str
    step_s: float
    quantity: str
    body: str
    direction: str
    fs_hz: float
    duration_s: float
    snr_db: float
    background_db: float
    fault_snr_db: float
    noise_rms: float
    resonance_hz: float
    ftf_hz: float
    bpfo_hz: float
    bpfi_hz: float
    bsf_hz: float
    two_bsf_hz: float
    wpf_hz: float
    random_slip: float
    ball_jitter_rad: float
    cage_slip: float
    inner_form_waviness_m: float
    outer_form_waviness_m: float
    ball_form_waviness_m: float
    fault_band_low_hz: float
    fault_band_high_hz: float
    chain: str


#: Metadata columns of a generated signal, in order (units in the names).
CASE_COLUMNS = tuple(f.name for f in fields(CaseRecord))


def column_kind(name: str) -> str:
    """A metadata column's storage kind: ``text``, ``bool``, ``int``, ``uint`` or ``float``.

    Parameters
    ----------
    name : str
        The column's name.

    Returns
    -------
    str

    Examples
    --------
    >>> column_kind("seed"), column_kind("rpm"), column_kind("label")
    ('uint', 'float', 'text')
    """
    f = _FIELDS[name]
    if f.metadata.get("unsigned"):
        return "uint"
    return {"str": "text", "bool": "bool", "int": "int"}.get(str(f.type), "float")


_FIELDS = {f.name: f for f in fields(CaseRecord)}


@dataclass(frozen=True)
class Case:
    """One signal to generate (all parameters drawn, SI units)."""

    index: int
    label: str
    condition: int
    bearing: str
    operating_point_id: int
    rpm: float
    radial_load_n: float
    clearance_m: float | None
    surface: str | None
    waviness_order: int
    waviness_amplitude_m: float
    snr_db: float | None
    seed: int
    background_db: float = math.nan
    fault_snr_db: float = math.nan
    defect_kind: str = "none"
    defect_length_m: float = math.nan
    defect_depth_m: float = math.nan
    defect_position_rad: float = math.nan
    defect_axis_drift_rad_s: float = math.nan
    fs_hz: float = math.nan
    resonance_hz: float = math.nan
    random_slip: float = 0.0
    ball_jitter_rad: float = 0.0
    cage_slip: float = 0.0
    inner_form_waviness_m: float = 0.0
    outer_form_waviness_m: float = 0.0
    ball_form_waviness_m: float = 0.0
    load_angle_rad: float = -math.pi / 2
    shaft_mass_kg: float = math.nan  # NaN: the default Rig's
    housing_mass_kg: float = math.nan
    pedestal_stiffness_n_m: float = math.nan
    film_damping_factor: float = math.nan
    housing_damping_ratio: float = math.nan  # NaN: the Rig's dashpots as they are
    shaft_damping_ratio: float = math.nan
    film_entrainment_factor: float = math.nan  # NaN: none (the Rig's 0)


#: The rig's parameters a recipe may draw under ``[model]``: recipe key (and case column) ->
#: ``generators.Rig`` field. NaN in a case: the default Rig's value.
RIG_KEYS = {
    "shaft_mass_kg": "shaft_mass",
    "housing_mass_kg": "housing_mass",
    "pedestal_stiffness_n_m": "pedestal_stiffness",
    "film_damping_factor": "film_damping_factor",
}

#: Modal damping ratios a recipe may draw under ``[model]``: recipe key (and case column) ->
#: the ``generators.Rig`` dashpot it sets, c = 2 zeta sqrt(k M) (``synthesis.case_rig``): the
#: housing on its support (k_h, M_h), the shaft on the bearing (its static radial stiffness at
#: the case's load, M_s). A drawn mass or stiffness then keeps a plausible damping ratio,
#: where a fixed dashpot would not (docs/realism.md 5).
DAMPING_RATIO_KEYS = {
    "housing_damping_ratio": "pedestal_damping",
    "shaft_damping_ratio": "shaft_damping",
}


def _draw(spec: dict, rng: np.random.Generator, cycle: int, *, integer: bool = False):
    if "grid" in spec:
        v = spec["grid"][cycle % len(spec["grid"])]
    else:
        lo, hi = spec["range"]
        v = rng.integers(int(lo), int(hi) + 1) if integer else rng.uniform(lo, hi)
    return int(v) if integer else float(v)


def case_count(recipe: dict) -> int:
    """Number of cases (signals) of a validated recipe.

    Parameters
    ----------
    recipe : dict
        The recipe, validated (``generators.recipe.validate_recipe``).

    Returns
    -------
    int
    """
    return sum(c["count"] for c in recipe["conditions"])


def expand_cases(recipe: dict) -> list[Case]:
    """All cases of a validated recipe, in index order (deterministic): ``list(iter_cases())``.

    Grid operating points: each condition cycles through the full grid (bearing x rpm x load
    x clearance) so every label sees every operating point; ranges draw one value per case.
    Defect grids (orders, amplitudes, sizes) cycle too, shifted by one value per pass through
    the operating grid, so that no defect value is tied to a single operating point.
    ``operating_point_id`` numbers the distinct (bearing, rpm, load, clearance) points so
    that splits can group by it.

    Parameters
    ----------
    recipe : dict
        The recipe, validated (``generators.recipe.validate_recipe``).

    Returns
    -------
    list of Case
    """
    return list(iter_cases(recipe))


def iter_cases(recipe: dict) -> Iterator[Case]:
    """The cases of :func:`expand_cases` one at a time, in index order.

    Each case is drawn from its own child of the recipe seed's ``SeedSequence`` (children
    spawned one by one are those of a single ``spawn(n)``), so a generator can start
    simulating the first chunk before the last case exists (drawing costs ~50 us per case).

    Parameters
    ----------
    recipe : dict
        The recipe, validated (``generators.recipe.validate_recipe``).

    Yields
    ------
    Case
    """
    r = recipe
    op = r["operating"]
    parent = np.random.SeedSequence(r["seed"])
    grids = [
        (b, rpm, load, cl)
        for b in r["bearings"]
        for rpm in (op["rpm"].get("grid") or [None])
        for load in (op["load_n"].get("grid") or [None])
        for cl in ((op.get("clearance_m") or {}).get("grid") or [None])
    ]
    point_ids: dict[tuple, int] = {}
    index = 0
    for ci, cond in enumerate(r["conditions"]):
        for k in range(cond["count"]):
            ss = parent.spawn(1)[0]
            rng = np.random.default_rng(ss)
            b, rpm, load, cl = grids[k % len(grids)]
            rpm = rpm if rpm is not None else _draw(op["rpm"], rng, k)
            load = load if load is not None else _draw(op["load_n"], rng, k)
            if "clearance_m" in op:
                cl = cl if cl is not None else _draw(op["clearance_m"], rng, k)
            key = (b, round(rpm, 6), round(load, 6), None if cl is None else round(cl, 12))
            pid = point_ids.setdefault(key, len(point_ids))
            # defect grids shift by one per pass through the operating grid, so that a defect
            # value is not tied to one operating point (splits grouped by operating point
            # would otherwise hold out every case of that value)
            shifted = k + k // len(grids)
            order, amp = 0, 0.0
            kind, length, depth, position = "none", math.nan, math.nan, math.nan
            drift = math.nan
            if cond["defect"] == "waviness":
                kind = "waviness"
                order = _draw(cond["order"], rng, shifted, integer=True)
                amp = _draw(cond["amplitude_m"], rng, shifted)
            elif cond["defect"] == "localized":
                kind = "localized"
                length = _draw(cond["length_m"], rng, shifted)
                depth = _draw(cond["depth_m"], rng, shifted)
                if "position_rad" in cond:
                    position = _draw(cond["position_rad"], rng, shifted)
                elif cond["surface"] == "outer":
                    position = -math.pi / 2  # centre of the load zone (downward load)
                if cond["surface"] == "ball":
                    drift = 0.0
                    if "axis_drift_rad_s" in cond:
                        drift = _draw(cond["axis_drift_rad_s"], rng, shifted)
            snr = None
            if "snr_db" in r["sensor"]:
                snr = _draw(r["sensor"]["snr_db"], rng, k)
            # sample rates alternate per full pass through the operating grid (every
            # operating point sees every rate)
            background = math.nan
            if "background_db" in r["sensor"]:
                background = _draw(r["sensor"]["background_db"], rng, k)
            fault_snr = math.nan
            if "fault_snr_db" in r["sensor"] and cond["surface"] is not None:
                fault_snr = _draw(r["sensor"]["fault_snr_db"], rng, k)
            fs = _draw(r["sensor"]["fs_hz"], rng, k // len(grids))
            resonance = math.nan
            if "resonance_hz" in r["sensor"]:
                resonance = _draw(r["sensor"]["resonance_hz"], rng, k)
            # drawn last, so that recipes without them draw every other value as before
            slip = _draw(op["random_slip"], rng, k) if "random_slip" in op else 0.0
            jitter = _draw(op["ball_jitter_rad"], rng, k) if "ball_jitter_rad" in op else 0.0
            form = [0.0, 0.0, 0.0]  # inner, outer, ball: after the others, for the same reason
            if "race_form_waviness_m" in op:
                form[0] = _draw(op["race_form_waviness_m"], rng, k)
                form[1] = _draw(op["race_form_waviness_m"], rng, k)
            if "ball_form_waviness_m" in op:
                form[2] = _draw(op["ball_form_waviness_m"], rng, k)
            load_angle = -math.pi / 2  # downward, along the sensor's axis y; drawn last too
            if "load_angle_deg" in op:
                load_angle = math.radians(_draw(op["load_angle_deg"], rng, k))
                if kind == "localized" and cond["surface"] == "outer":
                    position += load_angle + math.pi / 2  # the recipe's angle is from the load
            rig = {  # the rig's masses, support, film damping, damping ratios: drawn last too
                key: _draw(r["model"][key], rng, k) if key in r["model"] else math.nan
                for key in (*RIG_KEYS, *DAMPING_RATIO_KEYS)
            }
            cage_slip = _draw(op["cage_slip"], rng, k) if "cage_slip" in op else 0.0  # last
            entrainment = math.nan  # the film at light load: after everything else
            if "film_entrainment_factor" in r["model"]:
                entrainment = _draw(r["model"]["film_entrainment_factor"], rng, k)
            yield Case(
                index=index,
                label=cond["label"],
                condition=ci,
                bearing=b,
                operating_point_id=pid,
                rpm=rpm,
                radial_load_n=load,
                clearance_m=cl,
                surface=cond["surface"],
                waviness_order=order,
                waviness_amplitude_m=amp,
                snr_db=snr,
                seed=int(ss.generate_state(1)[0]),
                defect_kind=kind,
                defect_length_m=length,
                defect_depth_m=depth,
                defect_position_rad=position,
                defect_axis_drift_rad_s=drift,
                fs_hz=fs,
                resonance_hz=resonance,
                background_db=background,
                fault_snr_db=fault_snr,
                random_slip=slip,
                ball_jitter_rad=jitter,
                cage_slip=cage_slip,
                inner_form_waviness_m=form[0],
                outer_form_waviness_m=form[1],
                ball_form_waviness_m=form[2],
                load_angle_rad=load_angle,
                film_entrainment_factor=entrainment,
                **rig,
            )
            index += 1
