"""A folder of recordings described by MANIFEST.csv: read once, every row checked."""

import json
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
    ("separator", "decimal"), [(";", ","), ("\t", ","), (";", "."), (",", ".")]
)
def test_a_spreadsheets_manifest_reads_as_the_comma_separated_one(tmp_path, separator, decimal):
    """Where the decimal mark is a comma, spreadsheets save CSV with semicolons (or tabs)
    between columns and a byte-order mark first; the entries are those of the plain file."""
    rows = [
        {**GOOD, "shaft_rpm": 1797.5, "dataset": "CWRU", "time": "2026-01-01T08:00"},
        {**GOOD, "file": "b.npy", "sampling_rate_hz": 48828.125, "bearing": "6308"},
    ]
    plain = read_manifest(_folder(tmp_path, rows))
    text = pd.DataFrame(rows).to_csv(index=False, sep=separator, decimal=decimal)
    (tmp_path / "MANIFEST.csv").write_text(text, encoding="utf-8-sig")
    assert read_manifest(tmp_path) == plain
    assert [(e.fs_hz, e.rpm, e.bearing) for e in plain] == [
        (12000.0, 1797.5, "6205"),
        (48828.125, 1797.0, "6308"),
    ]


def test_a_windows_spreadsheets_manifest_names_its_files_in_its_own_encoding(tmp_path):
    name = "Lager_\u00d6l.npy"
    _folder(tmp_path, [{**GOOD, "file": name}])
    text = f"file;sampling_rate_hz;shaft_rpm\n{name};12000;1797,5\n"
    (tmp_path / "MANIFEST.csv").write_bytes(text.encode("cp1252"))
    (entry,) = read_manifest(tmp_path)
    assert entry.path == tmp_path / name and entry.rpm == 1797.5


def test_a_manifest_written_on_windows_finds_its_files_in_subfolders(tmp_path):
    """File and baseline names with backslashes, as a Windows spreadsheet writes them
    (pump3\\2026-01.npy): each was "no such file" on Linux and macOS."""
    (tmp_path / "pump3").mkdir()
    rng = np.random.default_rng(6)
    for name in ("2026-01.npy", "2026-02.npy"):
        np.save(tmp_path / "pump3" / name, rng.standard_normal(12000))
    rows = [
        {**GOOD, "file": "pump3\\2026-01.npy"},
        {**GOOD, "file": ".\\pump3\\2026-02.npy", "baseline": "pump3\\2026-01.npy"},
    ]
    pd.DataFrame(rows).to_csv(tmp_path / "MANIFEST.csv", index=False)
    first, second = read_manifest(tmp_path)
    assert (first.file, second.file) == ("pump3/2026-01.npy", "pump3/2026-02.npy")
    assert second.path == tmp_path / "pump3" / "2026-02.npy" and second.path.is_file()
    assert second.baseline == first.path
    rows[0]["file"] = "pump3\\2026-03.npy"  # missing either way: named, with its line
    pd.DataFrame(rows).to_csv(tmp_path / "MANIFEST.csv", index=False)
    with pytest.raises(FileNotFoundError, match=r"line 2 .*pump3/2026-03.npy: no such file"):
        read_manifest(tmp_path)


def test_a_manifests_rates_and_speeds_may_carry_their_units(tmp_path):
    """``12 kHz``, ``25,6 kS/s``, ``1797 rpm`` or a shaft's ``29.95 Hz`` are what people write
    in a spreadsheet; each was refused as "not a number"."""
    rows = [
        {**GOOD, "sampling_rate_hz": "12 kHz", "shaft_rpm": "1797 rpm"},
        {**GOOD, "file": "b.npy", "sampling_rate_hz": "25.6 kS/s", "shaft_rpm": "29.95 Hz"},
        {**GOOD, "file": "c.npy", "sampling_rate_hz": "48828.125 Hz", "shaft_rpm": "1500 r/min"},
    ]
    entries = read_manifest(_folder(tmp_path, rows))
    assert [e.fs_hz for e in entries] == pytest.approx([12000.0, 25600.0, 48828.125])
    assert [e.rpm for e in entries] == pytest.approx([1797.0, 1797.0, 1500.0])
    text = "file;sampling_rate_hz;shaft_rpm\na.npy;48,8 kHz;1797,5 RPM\n"
    (tmp_path / "MANIFEST.csv").write_text(text)
    (entry,) = read_manifest(tmp_path)
    assert (entry.fs_hz, entry.rpm) == pytest.approx((48800.0, 1797.5))


