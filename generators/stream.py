"""Long simulations in blocks: bounded memory, one block of output at a time.

:func:`simulate` holds the whole integration record (``oversample`` records per output sample,
twelve columns) and the decimated channels in memory: about 0.2 kB per output sample, so a
10-minute run at 51.2 kHz needs several GB. :func:`simulate_stream` integrates the same run
block after block, continuing the RK4 integration from the state the kernel returns, and
decimates each block with a margin of integration records on both sides that covers the
anti-alias filter (``resample_poly``'s half-length, ten records per decimation factor, and
five more for the accelerations' differentiator), so that the output is the in-memory one:
the same step grid, the same filter, and the same records beyond the record's ends
(``generators.prepared.Plan.lead`` and ``tail``): the samples agree to rounding, the first and last
too (measured within 1e-11 of the signal's RMS; ``tests/tests_generators/test_stream.py``).
Where the settling is shorter than the filter's reach (15 output samples), the first samples
are filtered from the line extension of what each call is given (a line through its first
and last records) and differ (no settling: 0.65 % of the RMS).

Only the fixed-step RK4 integrator streams (the adaptive DOPRI5 kernel ends a call after the
step that covers its last record, past the next block's first record time).
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np

from . import _integrators
from . import _kernels as K
from ._validate import ParameterError
from .decimation import DIFFERENTIATOR_HALF_LENGTH, decimate, record_columns
from .kinematics import BearingFrequencies
from .packing import Defect
from .params import CHANNELS, BearingGeometry, OperatingCondition, Rig, Scene, SimulationSettings
from .prepared import Prepared, diverged_error, params_record, plan_run, prepare

__all__ = ["SignalBlock", "SignalStream", "simulate_stream", "RECORD_BYTES_PER_SAMPLE"]

#: Integration-record columns held per record (states and accelerations) [float64].
_RECORD_COLUMNS = K.N_OUT_STATE + K.N_OUT_ACCEL

#: Bytes :func:`generators.simulate` holds per output sample and oversample factor (record).
RECORD_BYTES_PER_SAMPLE = 8 * _RECORD_COLUMNS


@dataclass(frozen=True)
class SignalBlock:
    """One block of a streamed simulation.

    Attributes
    ----------
    start : int
        Index of the block's first sample in the whole record.
    time : ndarray
        Sample times [s] (from 0 at the end of settling, as :attr:`SimulationResult.time`).
    signals : dict of str to ndarray
        The requested channels [m, m/s, m/s^2].
    contact_loads : ndarray or None, shape (n, 2, Z)
        Inner and outer contact load of every ball [N], when requested.
    """

    start: int
    time: np.ndarray
    signals: dict[str, np.ndarray]
    contact_loads: np.ndarray | None = None


class SignalStream:
    """A prepared simulation that yields its output in blocks (see :func:`simulate_stream`).

    Attributes
    ----------
    fs : float
        Output sample rate [Hz].
    n_samples : int
        Samples in the whole record.
    channels : tuple of str
        Channels of every block.
    frequencies : BearingFrequencies
        Characteristic frequencies of the run [Hz].
    parameters : dict
        The parameter record of the run (as :attr:`SimulationResult.parameters`).
    block_samples : int
        Samples per block (the last block may be shorter).
    """

    def __init__(self, prep: Prepared, block_samples: int) -> None:
        settings = prep.settings
        if settings.integrator != "rk4":
            raise ParameterError(
                f"integrator = {settings.integrator!r}: only 'rk4' streams in blocks "
                "(run DOPRI5 in memory with generators.simulate)"
            )
        if not isinstance(block_samples, int) or block_samples < 1:
            raise ParameterError(f"block_samples = {block_samples!r} must be an integer >= 1")
        self._prep = prep
        self.plan_run = plan_run(prep)
        self.fs = float(settings.fs)
        self.n_samples = self.plan_run.n_out
        self.channels: tuple[str, ...] = tuple(settings.channels or CHANNELS)
        self.block_samples = block_samples
        self.frequencies = prep.freqs or BearingFrequencies(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        plan = self.plan_run
        extra = {
            "integrator_stats": {"step_s": plan.dt, "steps": plan.n_steps}
            | ({"defect_step_s": plan.dt / plan.fine_steps} if plan.fine_steps > 1 else {}),
            "oversample": plan.oversample,
            "first_sample_time_s": plan.t_first,
            "max_static_ball_load_n": prep.max_ball_load,
            "streamed_block_samples": block_samples,
        }
        self.parameters = params_record(
            prep.geometry,
            prep.operating,
            prep.rig,
            prep.scene,
            prep.scene_name,
            prep.reason,
            settings,
            prep.defects,
            extra,
        )

    def peak_memory_bytes(self) -> int:
        """Memory the blocks hold at once (integration record, decimated block) [bytes].

        Returns
        -------
        int
        """
        q = self.plan_run.oversample
        margin = _margin_records(q)
        records = self.block_samples * q + 2 * margin
        loads = 2 * self._prep.geometry.ball_count * self._prep.settings.record_contact_loads
        return int(8 * records * (_RECORD_COLUMNS + loads + 2 * len(self.channels)))

    def __iter__(self) -> Iterator[SignalBlock]:
        return self._blocks()

    def _blocks(self) -> Iterator[SignalBlock]:
        prep, plan = self._prep, self.plan_run
        q, n_out, n_record = plan.oversample, plan.n_out, plan.n_record
        record_dt, dt, t_first = plan.record_dt, plan.dt, plan.record_start
        lead = plan.lead  # output sample i is record lead + i q
        margin = _margin_records(q)
        z = prep.geometry.ball_count
        record_loads = bool(prep.settings.record_contact_loads)
        y = prep.y0
        t = 0.0  # integrator time, on the step grid k * dt
        produced = 0  # integration records made so far
        carry_start = 0
        carry: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        for i0 in range(0, n_out, self.block_samples):
            i1 = min(n_out, i0 + self.block_samples)
            need = n_record if i1 == n_out else min(n_record, lead + i1 * q + margin)
            while need < n_record and _step_of(need, t_first, record_dt, dt) == _step_of(
                need - 1, t_first, record_dt, dt
            ):
                need += 1  # end the call on a step boundary: the next record starts a step
            if need > produced:
                state, accel, loads, t, y = self._integrate(
                    y, t, produced, need - produced, record_dt, dt, t_first, z, record_loads
                )
                produced = need
                if carry is not None:
                    state = np.concatenate([carry[0], state])
                    accel = np.concatenate([carry[1], accel])
                    if record_loads:
                        loads = np.concatenate([carry[2], loads])
            else:  # pragma: no cover - every block needs records past the previous one
                raise AssertionError("streamed block made no progress")
            signals = decimate(state, accel, q, self.channels, record_dt)
            # the block's first sample in the decimated chunk (which starts at carry_start)
            first = i0 + (lead - carry_start) // q
            block_signals = {name: v[first : first + i1 - i0].copy() for name, v in signals.items()}
            block_loads = None
            if record_loads:
                start = lead + i0 * q - carry_start
                block_loads = loads[start : start + (i1 - i0) * q : q].copy()
            yield SignalBlock(i0, np.arange(i0, i1) / self.fs, block_signals, block_loads)
            keep_from = max(0, lead + i1 * q - margin)
            carry = (
                state[keep_from - carry_start :],
                accel[keep_from - carry_start :],
                loads[keep_from - carry_start :] if record_loads else loads,
            )
            carry_start = keep_from

    def _integrate(self, y, t0, r0, count, record_dt, dt, t_first, z, record_loads):
        """Records ``r0 .. r0 + count - 1`` from state ``y`` at ``t0``: arrays, end time, state.

        The kernel returns at the end of the step that holds the last record; the caller ends
        blocks where the next record starts a new step, so the next call starts at or before
        its first record (the step grid ``k * dt`` continues unchanged).
        """
        prep = self._prep
        first_time = t_first + r0 * record_dt
        last_step = _step_of(r0 + count - 1, t_first, record_dt, dt)
        n_steps = last_step - round(t0 / dt) + 2  # an upper bound: the kernel stops at the end
        out_state = np.zeros((count, K.N_OUT_STATE))
        out_accel = np.zeros((count, K.N_OUT_ACCEL))
        out_loads = np.zeros((count if record_loads else 1, 2, z))
        status, t_end, y_end = _integrators._rk4(
            prep.scene_code,
            prep.film_mode,
            y,
            prep.p,
            prep.wav,
            t0,
            dt,
            n_steps,
            first_time,
            record_dt,
            count,
            out_state,
            out_accel,
            out_loads,
            record_loads,
            self.plan_run.fine_steps,
            record_columns(self.channels, self.plan_run.oversample),
        )
        if status != K.STATUS_OK:
            raise diverged_error(prep, int(status), float(t_end))
        return out_state, out_accel, out_loads, float(t_end), y_end


def _step_of(record: int, t_first: float, record_dt: float, dt: float) -> int:
    """The RK4 step (index on the grid ``k * dt``) in which the kernel writes a record."""
    return math.floor((t_first + record * record_dt) / dt + 1e-9)


def _margin_records(q: int) -> int:
    """Integration records on each side of a block that cover the anti-alias filter."""
    # resample_poly's half-length is 10 q, 15 q with the accelerations' differentiator
    # (DIFFERENTIATOR_HALF_LENGTH); a multiple of q keeps the phase
    return (12 + DIFFERENTIATOR_HALF_LENGTH) * q


def simulate_stream(
    bearing: BearingGeometry,
    operating: OperatingCondition,
    defects: Defect | Sequence[Defect] | None = None,
    *,
    scene: Scene | None = None,
    rig: Rig | None = None,
    settings: SimulationSettings | None = None,
    random_state: int | np.random.Generator | None = None,
    block_samples: int = 1 << 17,
) -> SignalStream:
    """Prepare a simulation whose output comes block by block (memory bounded by the block).

    The inputs are those of :func:`generators.simulate`; the run is the same (same static
    start, step and anti-alias filter), integrated in stretches of ``block_samples`` output
    samples, each continued from the state where the previous one stopped.

    Parameters
    ----------
    bearing, operating, defects, scene, rig, settings, random_state
        As :func:`generators.simulate` (the integrator must be ``rk4``).
    block_samples : int, optional
        Output samples per block (default 131 072: about 2.6 s at 51.2 kHz, ~60 MB held).

    Returns
    -------
    SignalStream
        Iterate it for :class:`SignalBlock` objects; its ``parameters`` are known before the
        first block (a file header can be written first).

    Raises
    ------
    ParameterError
        An input is out of range, or the integrator is not ``rk4``.
    SimulationDivergedError
        Raised by the iteration when a block diverges.

    Examples
    --------
    >>> from generators import OperatingCondition, SimulationSettings, bearing
    >>> from generators.stream import simulate_stream
    >>> stream = simulate_stream(bearing("6205"), OperatingCondition.from_rpm(1800, 500.0),
    ...                          settings=SimulationSettings(duration=0.05, settle_time=0.02,
    ...                                                      channels=("housing_velocity_y",)),
    ...                          block_samples=512)
    >>> [len(b.time) for b in stream]
    [512, 512, 256]
    """
    prep = prepare(
        bearing,
        operating,
        defects,
        scene=scene,
        rig=rig,
        settings=settings,
        random_state=random_state,
    )
    return SignalStream(prep, block_samples)
