"""The plain spectrum's lines at the fault rates, per class, in a simulated dataset.

The realism gauge (``cmtool realism``, docs/realism.md 7) tells simulated from measured signals
first by the plain (not demodulated) spectrum's line-to-floor ratios at BPFI and 2 x BSF and
their sidebands, as issue 17 found. This prints, per class, the median of those features
(``scale-free`` set) over the healthy signals and the faults at fault SNR >= -10 dB, and for
the inner-race pits their correlation with the labelled fault SNR and with the gain the chain
applied to the signature (``chain`` column's ``fault_gain``): simulated data only.

Run: .venv/bin/python benchmarks/plain_lines.py DATASET [DATASET ...]
"""

import json
import sys

import numpy as np
import pandas as pd

from cmtool.datasets import read_dataset
from features import FeatureExtractor

COLUMNS = (
    "spectrum_bpfi_h1_snr",
    "spectrum_bpfi_h1_sideband_snr",
    "spectrum_bpfi_max_snr",
    "spectrum_two_bsf_h2_sideband_snr",
    "spectrum_two_bsf_max_snr",
    "spectrum_bpfo_max_snr",
)
MIN_VISIBLE_DB = -10.0


def main(paths: list[str]) -> None:
    pd.set_option("display.width", 200)
    for path in paths:
        frame = read_dataset(path)
        frame = frame[(frame["label"] == "healthy") | (frame["fault_snr_db"] >= MIN_VISIBLE_DB)]
        extractor = FeatureExtractor(feature_set="scale-free", n_jobs=2).fit(frame)
        table = pd.DataFrame(extractor.transform(frame), columns=extractor.get_feature_names_out())
        table["label"] = frame["label"].to_numpy()
        print(f"{path}: {len(frame)} signals, medians [dB over the line's floor]")
        print(table.groupby("label")[list(COLUMNS)].median().round(1).to_string())
        inner = (table["label"] == "inner").to_numpy()
        if inner.sum() > 2:
            gains = [json.loads(c).get("fault_gain", 1.0) for c in frame["chain"]]
            gain_db = 20 * np.log10(np.maximum(np.asarray(gains, dtype=float), 1e-12))
            line = table["spectrum_bpfi_h1_snr"].to_numpy()[inner]
            snr = frame["fault_snr_db"].to_numpy()[inner]
            print(
                f"inner-race pits: spectrum_bpfi_h1_snr against the fault SNR r = "
                f"{np.corrcoef(line, snr)[0, 1]:.2f}, against the chain's gain r = "
                f"{np.corrcoef(line, gain_db[inner])[0, 1]:.2f}"
            )


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