def test_a_folders_json_says_what_the_manifest_says_of_each_recording(tmp_path, capsys):
    """Machine, time and label were in verdicts.csv only: a JSON reader of a route had no
    way to tell which machine an object was, nor when it was measured."""
    rows = [
        {**GOOD, "machine": "pump 3", "time": "2026-01-15T08:00"},
        {**GOOD, "file": "b.npy", "shaft_rpm": "29.95 Hz", "fault_location": ""},
    ]
    assert main(["diagnose", str(_folder(tmp_path, rows)), "--json"]) == 0
    first, second = json.loads(capsys.readouterr().out)
    assert first["manifest"] == {
        "bearing": "6205",
        "rpm": 1797.0,
        "fs_hz": 12000.0,
        "machine": "pump 3",
        "manifest_label": "inner race",
        "time": "2026-01-15T08:00:00",
    }
    assert second["manifest"] == {"bearing": "6205", "rpm": pytest.approx(1797.0), "fs_hz": 12000.0}


def test_a_manifest_finds_its_files_regardless_of_case_where_only_one_matches(tmp_path):
    """Windows ignores case, so a manifest written there may name ``PUMP3\\A.NPY`` for
    pump3/a.npy; where two files differ only by case the name is not guessed."""
    (tmp_path / "pump3").mkdir()
    rng = np.random.default_rng(7)
    for name in ("a.npy", "twin.npy", "TWIN.npy"):
        np.save(tmp_path / "pump3" / name, rng.standard_normal(12000))
    pd.DataFrame([{**GOOD, "file": "PUMP3\\A.NPY"}]).to_csv(tmp_path / "MANIFEST.csv", index=False)
    (entry,) = read_manifest(tmp_path)
    assert entry.file == "pump3/a.npy" and entry.path == tmp_path / "pump3" / "a.npy"
    pd.DataFrame([{**GOOD, "file": "pump3/Twin.npy"}]).to_csv(
        tmp_path / "MANIFEST.csv", index=False
    )
    with pytest.raises(FileNotFoundError, match=r"line 2 .*Twin.npy: no such file"):
        read_manifest(tmp_path)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"shaft_rpm": "abc"}, r"line 2 \(a.npy\): shaft_rpm = 'abc' is not a number \[rpm\]"),
        (
            {"sampling_rate_hz": "12 kg"},
            r"sampling_rate_hz = '12 kg': the unit 'kg' is not one of hz",
        ),
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


