"""The integration record's channels and their anti-alias decimation to the output rate."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy import signal as sp_signal

#: Output channel -> (record array: 0 state, 1 acceleration; column).
CHANNEL_COLUMNS = {
    "housing_displacement_x": (0, 2),
    "housing_displacement_y": (0, 3),
    "housing_velocity_x": (0, 6),
    "housing_velocity_y": (0, 7),
    "housing_acceleration_x": (1, 2),
    "housing_acceleration_y": (1, 3),
    "shaft_displacement_x": (0, 0),
    "shaft_displacement_y": (0, 1),
    "shaft_velocity_x": (0, 4),
    "shaft_velocity_y": (0, 5),
    "shaft_acceleration_x": (1, 0),
    "shaft_acceleration_y": (1, 1),
}


def decimate(
    out_state: np.ndarray, out_accel: np.ndarray, factor: int, channels: Sequence[str]
) -> dict[str, np.ndarray]:
    """Anti-alias filter and downsample the integration record to the output rate.

    All requested channels in one block (one gather, one polyphase filter call): each output
    channel is a contiguous row of the result.
    """
    records = (out_state, out_accel)
    block = np.empty((len(channels), out_state.shape[0]))
    for c, name in enumerate(channels):
        which, column = CHANNEL_COLUMNS[name]
        block[c] = records[which][:, column]
    if factor > 1:
        # polyphase FIR (Kaiser window), linear phase with its delay compensated
        block = sp_signal.resample_poly(block, 1, factor, axis=1, padtype="line")
    return {name: block[c] for c, name in enumerate(channels)}
