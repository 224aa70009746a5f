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
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from ._validate import ParameterError
from .catalog import BEARINGS
from .params import (
    INTEGRATORS,
    MAX_SHAFT_SPEED_RPM,
    SCENE_LEVELS,
)

__all__ = [
    "validate_recipe",
    "expand_cases",
    "iter_cases",
    "case_count",
    "Case",
    "QUANTITIES",
    "DIRECTIONS",
    "CASE_COLUMNS",
]

#: cases per parquet file (and per worker task) when a recipe does not say: four 32-signal SIMD
#: blocks (measured: 64-signal chunks ran 3-14 % slower than 128 or 256 on two workers)
DEFAULT_CHUNK_SIZE = 128

QUANTITIES = ("displacement", "velocity", "acceleration")
DIRECTIONS = ("x", "y")
DEFECT_KINDS = ("waviness", "localized")
#: Keys of a [[conditions]] table that describe its defect.
_DEFECT_KEYS = frozenset(
    {"defect", "order", "amplitude_m", "length_m", "depth_m", "position_rad", "axis_drift_rad_s"}
)
CONDITION_SURFACES = {"healthy": None, "inner": "inner", "outer": "outer", "ball": "ball"}

#: Metadata columns of a generated signal, in order (units in the names).
CASE_COLUMNS = (
    "id",
    "index",
    "label",
    "condition",
    "bearing",
    "operating_point_id",
    "rpm",
    "shaft_frequency_hz",
    "radial_load_n",
    "radial_internal_clearance_m",
    "surface",
    "waviness_order",
    "waviness_amplitude_m",
    "defect_kind",
    "defect_length_m",
    "defect_depth_m",
    "defect_position_rad",
    "defect_axis_drift_rad_s",
    "seed",
    "scene",
    "ehl",
    "integrator",
    "step_s",
    "quantity",
    "body",
    "direction",
    "fs_hz",
    "duration_s",
    "snr_db",
    "background_db",
    "fault_snr_db",
    "noise_rms",
    "resonance_hz",
    "ftf_hz",
    "bpfo_hz",
    "bpfi_hz",
    "bsf_hz",
    "two_bsf_hz",
    "wpf_hz",
    "random_slip",
    "ball_jitter_rad",
    "fault_band_low_hz",
    "fault_band_high_hz",
    "chain",
)

_TOP_KEYS = {
    "name",
    "seed",
    "description",
    "bearings",
    "operating",
    "conditions",
    "model",
    "sensor",
    "chunk_size",
    "background",
}

#: Keys of [sensor] that describe the realistic measurement chain (docs/realism.md).
_CHAIN_SENSOR_KEYS = {
    "modes": (1, 12, ""),
    "mode_hz": (1.0, 1e6, "Hz"),
    "mode_damping": (1e-3, 0.99, ""),
    "mode_gain_db": (-60.0, 60.0, "dB"),
    "sensor_resonance_hz": (1.0, 1e6, "Hz"),
    "sensor_damping": (1e-3, 0.99, ""),
    "anti_alias": (0.05, 0.49, "x fs"),
    "anti_alias_order": (1, 16, ""),
    "adc_bits": (2, 32, "bits"),
    "adc_headroom_db": (-20.0, 60.0, "dB"),
}
#: Keys of [background]: levels in dB relative to the healthy bearing's RMS at the sensor.
_BACKGROUND_KEYS = {
    "shaft_db": (-80.0, 80.0, "dB"),
    "shaft_harmonics": (1, 20, ""),
    "shaft_decay_db": (0.0, 40.0, "dB per harmonic"),
    "line_hz": (1.0, 1000.0, "Hz"),
    "line_db": (-80.0, 80.0, "dB"),
    "other_bearing_db": (-80.0, 80.0, "dB"),
    "floor_db": (-80.0, 80.0, "dB"),
}
_INTEGER_KEYS = {"modes", "anti_alias_order", "adc_bits", "shaft_harmonics"}


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


