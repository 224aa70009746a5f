"""A folder of recordings described by MANIFEST.csv: read once, every row checked."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cmtool.cli import main
from cmtool.io import RecordingError
from cmtool.manifest import read_manifest


def _folder(tmp_path: Path, rows: list[dict]) -> Path:
    """Write rows as MANIFEST.csv and a 1 s noise .npy for every file they name."""
    rng = np.random.default_rng(4)
    for row in rows:
        name = row.get("file")
        if name and not (tmp_path / name).exists():
            np.save(tmp_path / name, rng.standard_normal(12000))
    pd.DataFrame(rows).to_csv(tmp_path / "MANIFEST.csv", index=False)
    return tmp_path


SMALL = Path(__file__).resolve().parents[2] / "datasets" / "small"
GOOD = {"file": "a.npy", "sampling_rate_hz": 12000, "shaft_rpm": 1797, "fault_location": "inner"}


def test_a_manifest_gives_each_recordings_rate_speed_bearing_rig_and_label(tmp_path):
    rows = [
        {**GOOD, "dataset": "CWRU", "channel_variable": "X105_DE_time"},
        {**GOOD, "file": "b.npy", "dataset": "MFPT", "fault_location": "Normal"},
        {**GOOD, "file": "c.npy", "bearing": "6308", "fault_location": "outer race"},
        {**GOOD, "file": "d.npy", "fault_location": "", "channel_variable": "bearing.gs"},
    ]
    entries = read_manifest(_folder(tmp_path, rows))
    assert [e.bearing for e in entries] == ["6205", "mfpt", "6308", "6205"]
    assert [e.rig for e in entries] == ["CWRU", "MFPT", "6308", "6205"]
    assert [e.label for e in entries] == ["inner race", "healthy", "outer race", "unknown"]
    assert [e.variable for e in entries] == ["X105_DE_time", None, None, None]
    assert entries[0].fs_hz == 12000.0 and entries[0].rpm == 1797.0
    assert entries[2].path == tmp_path / "c.npy"
    with pytest.raises(RecordingError, match=r"line 5 \(d.npy\): fault_location is empty"):
        read_manifest(tmp_path, labelled=True)  # a benchmark scores against the label


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"shaft_rpm": "abc"}, r"line 2 \(a.npy\): shaft_rpm = 'abc' is not a number \[rpm\]"),
        ({"shaft_rpm": -5}, r"shaft_rpm = -5 rpm is outside the allowed range \(0, 120000\]"),
        ({"sampling_rate_hz": 0}, r"sampling_rate_hz = 0 Hz is outside the allowed range"),
        ({"fault_location": "weird"}, r"fault_location = 'weird' is not one of ball, healthy"),
        ({"bearing": "7205"}, r"bearing = '7205' is not in the catalog \(6002"),
        ({"file": "gone.npy"}, r"line 2 \(gone.npy\): .*gone.npy: no such file"),
    ],
)
def test_a_row_that_cannot_be_used_is_an_error_naming_line_column_value_and_range(
    tmp_path, change, message
):
    _folder(tmp_path, [GOOD])
    row = {**GOOD, **change}
    pd.DataFrame([row]).to_csv(tmp_path / "MANIFEST.csv", index=False)
    with pytest.raises((RecordingError, FileNotFoundError), match=message):
        read_manifest(tmp_path)


def test_missing_columns_are_named_before_any_recording_is_read(tmp_path, capsys):
    folder = _folder(tmp_path, [{"file": "a.npy", "sampling_rate_hz": 12000}])
    with pytest.raises(RecordingError, match=r"no column 'shaft_rpm' \(required: file, sam"):
        read_manifest(folder)
    # both commands that read manifests say so in one line, no traceback
    for argv in (["bench", str(folder)], ["realism", str(SMALL), str(folder)]):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert "Traceback" not in err and err.count("\n") == 1, err
        assert "no column 'shaft_rpm'" in err
    (tmp_path / "MANIFEST.csv").write_text("")
    with pytest.raises(RecordingError, match="MANIFEST.csv: the file holds no data"):
        read_manifest(folder)
