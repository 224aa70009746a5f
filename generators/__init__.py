"""Bearing physics for cmtool: parameters, catalog, kinematics, contact mechanics, dynamic model.

All quantities are SI (m, kg, s, N, Pa, rad); frequencies are in Hz.
"""

from typing import TYPE_CHECKING

# the light modules (pure Python: parameters, catalog, kinematics) load with the package; the
# numerical ones (numpy, scipy, numba) on first use of one of their names, so that a command
# line's --help or a parameter check does not pay for the compiler (PEP 562)
from ._validate import (
    OperatingRangeWarning,
    ParameterError,
    SimulationDivergedError,
    StepShortenedWarning,
)
from .catalog import BEARINGS, bearing
from .form import form_waviness
from .kinematics import (
    BearingFrequencies,
    WavinessLine,
    characteristic_frequencies,
    waviness_passage_frequencies,
)
from .params import (
    CHANNELS,
    LUBRICANTS,
    STEEL_52100,
    BearingGeometry,
    LocalizedDefect,
    Lubricant,
    Material,
    OperatingCondition,
    Rig,
    Scene,
    SimulationSettings,
    Waviness,
    operating_range_warnings,
)

#: Public name -> the submodule that defines it (imported when the name is first used).
_LAZY = {
    **dict.fromkeys(
        (
            "ContactGeometry",
            "HertzContact",
            "contact_geometry",
            "contact_static_capacity",
            "entrainment_speed",
            "film_stiffness",
            "film_thickness",
            "hertz_contact",
            "load_deflection_constants",
            "series_constant",
            "squeeze_film_damping",
        ),
        "contact",
    ),
    **dict.fromkeys(("DefectPath", "defect_path", "sagitta"), "defects"),
    **dict.fromkeys(
        ("SimulationResult", "natural_frequencies", "resolve_scene", "simulate"), "model"
    ),
    **dict.fromkeys(("StaticSolution", "static_load_distribution"), "static"),
}

if TYPE_CHECKING:
    from .contact import (
        ContactGeometry,
        HertzContact,
        contact_geometry,
        contact_static_capacity,
        entrainment_speed,
        film_stiffness,
        film_thickness,
        hertz_contact,
        load_deflection_constants,
        series_constant,
        squeeze_film_damping,
    )
    from .defects import DefectPath, defect_path, sagitta
    from .model import SimulationResult, natural_frequencies, resolve_scene, simulate
    from .static import StaticSolution, static_load_distribution


def __getattr__(name: str):
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'generators' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "BEARINGS",
    "CHANNELS",
    "LUBRICANTS",
    "STEEL_52100",
    "BearingFrequencies",
    "BearingGeometry",
    "ContactGeometry",
    "DefectPath",
    "HertzContact",
    "LocalizedDefect",
    "Lubricant",
    "Material",
    "OperatingCondition",
    "OperatingRangeWarning",
    "ParameterError",
    "Rig",
    "Scene",
    "SimulationDivergedError",
    "SimulationResult",
    "SimulationSettings",
    "StaticSolution",
    "StepShortenedWarning",
    "Waviness",
    "WavinessLine",
    "bearing",
    "characteristic_frequencies",
    "contact_geometry",
    "contact_static_capacity",
    "defect_path",
    "entrainment_speed",
    "film_stiffness",
    "film_thickness",
    "form_waviness",
    "hertz_contact",
    "load_deflection_constants",
    "natural_frequencies",
    "operating_range_warnings",
    "resolve_scene",
    "sagitta",
    "series_constant",
    "simulate",
    "squeeze_film_damping",
    "static_load_distribution",
    "waviness_passage_frequencies",
]