def validate_recipe(recipe: dict) -> dict:
    """Check a recipe completely and return a normalised copy (raises ParameterError).

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
    unknown = set(r) - _TOP_KEYS
    if unknown:
        raise _fail(
            sorted(unknown)[0], r[sorted(unknown)[0]], f"unknown key; allowed: {sorted(_TOP_KEYS)}"
        )
    name = r.get("name")
    if not isinstance(name, str) or not name.replace("-", "").replace("_", "").isalnum():
        raise _fail("name", name, "a name of letters, digits, - and _ is required")
    seed = r.get("seed")
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise _fail("seed", seed, "a non-negative integer is required")
    chunk = r.setdefault("chunk_size", DEFAULT_CHUNK_SIZE)
    if isinstance(chunk, bool) or not isinstance(chunk, int) or not 1 <= chunk <= 10000:
        raise _fail("chunk_size", chunk, "an integer in [1, 10000] is required")
    bearings = r.get("bearings", ["6205"])
    if isinstance(bearings, str):
        bearings = [bearings]
    if not isinstance(bearings, list) or not bearings:
        raise _fail("bearings", bearings, "a non-empty list of catalog names is required")
    for b in bearings:
        if str(b).lower() not in BEARINGS:
            raise _fail("bearings", bearings, f"{b!r} is not in the catalog {sorted(BEARINGS)}")
    r["bearings"] = [str(b).lower() for b in bearings]
    op = r.get("operating")
    if not isinstance(op, dict) or "rpm" not in op or "load_n" not in op:
        raise _fail("operating", op, "a table with rpm and load_n is required")
    extra = set(op) - {"rpm", "load_n", "clearance_m", "random_slip", "ball_jitter_rad"}
    if extra:
        raise _fail(f"operating.{sorted(extra)[0]}", op[sorted(extra)[0]], "unknown key")
    r["operating"] = {
        "rpm": _range_or_grid(
            "operating.rpm",
            op["rpm"],
            low=0.0,
            high=MAX_SHAFT_SPEED_RPM,
            unit="rpm",
            low_inclusive=False,
        ),
        "load_n": _range_or_grid("operating.load_n", op["load_n"], low=0.0, high=1e6, unit="N"),
    }
    if "clearance_m" in op:
        r["operating"]["clearance_m"] = _range_or_grid(
            "operating.clearance_m", op["clearance_m"], low=-20e-6, high=200e-6, unit="m"
        )
    for key, high, unit in (("random_slip", 0.1, ""), ("ball_jitter_rad", 0.1, "rad")):
        if key in op:
            r["operating"][key] = _range_or_grid(
                f"operating.{key}", op[key], low=0.0, high=high, unit=unit
            )
    model = r.setdefault("model", {})
    if not isinstance(model, dict):
        raise _fail("model", model, "a table is required")
    extra = set(model) - {"scene", "ehl", "integrator", "step_s", "rtol"}
    if extra:
        raise _fail(f"model.{sorted(extra)[0]}", model[sorted(extra)[0]], "unknown key")
    model.setdefault("scene", "shaft+housing")
    model.setdefault("ehl", True)
    model.setdefault("integrator", "rk4")
    if model["scene"] not in SCENE_LEVELS:
        raise _fail("model.scene", model["scene"], f"allowed: {SCENE_LEVELS}")
    if not isinstance(model["ehl"], bool):
        raise _fail("model.ehl", model["ehl"], "true or false")
    if model["integrator"] not in INTEGRATORS:
        raise _fail("model.integrator", model["integrator"], f"allowed: {INTEGRATORS}")
    sensor = r.get("sensor")
    if not isinstance(sensor, dict):
        raise _fail("sensor", sensor, "a table is required")
    extra = set(sensor) - {
        "quantity",
        "direction",
        "body",
        "fs_hz",
        "duration_s",
        "settle_s",
        "snr_db",
        "background_db",
        "fault_snr_db",
        "noise_rms",
        "resonance_hz",
        "resonance_damping",
        *_CHAIN_SENSOR_KEYS,
        "other_bearing",
    }
    if extra:
        raise _fail(f"sensor.{sorted(extra)[0]}", sensor[sorted(extra)[0]], "unknown key")
    sensor.setdefault("quantity", "acceleration")
    sensor.setdefault("direction", "y")
    sensor.setdefault("body", "housing")
    sensor.setdefault("settle_s", 0.1)
    if sensor["quantity"] not in QUANTITIES:
        raise _fail("sensor.quantity", sensor["quantity"], f"allowed: {QUANTITIES}")
    if sensor["direction"] not in DIRECTIONS:
        raise _fail("sensor.direction", sensor["direction"], f"allowed: {DIRECTIONS}")
    if sensor["body"] not in ("housing", "shaft"):
        raise _fail("sensor.body", sensor["body"], "allowed: housing, shaft")
    fs = sensor.get("fs_hz")
    sensor["fs_hz"] = _range_or_grid("sensor.fs_hz", fs, low=100.0, high=1e7, unit="Hz")
    if "grid" not in sensor["fs_hz"]:
        raise _fail("sensor.fs_hz", fs, "a sample rate or a list of them is required")
    fs_min = min(sensor["fs_hz"]["grid"])
    for key, lo, hi in (
        ("duration_s", 1e-3, 3600.0),
        ("settle_s", 0.0, 3600.0),
    ):
        v = sensor.get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
            raise _fail(f"sensor.{key}", v, f"a number in [{lo:g}, {hi:g}] is required")
    given = [k for k in ("snr_db", "background_db", "noise_rms") if k in sensor]
    if len(given) > 1:
        raise _fail(
            f"sensor.{given[1]}",
            sensor[given[1]],
            f"give one of snr_db, background_db, noise_rms (also given: {given[0]})",
        )
    if "fault_snr_db" in sensor:
        if "background_db" not in sensor:
            raise _fail(
                "sensor.fault_snr_db",
                sensor["fault_snr_db"],
                "needs background_db too (the noise of the healthy cases)",
            )
        sensor["fault_snr_db"] = _range_or_grid(
            "sensor.fault_snr_db", sensor["fault_snr_db"], low=-60.0, high=200.0, unit="dB"
        )
    if "background_db" in sensor:
        sensor["background_db"] = _range_or_grid(
            "sensor.background_db", sensor["background_db"], low=-40.0, high=60.0, unit="dB"
        )
    if "snr_db" in sensor:
        sensor["snr_db"] = _range_or_grid(
            "sensor.snr_db", sensor["snr_db"], low=-40.0, high=200.0, unit="dB"
        )
    if "noise_rms" in sensor:
        v = sensor["noise_rms"]
        if isinstance(v, bool) or not isinstance(v, (int, float)) or v < 0:
            raise _fail("sensor.noise_rms", v, "a non-negative number (signal unit) is required")
    if "resonance_hz" in sensor:
        sensor["resonance_hz"] = _range_or_grid(
            "sensor.resonance_hz",
            sensor["resonance_hz"],
            low=1.0,
            high=0.45 * fs_min,
            unit="Hz (below 0.45 x the lowest sample rate)",
        )
        zeta = sensor.setdefault("resonance_damping", 0.05)
        if isinstance(zeta, bool) or not isinstance(zeta, (int, float)) or not 0 < zeta < 1:
            raise _fail("sensor.resonance_damping", zeta, "a number in (0, 1) is required")
    _validate_chain(r, fs_min)
    conditions = r.get("conditions")
    if not isinstance(conditions, list) or not conditions:
        raise _fail("conditions", conditions, "a non-empty list of [[conditions]] is required")
    labels = set()
    for i, c in enumerate(conditions):
        key = f"conditions[{i}]"
        if not isinstance(c, dict):
            raise _fail(key, c, "a table is required")
        extra = set(c) - {"label", "count", "surface", *_DEFECT_KEYS}
        if extra:
            raise _fail(f"{key}.{sorted(extra)[0]}", c[sorted(extra)[0]], "unknown key")
        label = c.get("label")
        if not isinstance(label, str) or not label:
            raise _fail(f"{key}.label", label, "a label is required")
        if label in labels:
            raise _fail(f"{key}.label", label, "labels must be unique")
        labels.add(label)
        count = c.get("count")
        if isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise _fail(f"{key}.count", count, "a positive integer is required")
        surface = c.get("surface", CONDITION_SURFACES.get(label))
        if surface is None:
            if _DEFECT_KEYS & set(c):
                raise _fail(
                    f"{key}.surface",
                    None,
                    "a defect condition needs a surface (inner, outer or ball)",
                )
            c["surface"] = None
            c["defect"] = None
            continue
        if surface not in ("inner", "outer", "ball"):
            raise _fail(f"{key}.surface", surface, "allowed: inner, outer, ball")
        c["surface"] = surface
        kind = c.setdefault("defect", "waviness")
        if kind not in DEFECT_KINDS:
            raise _fail(f"{key}.defect", kind, f"allowed: {DEFECT_KINDS}")
        wrong = {
            "waviness": {"length_m", "depth_m", "position_rad", "axis_drift_rad_s"},
            "localized": {"order", "amplitude_m"},
        }[kind] & set(c)
        if wrong:
            name = sorted(wrong)[0]
            raise _fail(f"{key}.{name}", c[name], f"not a key of a {kind} defect")
        if kind == "localized":
            c["length_m"] = _range_or_grid(
                f"{key}.length_m", c.get("length_m"), low=1e-6, high=0.05, unit="m"
            )
            c["depth_m"] = _range_or_grid(
                f"{key}.depth_m", c.get("depth_m"), low=0.0, high=1e-3, unit="m"
            )
            if "position_rad" in c:
                c["position_rad"] = _range_or_grid(
                    f"{key}.position_rad", c["position_rad"], low=-100.0, high=100.0, unit="rad"
                )
            if "axis_drift_rad_s" in c:
                if surface != "ball":
                    raise _fail(
                        f"{key}.axis_drift_rad_s", c["axis_drift_rad_s"], "only for ball defects"
                    )
                c["axis_drift_rad_s"] = _range_or_grid(
                    f"{key}.axis_drift_rad_s",
                    c["axis_drift_rad_s"],
                    low=0.0,
                    high=1e4,
                    unit="rad/s",
                )
            continue
        order = c.get("order")
        grid = _range_or_grid(f"{key}.order", order, low=1, high=500, unit="")
        if "range" in grid and any(v != int(v) for v in grid["range"]):
            raise _fail(f"{key}.order", order, "orders are integers")
        c["order"] = grid
        c["amplitude_m"] = _range_or_grid(
            f"{key}.amplitude_m", c.get("amplitude_m"), low=0.0, high=1e-4, unit="m"
        )
    return r


def _validate_chain(r: dict, fs_min: float) -> None:
    """The realistic measurement chain's keys of [sensor] and the [background] table."""
    sensor = r["sensor"]
    for key, (low, high, unit) in _CHAIN_SENSOR_KEYS.items():
        if key in sensor and key not in ("sensor_resonance_hz",):
            sensor[key] = _range_or_grid(
                f"sensor.{key}", sensor[key], low=low, high=high, unit=unit
            )
    if "sensor_resonance_hz" in sensor:
        sensor["sensor_resonance_hz"] = _range_or_grid(
            "sensor.sensor_resonance_hz",
            sensor["sensor_resonance_hz"],
            low=1.0,
            high=1e6,
            unit="Hz",
        )
    for key in _INTEGER_KEYS & set(sensor):
        if any(v != int(v) for v in sensor[key].get("grid", sensor[key].get("range", ()))):
            raise _fail(f"sensor.{key}", sensor[key], "integers are required")
    background = r.get("background")
    realistic = background is not None or "modes" in sensor
    if not realistic:
        for key in set(_CHAIN_SENSOR_KEYS) & set(sensor):
            raise _fail(f"sensor.{key}", sensor[key], "needs sensor.modes (the transfer path)")
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
            sensor["resonance_hz"],
            "give the structure as modes, mode_hz, mode_damping (resonance_hz is the older "
            "single-resonance sensor model)",
        )
    if "modes" in sensor and "mode_hz" not in sensor:
        raise _fail("sensor.mode_hz", None, "the modes' frequency range is required")
    if "other_bearing" in sensor and str(sensor["other_bearing"]).lower() not in BEARINGS:
        raise _fail("sensor.other_bearing", sensor["other_bearing"], f"not in {sorted(BEARINGS)}")
    if background is None:
        r["background"] = background = {}
    if not isinstance(background, dict):
        raise _fail("background", background, "a table is required")
    extra = set(background) - set(_BACKGROUND_KEYS) - {"other_bearing"}
    if extra:
        raise _fail(f"background.{sorted(extra)[0]}", background[sorted(extra)[0]], "unknown key")
    if "other_bearing" in background:
        name = str(background["other_bearing"]).lower()
        if name not in BEARINGS:
            raise _fail("background.other_bearing", name, f"not in {sorted(BEARINGS)}")
        background["other_bearing"] = name
    for key, (low, high, unit) in _BACKGROUND_KEYS.items():
        if key in background:
            background[key] = _range_or_grid(
                f"background.{key}", background[key], low=low, high=high, unit=unit
            )
    if "other_bearing_db" in background and "other_bearing" not in background:
        raise _fail("background.other_bearing", None, "other_bearing_db needs other_bearing")
    del fs_min  # mode and sensor frequencies above 0.45 fs are out of band and ignored


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


