"""cmtool: condition monitoring of rolling-element bearings.

The public API re-exports the physics (``generators``) and the features (``features``) that a
user needs, plus the application layer (I/O, plots, command line).
"""

from typing import TYPE_CHECKING

__version__ = "0.2.0"

from generators import (  # noqa: E402
    BEARINGS,
    BearingGeometry,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
)

if TYPE_CHECKING:
    from generators import SimulationResult, simulate


def __getattr__(name: str):
    # the model (numpy, scipy, numba) loads on first use: ``cmtool --help`` stays fast
    if name in ("SimulationResult", "simulate"):
        import generators

        return getattr(generators, name)
    raise AttributeError(f"module 'cmtool' has no attribute {name!r}")


__all__ = [
    "BEARINGS",
    "BearingGeometry",
    "OperatingCondition",
    "ParameterError",
    "Rig",
    "Scene",
    "SimulationDivergedError",
    "SimulationResult",
    "SimulationSettings",
    "Waviness",
    "__version__",
    "bearing",
    "characteristic_frequencies",
    "simulate",
]
