"""The option texts of the model's commands: waviness, defects, geometry, form errors, WPF.

Each parser turns one option's text into a parameter object or numbers in SI units, and
refuses a text it cannot read with an error naming the option, the text and what it takes
(``cmtool simulate``, ``fidelity`` and ``frequencies`` use them).
"""

from __future__ import annotations

import argparse

from generators import BearingGeometry, LocalizedDefect, Waviness
from generators.form import MAX_FORM_WAVINESS

from .common import CliError

__all__ = [
    "parse_waviness",
    "parse_defect",
    "parse_geometry",
    "parse_form_waviness",
    "parse_wpf",
]


def _optional_float(value: str) -> float | None:
    return None if value == "random" else float(value)


def _parse_spec(
    spec: str, option: str, usage: str, keys: dict[str, tuple[str, object]], required: tuple
) -> tuple[str, dict[str, object]]:
    """Split ``surface:key=value:...`` (:func:`cmtool.io.split_spec`, errors as CliError)."""
    from ..io import split_spec

    return split_spec(spec, option, usage, keys, required, CliError)


def parse_waviness(spec: str) -> Waviness:
    """Parse ``surface:order=N:amplitude=A[:phase=P|random][:ball=J]`` into a Waviness.

    Parameters
    ----------
    spec : str
        The option's text.

    Returns
    -------
    Waviness

    Examples
    --------
    >>> parse_waviness("outer:order=9:amplitude=1e-6").order
    9
    """
    surface, fields = _parse_spec(
        spec,
        "--waviness",
        "surface:order=N:amplitude=A[:phase=P][:ball=J]",
        {
            "order": ("order", int),
            "amplitude": ("amplitude", float),
            "phase": ("phase", _optional_float),
            "ball": ("ball", int),
        },
        ("order", "amplitude"),
    )
    if surface == "ball" and "phase" not in fields:
        fields["phase"] = None  # each ball its own phase
    return Waviness(surface=surface, **fields)  # type: ignore[arg-type]


def parse_defect(spec: str) -> LocalizedDefect:
    """Parse ``surface:length=L:depth=H[:position=P|random][:ball=J]`` into a LocalizedDefect.

    Lengths in m, position in rad (outer race default -pi/2: 6 o'clock, the load-zone centre;
    inner race and ball default random); ball pits also take ``latitude=A|random`` [rad] and
    ``drift=W`` (spin-axis drift [rad/s]).

    Parameters
    ----------
    spec : str
        The option's text.

    Returns
    -------
    LocalizedDefect

    Examples
    --------
    >>> parse_defect("outer:length=0.18e-3:depth=20e-6").depth
    2e-05
    """
    surface, fields = _parse_spec(
        spec,
        "--defect",
        "surface:length=L:depth=H[:position=P|random][:ball=J][:latitude=A|random][:drift=W]",
        {
            "length": ("length", float),
            "depth": ("depth", float),
            "position": ("position", _optional_float),
            "ball": ("ball", int),
            "latitude": ("latitude", _optional_float),
            "drift": ("axis_drift", float),
        },
        ("length", "depth"),
    )
    if surface in ("inner", "ball") and "position" not in fields:
        fields["position"] = None
    return LocalizedDefect(surface=surface, **fields)  # type: ignore[arg-type]


def parse_geometry(spec: str) -> BearingGeometry:
    """``--geometry``: :func:`cmtool.io.geometry_from_spec` (a bearing not in the catalog).

    Parameters
    ----------
    spec : str
        The option's text.

    Returns
    -------
    BearingGeometry

    Examples
    --------
    >>> parse_geometry("6310:balls=8:ball_diameter=20.64e-3:pitch_diameter=77.5e-3").name
    '6310'
    """
    from ..io import geometry_from_spec

    return geometry_from_spec(spec, "--geometry")


def parse_form_waviness(spec: str) -> tuple[float, float, float]:
    """Parse ``INNER,OUTER,BALL`` form-error amplitudes [m] (each at least 0).

    Parameters
    ----------
    spec : str
        The option's text.

    Returns
    -------
    inner, outer, ball : float
        The amplitudes [m].

    Examples
    --------
    >>> parse_form_waviness("1e-7,0,5e-8")
    (1e-07, 0.0, 5e-08)
    """
    parts = [v.strip() for v in spec.split(",")]
    try:
        values = tuple(float(v) for v in parts)
    except ValueError:
        values = ()
    if len(values) != 3:
        raise argparse.ArgumentTypeError(
            f"--form-waviness {spec!r}: expected INNER,OUTER,BALL, three amplitudes [m]"
        )
    for name, value in zip(("INNER", "OUTER", "BALL"), values, strict=True):
        if not 0.0 <= value <= MAX_FORM_WAVINESS:
            raise argparse.ArgumentTypeError(
                f"--form-waviness {spec!r}: {name} = {value:g} m is outside the allowed range "
                f"[0, {MAX_FORM_WAVINESS:g}] m"
            )
    return values  # type: ignore[return-value]


def parse_wpf(spec: str) -> tuple[str, list[int]]:
    """``SURFACE:ORDERS`` of ``frequencies --wpf`` (``outer:9``, ``inner:8-10,17-19``).

    Parameters
    ----------
    spec : str
        The option's text.

    Returns
    -------
    surface : str
        ``outer``, ``inner`` or ``ball``.
    orders : list of int
        The waviness orders.
    """
    surface, _, orders = str(spec).partition(":")
    usage = "SURFACE:ORDERS, e.g. outer:9 or inner:8-10,17-19"
    if surface not in ("outer", "inner", "ball") or not orders:
        raise CliError(f"--wpf {spec!r}: expected {usage} (surface outer, inner or ball)")
    values: list[int] = []
    for item in orders.split(","):
        low, _, high = item.strip().partition("-")
        try:
            first, last = int(low), int(high or low)
        except ValueError:
            raise CliError(
                f"--wpf {spec!r}: {item.strip()!r} is not an order or a range of orders ({usage})"
            ) from None
        if not 1 <= first <= last <= 500:
            raise CliError(
                f"--wpf {spec!r}: orders {item.strip()!r} are outside the allowed range [1, 500]"
            )
        values += list(range(first, last + 1))
    return surface, values
