"""Envelope analysis on the measured recordings in ../shared/data (skipped when absent).

Nothing here is trained or tuned on these files. For each faulty record, the fault whose
fundamental stands highest above the local noise floor in the envelope spectrum (band chosen by
the kurtogram, at least MIN_BAND_FACTOR x the fastest fault rate wide) must be the labelled one.
"""

import pandas as pd
import pytest

import features as F
from cmtool.io import read_recording
from generators import bearing, characteristic_frequencies

pytestmark = pytest.mark.realdata

LABEL_TO_FAULT = {"inner": "bpfi", "outer": "bpfo", "ball": "two_bsf"}
BEARING = {"CWRU": "6205", "MFPT": "mfpt"}


def faulty_records(shared_data):
    manifest = pd.read_csv(shared_data / "MANIFEST.csv")
    return manifest[manifest.fault_location != "normal"]


@pytest.mark.parametrize("index", range(5))
def test_strongest_envelope_fault_is_the_labelled_one(shared_data, index):
    rows = faulty_records(shared_data)
    assert len(rows) == 5
    row = rows.iloc[index]
    x, meta = read_recording(shared_data / row.file)
    fs = float(row.sampling_rate_hz)
    shaft = float(row.shaft_rpm) / 60.0
    f = characteristic_frequencies(bearing(BEARING[row.dataset]), shaft)
    ctx = {"shaft": f.shaft, "ftf": f.ftf, "bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf}
    feats = F.extract_features(x, fs, fault_frequencies=ctx)
    snr = {k: feats[f"envelope_{k}_h1_snr"] for k in ("bpfo", "bpfi", "two_bsf")}
    assert max(snr, key=snr.get) == LABEL_TO_FAULT[row.fault_location], (row.file, snr)
