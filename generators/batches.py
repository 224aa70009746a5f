"""Batches of runs integrated together, one per SIMD lane (:mod:`generators._lanes`).

The dataset generator's path.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from . import _kernels as K
from . import _lanes
from ._validate import ParameterError, SimulationDivergedError
from .decimation import CHANNEL_COLUMNS, decimate_rows, differentiated, source_column
from .prepared import Plan, Prepared, diverged_error, plan_run


def lanes_supported(prep: Prepared) -> bool:
    """Whether :func:`simulate_lanes` can integrate this prepared run.

    RK4 in the ``shaft`` or ``shaft+housing`` scene with waviness only (no local defects, fewer
    than ``MAX_ROWS`` table rows, at most ``MAX_BALLS`` balls) and no contact-load record, in
    a film mode the lanes compile for the scene (``_lanes.LANE_PAIRS``: the film's entrainment,
    ``Rig.film_entrainment_factor``, in ``shaft+housing``).

    Parameters
    ----------
    prep : Prepared
        The prepared run (:func:`generators.prepared.prepare`).

    Returns
    -------
    bool
    """
    return (
        prep.settings.integrator == "rk4"
        and prep.scene_name in ("shaft", "shaft+housing")
        and not prep.settings.record_contact_loads
        and bool(np.all(prep.wav[:, K.W_SURFACE] <= K.SURF_BALL))
        and prep.wav.shape[0] < _lanes.MAX_ROWS
        and prep.geometry.ball_count <= _lanes.MAX_BALLS
        and (prep.scene_code, prep.film_mode) in _lanes.RK4
    )


def _row_padding(n_record: int) -> int:
    """Extra float64 per row of a lane block's output so rows start 64 bytes apart mod 4 KiB.

    The kernel writes one sample of every lane per record: with rows a multiple of 4 KiB
    long (25 600 samples) those stores all map to one set of the L1 cache, which holds 8
    lines, and evict each other (measured: the padded block integrates ~9 % faster).
    """
    return ((64 - (n_record * 8) % 4096) % 4096) // 8


def _block_buffer(
    workspace: list[np.ndarray] | None, index: int, width: int, n_record: int
) -> np.ndarray:
    """Output array (width, padded n_record) of lane block ``index``, from ``workspace``."""
    shape = (width, n_record + _row_padding(n_record))
    if workspace is None:
        return np.empty(shape)
    while len(workspace) <= index:
        workspace.append(np.empty((0, 0)))
    buffer = workspace[index]
    if buffer.shape[0] < width or buffer.shape[1] != shape[1]:
        buffer = workspace[index] = np.empty((max(width, _lanes.LANES), shape[1]))
    return buffer[:width]  # the first rows: C-contiguous, the kernel's array type


def simulate_lanes(
    preps: Sequence[Prepared], channel: str, *, workspace: list[np.ndarray] | None = None
) -> list[np.ndarray | SimulationDivergedError]:
    """One output channel of many prepared runs, integrated ``LANES`` at a time.

    The dataset generator's path: runs that share the scene, film switch, bearing (ball
    count), schedule and waviness layout are integrated together, one per SIMD lane
    (:mod:`generators._lanes`), by the same RK4 and dense output as :func:`simulate`, then
    decimated the same way. The result of a run does not depend on which runs share its
    block; it equals :func:`simulate`'s to rounding (the operations are grouped differently).

    Parameters
    ----------
    preps : sequence of Prepared
        Prepared runs (:func:`prepare`), each :func:`lanes_supported`.
    channel : str
        Output channel (``CHANNELS``), e.g. ``"housing_acceleration_y"``.
    workspace : list of ndarray, optional
        Output buffers kept from call to call (one per lane block, replaced when too small):
        the returned arrays are then views into them, valid until the next call with the
        same workspace. Writing into memory already touched saves ~9 % of the integration
        (page faults and cache misses of a fresh block); the dataset writer keeps one per
        worker thread.

    Returns
    -------
    list
        Per run, the channel at ``settings.fs`` [m, m/s or m/s^2], or the
        :class:`SimulationDivergedError` that says why the run diverged.
    """
    if channel not in CHANNEL_COLUMNS:
        raise ParameterError(f"channel = {channel!r} is not one of {sorted(CHANNEL_COLUMNS)}")
    groups: dict[tuple, list[tuple[int, Prepared, Plan]]] = {}
    for i, prep in enumerate(preps):
        if not lanes_supported(prep):
            raise ParameterError(
                f"preps[{i}] (scene {prep.scene_name}, integrator {prep.settings.integrator}) "
                "cannot run in lanes: RK4, shaft or shaft+housing scene, waviness only"
            )
        plan = plan_run(prep)
        layout = tuple(map(tuple, prep.wav[:, [K.W_SURFACE, K.W_BALL]].tolist()))
        key = (prep.scene_code, prep.film_mode, prep.geometry.ball_count, prep.p.size, layout, plan)
        groups.setdefault(key, []).append((i, prep, plan))
    results: list = [None] * len(preps)
    lanes = _lanes.LANES
    n_blocks = 0
    for (code, film_mode, *_), members in groups.items():
        kernel = _lanes.RK4[(code, film_mode)]
        plan = members[0][2]
        # an acceleration is recorded as its velocity and differentiated by the decimation
        which, column = source_column(channel, plan.oversample)
        derivative_dt = plan.record_dt if differentiated(channel, plan.oversample) else None
        for start in range(0, len(members), lanes):
            block = members[start : start + lanes]
            # no padding: a lane's bytes are the same in the vector body of the lane loops
            # and in their scalar remainder (tests_generators/test_lanes.py checks it)
            width = len(block)
            padded = [m[1] for m in block]
            y0 = np.stack([m.y0 for m in padded], axis=1)
            p = np.stack([m.p for m in padded], axis=1)
            wav = np.ascontiguousarray(np.stack([m.wav for m in padded], axis=2))
            out = _block_buffer(workspace, n_blocks, width, plan.n_record)
            n_blocks += 1
            status = np.empty(width, dtype=np.int64)
            t_status = np.empty(width)
            kernel(
                y0,
                p,
                wav,
                0.0,
                plan.dt,
                plan.n_steps,
                plan.record_start,
                plan.record_dt,
                plan.n_record,
                which,
                column,
                out,
                status,
                t_status,
            )
            records = out[:, : plan.n_record]
            if plan.oversample > 1:
                records = decimate_rows(records, plan.oversample, derivative_dt)
            records = records[:, plan.output_slice()]  # without the filter's lead and tail
            for b, (i, prep, _) in enumerate(block):
                if status[b] != K.STATUS_OK:
                    results[i] = diverged_error(prep, int(status[b]), float(t_status[b]))
                else:
                    results[i] = records[b]  # a row of the block's array
    return results