def _draw(spec: dict, rng: np.random.Generator, cycle: int, *, integer: bool = False):
    if "grid" in spec:
        v = spec["grid"][cycle % len(spec["grid"])]
    else:
        lo, hi = spec["range"]
        v = rng.integers(int(lo), int(hi) + 1) if integer else rng.uniform(lo, hi)
    return int(v) if integer else float(v)


def case_count(recipe: dict) -> int:
    """Number of cases (signals) of a validated recipe."""
    return sum(c["count"] for c in recipe["conditions"])


def expand_cases(recipe: dict) -> list[Case]:
    """All cases of a validated recipe, in index order (deterministic): ``list(iter_cases())``.

    Grid operating points: each condition cycles through the full grid (bearing x rpm x load
    x clearance) so every label sees every operating point; ranges draw one value per case.
    Defect grids (orders, amplitudes, sizes) cycle too, shifted by one value per pass through
    the operating grid, so that no defect value is tied to a single operating point.
    ``operating_point_id`` numbers the distinct (bearing, rpm, load, clearance) points so
    that splits can group by it.
    """
    return list(iter_cases(recipe))


def iter_cases(recipe: dict) -> Iterator[Case]:
    """The cases of :func:`expand_cases` one at a time, in index order.

    Each case is drawn from its own child of the recipe seed's ``SeedSequence`` (children
    spawned one by one are those of a single ``spawn(n)``), so a generator can start
    simulating the first chunk before the last case exists (drawing costs ~50 us per case).
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
            )
            index += 1
