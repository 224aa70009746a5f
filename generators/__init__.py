"""Bearing physics for cmtool: parameters, catalog, kinematics, contact mechanics, dynamic model.

All quantities are SI (m, kg, s, N, Pa, rad); frequencies are in Hz.
"""

from ._validate import ParameterError, SimulationDivergedError
from .catalog import BEARINGS, bearing
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
from .kinematics import (
    BearingFrequencies,
    WavinessLine,
    characteristic_frequencies,
    waviness_passage_frequencies,
)
from .model import CHANNELS, SimulationResult, natural_frequencies, resolve_scene, simulate
from .params import (
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
)
from .static import StaticSolution, static_load_distribution

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
    "ParameterError",
    "Rig",
    "Scene",
    "SimulationDivergedError",
    "SimulationResult",
    "SimulationSettings",
    "StaticSolution",
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
    "hertz_contact",
    "load_deflection_constants",
    "natural_frequencies",
    "resolve_scene",
    "sagitta",
    "series_constant",
    "simulate",
    "squeeze_film_damping",
    "static_load_distribution",
    "waviness_passage_frequencies",
]
