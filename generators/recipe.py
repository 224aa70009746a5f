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
from typing import Any

from ._validate import ParameterError
from .catalog import BEARINGS, bearing
from .content import fault_rates_outside_record, odd_ball_waviness
from .params import OperatingCondition, operating_range_warnings
from .recipe_schema import (
    CONDITION_SURFACES,
    DEFAULT_CHUNK_SIZE,
    DIRECTIONS,
    QUANTITIES,
    RECIPE_SCHEMA,
    TRAINING_CLASSIFIERS,
    Key,
    schema_table,
    unit_text,
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

_SECTIONS = ("operating", "model", "sensor", "background", "training")
#: Keys of [sensor] that describe the realistic measurement chain (docs/realism.md).
_CHAIN_SENSOR_KEYS = (
    "modes",
    "mode_hz",
    "mode_damping",
    "mode_gain_db",
    "sensor_resonance_hz",
    "sensor_damping",
    "sensor_noise_density",
    "electronic_floor_db",
    "anti_alias",
    "anti_alias_order",
    "adc_bits",
    "adc_headroom_db",
    "machine_velocity_mm_s",
)
#: Keys of a [[conditions]] table per defect kind.
_KIND_KEYS = {
    "waviness": ("order", "amplitude_m"),
    "localized": ("length_m", "depth_m", "position_rad", "axis_drift_rad_s"),
}
#: Keys of a [[conditions]] table that describe its defect.
_DEFECT_KEYS = frozenset({"defect", *_KIND_KEYS["waviness"], *_KIND_KEYS["localized"]})


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
            raise _fail(where, value, f"{what} in {interval}{unit_text(key)} is required")
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
    raise AssertionError(f"recipe key {where}: the schema's kind {key.kind!r} is not known")


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
            raise _fail(f"{where}{name}", None, f"required ({key.kind}{unit_text(key)})")


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
    entrainment = model.get("film_entrainment_factor")
    if entrainment and max(entrainment.get("grid", entrainment.get("range", ()))) > 0.0:
        if model["scene"] == "full" or not model["ehl"]:
            raise _fail(
                "model.film_entrainment_factor",
                recipe_value(entrainment),
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
    if "machine_velocity_mm_s" in sensor and sensor["body"] != "housing":
        raise _fail(
            "sensor.machine_velocity_mm_s",
            _shown(sensor["machine_velocity_mm_s"]),
            f"ISO 10816's overall velocity is a housing's; sensor.body = {sensor['body']!r}",
        )
    if "sensor_noise_density" in sensor:
        # an absolute noise needs records in absolute units: an acceleration in m/s^2
        why = ""
        if "machine_velocity_mm_s" not in sensor:
            why = "an absolute noise needs the record's absolute level, machine_velocity_mm_s"
        elif sensor["quantity"] != "acceleration":
            quantity = sensor["quantity"]
            why = f"a density in m/s^2/sqrt(Hz) is an acceleration's; quantity = {quantity!r}"
        if why:
            raise _fail("sensor.sensor_noise_density", _shown(sensor["sensor_noise_density"]), why)
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
