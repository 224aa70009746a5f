"""The shaft speed and sample rate ``cmtool diagnose`` uses where a file holds its own.

A rate or speed given on the command line or in a manifest against the file's (the given
one is used, the difference said), and the speed from a tachometer channel (``--tacho``).
"""

from __future__ import annotations

import argparse

from generators.params import check_shaft_speed_rpm

from .common import CliError

__all__ = ["GIVEN_AGAINST_FILE", "TACHO_VARIATION_WARNING", "differs_from_file", "tacho_speed"]


#: A tachometer's speed varying more than this over a record (revolution-to-revolution
#: standard deviation over the mean) is warned of: a fault's lines smear over the range and
#: no order tracking is done.
TACHO_VARIATION_WARNING = 0.01


def tacho_speed(
    args: argparse.Namespace, x, fs: float, rpm_given: float | None
) -> tuple[float, str, list[str], object]:
    """The ``--tacho`` channel's shaft speed [rpm], description, warnings and TachoSpeed."""
    import numpy as np

    from features import shaft_rate_from_tacho

    from ..diagnose import SPEED_WARNING
    from ..io import read_recording

    pulses, _ = read_recording(args.recording, variable=args.variable, channel=args.tacho)
    if pulses.shape == x.shape and np.array_equal(pulses, x):
        raise CliError(
            f"--tacho {args.tacho} is the channel diagnosed; give the vibration's with --channel"
        )
    speed = shaft_rate_from_tacho(pulses, fs, args.pulses_per_rev)
    rpm = check_shaft_speed_rpm("the tacho's speed", 60.0 * speed.rate_hz)
    said = []
    if rpm_given is not None and abs(rpm_given / rpm - 1.0) > SPEED_WARNING:
        said.append(
            f"{'--rpm' if args.rpm is not None else 'the file'} {rpm_given:g} rpm is "
            f"{100 * abs(rpm_given / rpm - 1.0):.1f} % from the tacho's {rpm:.1f} rpm; using "
            "the tacho's"
        )
    if speed.variation > TACHO_VARIATION_WARNING and not args.order_track:
        said.append(
            f"the tacho's speed varies by {100 * speed.variation:.1f} % (revolution to "
            "revolution) over the record: the fault lines smear over that range; "
            "--order-track resamples the record to constant speed"
        )
    text = (
        f"tacho channel {args.tacho}: {speed.pulses} pulses at {args.pulses_per_rev} per "
        f"revolution, {rpm:.2f} rpm mean, {100 * speed.variation:.2f} % revolution-to-"
        "revolution spread"
    )
    return rpm, text, said, speed


#: A rate or speed given differs from the file's where they are this far apart, relative (a
#: CSV's time column written to microseconds gives a 1 s record's rate to about 1e-6).
GIVEN_AGAINST_FILE = 1e-4


def differs_from_file(
    meta: dict, fs: float | None, rpm: float | None, fs_name: str, rpm_name: str
) -> list[str]:
    """Warnings where a rate or speed given is not the one the file holds (the given is used)."""
    said = []
    for key, given, name, unit in (("fs_hz", fs, fs_name, "Hz"), ("rpm", rpm, rpm_name, "rpm")):
        held = meta.get(key)
        if (
            given is not None
            and held is not None
            and abs(held - given) > GIVEN_AGAINST_FILE * given
        ):
            said.append(
                f"{name} {given:g} {unit} differs from the file's {held:g} {unit}; using {name}"
            )
    return said
