"""What the diagnosis benchmarks share: every signal of a dataset through ``diagnose_signal``."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np


def diagnosed(model, frame, *, visible_only: bool = False) -> Iterator[tuple[str, object]]:
    """(true verdict, Diagnosis with the model) for each signal of a dataset frame.

    ``visible_only``: healthy signals and the faults at fault SNR >= -10 dB (the floor under
    which ``cmtool train`` leaves faults out: nothing in them shows).
    """
    from cmtool.diagnose import CANONICAL, diagnose_signal

    if visible_only and "fault_snr_db" in frame.columns:
        frame = frame[~(frame["fault_snr_db"] < -10.0)]
    for _, row in frame.iterrows():
        d = diagnose_signal(
            np.asarray(row["signal"]),
            row["fs_hz"],
            row["rpm"],
            row["bearing"],
            model=model,
            waviness=False,
        )
        yield CANONICAL[row["label"]], d