def test_a_manifest_names_a_bearing_not_in_the_catalog_by_its_geometry(tmp_path, capsys):
    """bearing = NAME:balls=...: the same rates and verdicts as the catalog bearing it copies."""
    from cmtool.realism import recording_segments
    from generators import bearing

    g = bearing("6205")
    spec = f"copy:balls=9:ball_diameter={g.ball_diameter!r}:pitch_diameter={g.pitch_diameter!r}"
    rng = np.random.default_rng(5)
    x = rng.standard_normal(12000)
    x[::112] += 8.0  # impacts near BPFO at 1797 rpm, enough for a verdict to compare
    np.save(tmp_path / "a.npy", x)
    rows = [{**GOOD, "bearing": "6205"}, {**GOOD, "bearing": spec}]
    pd.DataFrame(rows).to_csv(tmp_path / "MANIFEST.csv", index=False)
    catalog, given = read_manifest(tmp_path, labelled=True)
    assert catalog.geometry is None and catalog.bearing_or_geometry == "6205"
    assert given.bearing == "copy" and given.geometry.ball_count == 9
    segments = recording_segments(tmp_path, 1.0)
    rates = ["bpfo_hz", "bpfi_hz", "two_bsf_hz", "ftf_hz"]
    np.testing.assert_allclose(segments[rates].iloc[1], segments[rates].iloc[0], rtol=1e-12)
    assert main(["diagnose", str(tmp_path), "--json"]) == 0
    by_name, by_geometry = json.loads(capsys.readouterr().out)
    assert by_geometry["candidates"] == by_name["candidates"]
    assert "given: 9 balls" in by_geometry["assumptions"]["bearing_geometry"]
    assert main(["bench", str(tmp_path), "--out", str(tmp_path / "bench")]) == 0
    results = pd.read_csv(tmp_path / "bench" / "results.csv")
    envelope = results[results["detector"] == "envelope"]
    assert list(envelope["bearing"]) == ["6205", "copy"]
    scores = ["verdict", "score_outer_race", "score_inner_race", "score_ball"]
    assert envelope[scores].iloc[0].tolist() == envelope[scores].iloc[1].tolist()
    pd.DataFrame([{**GOOD, "bearing": "copy:balls=9:ball_diameter=8e-3"}]).to_csv(
        tmp_path / "MANIFEST.csv", index=False
    )
    with pytest.raises(ValueError, match=r"line 2 \(a.npy\): bearing 'copy:.*pitch_diameter= is"):
        read_manifest(tmp_path)


def test_a_bench_plugin_with_a_geometry_parameter_gets_the_bearings_geometry(tmp_path):
    """A plug-in f(x, fs, rpm, bearing) gets the name; one that also takes ``geometry`` gets
    the BearingGeometry, so that a bearing given by its geometry can be computed on."""
    from cmtool.bench import run_bench

    seen: dict = {"names": [], "balls": []}

    def by_name(x, fs, rpm, bearing):
        seen["names"].append(bearing)
        return "healthy"

    def by_geometry(x, fs, rpm, bearing, geometry):
        seen["balls"].append((bearing, geometry.ball_count, geometry.pitch_diameter))
        return "healthy"

    spec = "pump:balls=8:ball_diameter=20.64e-3:pitch_diameter=77.5e-3"
    _folder(tmp_path, [{**GOOD, "bearing": spec}, {**GOOD, "bearing": "6205"}])
    run_bench(tmp_path, detectors={"name": by_name, "geometry": by_geometry})
    assert seen["names"] == ["pump", "6205"]
    assert seen["balls"] == [("pump", 8, 77.5e-3), ("6205", 9, pytest.approx(39.04e-3, rel=1e-4))]


@pytest.mark.realdata
def test_the_measured_recordings_folder_is_diagnosed_file_by_file(shared_data, tmp_path, capsys):
    """``cmtool diagnose ../shared/data``: every CWRU and MFPT layout read with its manifest's
    rate, speed, bearing and variable, in g (velocity in mm/s), none refused."""
    out = tmp_path / "reports"
    assert main(["diagnose", str(shared_data), "--report", str(out)]) == 0
    capsys.readouterr()
    table = pd.read_csv(out / "verdicts.csv")
    manifest = pd.read_csv(shared_data / "MANIFEST.csv")
    assert list(table["file"]) == list(manifest["file"])
    assert table["error"].isna().all() and table["verdict"].notna().all()
    assert set(table["bearing"]) == {"6205", "mfpt"}
    assert (table["velocity_unit"] == "mm/s").all()
    assert all(
        (out / Path(f).with_suffix("").as_posix().replace("/", "__")).is_dir()
        for f in table["file"]
    )
