"""What the diagnosis benchmarks share: every signal of a dataset through ``diagnose_signal``."""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np


def diagnosed(model, frame, *, visible_only: bool = False) -> Iterator[tuple[str, object]]:
    """(true verdict, Diagnosis with the model) for each signal of a dataset frame.

    ``visible_only``: healthy signals and the faults at fault SNR >= ``MIN_FAULT_SNR_DB``
    (-10 dB, the floor under which ``cmtool train`` leaves faults out: nothing in them shows;
    :func:`cmtool.classifier.visible_faults`).
    """
    from cmtool.classifier import MIN_FAULT_SNR_DB, visible_faults
    from cmtool.diagnose import CANONICAL, diagnose_signal

    if visible_only:
        frame = frame[visible_faults(frame, MIN_FAULT_SNR_DB).to_numpy()]
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
