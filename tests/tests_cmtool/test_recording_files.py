"""Recording files as instruments and spreadsheets write them, and files that are not.

CSV recordings in the dialects instruments and spreadsheets write (cmtool.csv_layout), their
encodings and units; complex samples; cut or foreign files.

Each file is written from one known record; read back, it must give those samples (to the
digits written) and the rate its time column says, or be refused with the line or column
that stops it. Before cmtool.csv_layout, a decimal-comma column and a separator at each
line's end were read as other numbers without a word (a rate of -248 Hz from the second).
"""

import json

import numpy as np
import pytest
from impact_trains import ringing_impact_train

from cmtool.cli import main
from cmtool.io import RecordingError, read_recording

FS = 12000.0
N = 12000
X = np.random.default_rng(7).standard_normal(N)
T = np.arange(N) / FS


def _rows(sep: str, decimal: str, *, time: bool = True, end: str = "", digits: int = 6) -> str:
    def number(v: float) -> str:
        text = f"{v:.{digits}f}"
        return text.replace(".", ",") if decimal == "," else text

    return "\n".join(
        (f"{number(t)}{sep}{number(v)}" if time else number(v)) + end
        for t, v in zip(T, X, strict=True)
    )


DIALECTS = {
    "comma": "time,acc\n" + _rows(",", "."),
    "semicolon": "time;acc\n" + _rows(";", "."),
    "semicolon, decimal comma": "time;acc\n" + _rows(";", ","),
    "tab, decimal comma": "time\tacc\n" + _rows("\t", ","),
    "spaces": "time acc\n" + _rows(" ", "."),
    "separator at each line's end": "time,acc\n" + _rows(",", ".", end=","),
    "preamble and units row": "# logger 7\n# channel 1: drive end\ntime,acc\ns,g\n"
    + _rows(",", "."),
    "Windows line ends and a byte-order mark": "\ufefftime,acc\r\n"
    + _rows(",", ".").replace("\n", "\r\n"),
    "one column, decimal comma": "acc\n" + _rows("", ",", time=False),
    "one column, quoted decimal comma": "acc\n"
    + "\n".join(f'"{v:.6f}"'.replace(".", ",") for v in X),
}


@pytest.mark.parametrize("dialect", list(DIALECTS))
def test_each_dialect_reads_the_samples_and_the_rate(tmp_path, dialect):
    path = tmp_path / "rec.csv"
    path.write_text(DIALECTS[dialect], encoding="utf-8", newline="")
    x, meta = read_recording(path)
    np.testing.assert_allclose(x, X, rtol=0, atol=5e-7)  # six decimals written
    assert meta["variable"] == "acc" and meta["channels"] == 1
    if "one column" in dialect:
        assert "fs_hz" not in meta
    else:
        # the time column's 1 / 12000 s steps written as 0.000083 and 0.000084: the rate
        # from the span (within 1e-6 s over 1 s), not the median step (12048 Hz)
        assert meta["fs_hz"] == pytest.approx(FS, rel=1e-5)
    assert meta.get("unit") == ("g" if "units row" in dialect else None)
    assert "warnings" not in meta  # rounded steps are no gap


@pytest.mark.parametrize("suffix", [".txt", ".tsv"])
def test_a_loggers_text_export_is_read_as_a_csv_is(tmp_path, suffix):
    """A data logger's tab-separated export under .txt or .tsv: the same samples and rate as
    the same text under .csv. Before, both were an unknown format."""
    text = DIALECTS["tab, decimal comma"]
    (tmp_path / "rec.csv").write_text(text, encoding="utf-8", newline="")
    (tmp_path / f"rec{suffix}").write_text(text, encoding="utf-8", newline="")
    x, meta = read_recording(tmp_path / f"rec{suffix}")
    y, expected = read_recording(tmp_path / "rec.csv")
    np.testing.assert_array_equal(x, y)
    assert meta["fs_hz"] == expected["fs_hz"] and meta["variable"] == "acc"
    (tmp_path / "rec.dat").write_text(text)
    with pytest.raises(RecordingError, match=r"rec.dat: unknown format '.dat' \(mat, csv, txt"):
        read_recording(tmp_path / "rec.dat")


def test_a_csv_cut_within_its_last_line_is_refused_saying_where(tmp_path, capsys):
    """A copy stopped within a line leaves its last value missing (read as NaN). Before, the
    error said "contains 1 non-finite values", not where; now the sample and a likely cause."""
    lines = ["time,acc"] + [f"{float(t)!r},{float(x)!r}" for t, x in zip(T, X, strict=True)]
    text = "\n".join(lines)
    path = tmp_path / "cut.csv"
    path.write_text(text[: text.rindex(",") + 1])  # the last line keeps its time only
    assert main(["diagnose", str(path), "--rpm", "1797", "--bearing", "6205"]) == 2
    err = capsys.readouterr().err
    said = f"cut.csv contains 1 non-finite values (NaN or inf), the first at sample {N - 1} of"
    assert said in err and "(the last: a file cut short?)" in err
    from cmtool.diagnose import diagnose_signal

    middle = X.copy()
    middle[[10, 20]] = np.nan
    with pytest.raises(
        ValueError, match=rf"2 non-finite values .*, the first at sample 10 of {N}$"
    ):
        diagnose_signal(middle, FS, 1797.0, "6205")


def test_a_time_column_with_gaps_or_a_jump_back_is_read_at_its_rate_and_said(tmp_path, capsys):
    """A logger that dropped samples, or two files joined end to end: the rate of the regular
    steps (100 samples lost of 12000 gave 11900 Hz from the span, unsaid) and a warning
    naming the splice, in the diagnosis too. A clock's jitter (a tenth of a step) is none."""
    keep = np.r_[0:5000, 5100:N]
    cases = {
        "gap": (T[keep], X[keep], "jumps by 0.00841667 s after t = 0.416583 s (about 100 "),
        "joined": (np.r_[T[:6000], T[:6000]], X, "goes back by 0.499917 s after t = 0.499917"),
        "jitter": (T + np.random.default_rng(1).normal(0.0, 0.1 / FS, N), X, None),
    }
    for name, (times, x, said) in cases.items():
        path = tmp_path / f"{name}.csv"
        path.write_text(
            "time,acc\n" + "\n".join(f"{t:.9f},{v:.6f}" for t, v in zip(times, x, strict=True))
        )
        y, meta = read_recording(path)
        np.testing.assert_allclose(y, x, atol=5e-7)
        assert meta["fs_hz"] == pytest.approx(FS, rel=1e-4 if name == "jitter" else 1e-6)
        if said is None:
            assert "warnings" not in meta
            continue
        (warning,) = meta["warnings"]
        assert warning.startswith(f"{name}.csv: 'time' {said}"), warning
        argv = ["diagnose", str(path), "--rpm", "1797", "--bearing", "6205", "--json"]
        assert main(argv) == 0
        assert warning in json.loads(capsys.readouterr().out)["warnings"]


def test_a_decimal_comma_recording_gets_the_verdict_of_its_numbers(tmp_path, capsys):
    """The same record as .npy and as a spreadsheet's decimal-comma CSV: the same diagnosis."""

    from generators import bearing, characteristic_frequencies

    bpfo = characteristic_frequencies(bearing("6205"), 1797 / 60).bpfo
    rng = np.random.default_rng(5)
    x = ringing_impact_train(bpfo, FS, N, rng)
    x = np.round(x + 0.05 * rng.standard_normal(N), 6)
    np.save(tmp_path / "rec.npy", x)
    text = "Zeit [s];Beschleunigung [g]\n" + "\n".join(
        f"{t:.8f};{v:.6f}".replace(".", ",") for t, v in zip(T, x, strict=True)
    )
    (tmp_path / "rec.csv").write_text(text)
    said = []
    for name, extra in (("rec.npy", ["--fs", "12000"]), ("rec.csv", [])):
        argv = ["diagnose", str(tmp_path / name), "--rpm", "1797", "--bearing", "6205", "--json"]
        assert main(argv + extra) == 0
        said.append(capsys.readouterr().out)
    import json

    npy, csv = (json.loads(s) for s in said)
    assert npy["verdict"] == "outer race"
    assert csv["verdict"] == npy["verdict"] and csv["confidence"] == npy["confidence"]
    assert csv["assumptions"]["fs_hz"] == pytest.approx(FS, rel=1e-6)
    # the header's "[g]": velocities in mm/s, which a record of unknown unit does not get
    assert csv["assumptions"]["unit"] == "g" and npy["assumptions"].get("unit") is None


@pytest.mark.parametrize(
    ("name", "unit"),
    [
        ("acc [g]", "g"),
        ("AI0 (m/s^2)", "m/s^2"),
        ("a [m/s\u00b2]", "m/s^2"),
        ("v [mm/s]", "mm/s"),
        ("speed (in/s)", "in/s"),
        ("AI1 (V)", None),
        ("acc", None),
        ("g", None),
    ],
)
def test_a_columns_bracketed_unit_is_the_recordings(tmp_path, name, unit):
    path = tmp_path / "rec.csv"
    path.write_text(f"{name}\n" + "\n".join(f"{v:.6f}" for v in X))
    assert read_recording(path)[1].get("unit") == unit


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "acc\n" + "\n".join(f"{v:.6f}" for v in X[:50]) + "\nERROR\n" + "0.1\n" * 50,
            r"line 52 \('ERROR'\) interrupts the table",
        ),
        (
            "acc\n" + "\n".join(f"{v:.6f}" for v in X) + "\nEnd of data\n",
            r"column 'acc' holds text among its numbers \('End of data', row 12001",
        ),
        (
            "acc\n" + "\n".join(f"{v:.6f}" for v in X[:500]) + "\nacc\n" + "0.1\n" * 50,
            r"column 'acc' holds text among its numbers \('acc', row 501",
        ),
        ("a note\nanother\n", r"line 2 \('another'\) is no row of numbers"),
        ("\n\n", "the file holds no data"),
    ],
    ids=["text inside", "footer", "second header", "no numbers", "blank"],
)
def test_what_is_no_table_is_refused_by_its_line(tmp_path, text, message):
    path = tmp_path / "rec.csv"
    path.write_text(text)
    with pytest.raises(RecordingError, match=message):
        read_recording(path)


def test_a_windows_spreadsheets_encoding_is_read(tmp_path):
    """Windows-1252 text (a German spreadsheet's header) is no UTF-8: its table and its
    unit are read all the same."""
    path = tmp_path / "rec.csv"
    text = "Zeit [s];Beschleunigung [m/s\u00b2]\n" + _rows(";", ",")
    path.write_bytes(text.encode("cp1252"))
    x, meta = read_recording(path)
    np.testing.assert_allclose(x, X, rtol=0, atol=5e-7)
    assert meta["unit"] == "m/s^2" and meta["variable"] == "Beschleunigung [m/s\u00b2]"
    assert meta["fs_hz"] == pytest.approx(FS, rel=1e-5)


def test_a_headerless_file_of_integer_pairs_stays_two_columns(tmp_path):
    """Without a header, "125,-3" is two columns of counts (a logger's integers), not one
    number with a decimal comma."""
    counts = np.round(X * 1000).astype(int)
    path = tmp_path / "counts.csv"
    path.write_text("\n".join(f"{a},{a // 2}" for a in counts))
    x, meta = read_recording(path)
    assert meta["channels"] == 2 and meta["variable"] == "column 0"
    np.testing.assert_array_equal(x, counts)
    assert np.array_equal(read_recording(path, channel=1)[0], counts // 2)


def test_complex_samples_are_refused_not_cut_to_their_real_part(tmp_path):
    np.save(tmp_path / "iq.npy", X + 1j * X)
    with pytest.raises(RecordingError, match=r"iq.npy: the samples are complex numbers"):
        read_recording(tmp_path / "iq.npy")


@pytest.mark.parametrize("suffix", [".npz", ".npy", ".parquet"])
def test_a_cut_or_foreign_file_is_refused_by_name(tmp_path, suffix):
    """Half of a file (a copy that stopped), or another file under the suffix: a
    RecordingError naming the file, not another library's traceback (a cut .npz raised
    zipfile.BadZipFile)."""
    import pandas as pd

    whole = tmp_path / f"whole{suffix}"
    if suffix == ".npz":
        np.savez(whole, a=X)
    elif suffix == ".npy":
        np.save(whole, X)
    else:
        pd.DataFrame({"a": X}).to_parquet(whole)
    data = whole.read_bytes()
    for name, content in (("cut", data[: len(data) // 2]), ("foreign", b"PK\x03\x04not a file")):
        path = tmp_path / f"{name}{suffix}"
        path.write_bytes(content)
        with pytest.raises(RecordingError, match=rf"{name}{suffix}: cannot be read as a"):
            read_recording(path)


def test_a_dataset_file_is_not_read_as_a_recording():
    """A dataset part's numeric columns are its signals' metadata (rpm, load, ...): read as a
    recording it gave 'only 8 samples' (the rpm column)."""
    from pathlib import Path

    part = (
        Path(__file__).resolve().parents[2] / "datasets" / "small" / "data" / "part-00000.parquet"
    )
    with pytest.raises(RecordingError, match=r"a cmtool dataset's file \(8 signals in its"):
        read_recording(part)


def test_a_tachometers_pulses_are_not_diagnosed_as_a_vibration(tmp_path, capsys):
    """A two-level record is a tachometer's or a digital channel's: refused by name. The
    share of samples near the two ends is what a distribution puts there: about 6 % for a
    Gaussian (within 0.47 sigma of the 1st and 99th percentiles), 41 % for a sine (the
    arcsine law: arccos(0.8) / pi at each end), all of a square wave's."""
    from cmtool.cli import main
    from cmtool.diagnose import diagnose_signal
    from cmtool.quality import PULSE_SHARE, two_level_share

    rng = np.random.default_rng(0)
    t = np.arange(120000) / FS
    assert two_level_share(rng.standard_normal(t.size)) == pytest.approx(0.057, abs=0.005)
    assert two_level_share(np.sin(2 * np.pi * 107.3 * t)) == pytest.approx(0.41, abs=0.01)
    tacho = np.where((29.9 * t) % 1.0 < 0.05, 5.0, 0.0) + 0.05 * rng.standard_normal(t.size)
    assert two_level_share(tacho) >= PULSE_SHARE
    with pytest.raises(ValueError, match=r"signal takes two levels only \(100% of its samples"):
        diagnose_signal(tacho, FS, 1797.0, "6205")
    path = tmp_path / "rec.csv"
    path.write_text(
        "key,acc\n"
        + "\n".join(f"{a:.4f},{b:.6f}" for a, b in zip(tacho, X.repeat(10), strict=True))
    )
    argv = ["diagnose", str(path), "--fs", "12000", "--rpm", "1797", "--bearing", "6205"]
    assert main(argv) == 2
    assert "takes two levels only" in capsys.readouterr().err
    assert main([*argv, "--channel", "1", "--tacho", "0"]) == 0
    assert "from the tacho channel 0" in capsys.readouterr().out


def test_a_cut_wav_file_is_said_to_be_cut_in_the_diagnosis(tmp_path, capsys):
    """scipy reads a WAV file cut short as far as it goes, with a warning of its own; the
    warning goes into the diagnosis's warnings (JSON, report) with the file's name."""
    import json

    from scipy.io import wavfile

    from cmtool.cli import main

    wavfile.write(tmp_path / "whole.wav", 12000, np.tile(X, 2).astype(np.float32))
    data = (tmp_path / "whole.wav").read_bytes()
    (tmp_path / "cut.wav").write_bytes(data[: len(data) // 2])
    x, meta = read_recording(tmp_path / "cut.wav")
    assert 0.9 * N < x.size < 1.1 * N  # half of 2 N samples, less the header
    assert meta["warnings"][0].startswith("cut.wav: Reached EOF prematurely")
    assert "warnings" not in read_recording(tmp_path / "whole.wav")[1]
    argv = ["diagnose", str(tmp_path / "cut.wav"), "--rpm", "1797", "--bearing", "6205"]
    assert main([*argv, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["warnings"][0].startswith("cut.wav: Reached EOF")


def _save_mat_v73(path, variables: dict) -> None:
    """Write ``variables`` as MATLAB's ``save -v7.3`` does: an HDF5 file behind a 512-byte
    header (text, then version 0x0200 and the "IM" byte-order mark at bytes 124-127), each
    array stored in MATLAB's column-major order (an N x 1 column as 1 x N) with its
    ``MATLAB_class``, each struct a group of its fields, a cell a dataset of references."""
    import h5py

    def put(group, name, value):
        if isinstance(value, dict):
            sub = group.create_group(name)
            sub.attrs["MATLAB_class"] = np.bytes_("struct")
            for key, field in value.items():
                put(sub, key, field)
        elif isinstance(value, str):
            data = np.array([[ord(c)] for c in value], dtype=np.uint16)  # 1 x n char
            group.create_dataset(name, data=data).attrs["MATLAB_class"] = np.bytes_("char")
        elif isinstance(value, list):  # a 1 x n cell
            refs = group.file.require_group("#refs#")
            handles = []
            for i, item in enumerate(value):
                put(refs, f"{name}_{i}", item)
                handles.append(refs[f"{name}_{i}"].ref)
            data = np.array([[h] for h in handles], dtype=h5py.ref_dtype)
            group.create_dataset(name, data=data).attrs["MATLAB_class"] = np.bytes_("cell")
        else:
            array = np.atleast_2d(np.asarray(value, dtype=float))
            group.create_dataset(name, data=array.T).attrs["MATLAB_class"] = np.bytes_("double")

    with h5py.File(path, "w", userblock_size=512) as file:
        for name, value in variables.items():
            put(file, name, value)
    text = b"MATLAB 7.3 MAT-file, Platform: GLNXA64, Created on: Mon Nov 30 03:00:00 2026 HDF5 "
    header = text.ljust(116) + b"\x00" * 8 + b"\x00\x02" + b"IM"
    with open(path, "r+b") as file:
        file.write(header)


def _column(values: np.ndarray) -> np.ndarray:
    return np.asarray(values, dtype=float).reshape(-1, 1)


CWRU_LAYOUT = {
    "X105_DE_time": _column(X),
    "X105_FE_time": _column(0.5 * X),
    "X105RPM": np.array([[1797.0]]),
}
MFPT_LAYOUT = {
    "bearing": {"gs": _column(X), "sr": [[48828.0]], "rate": [[25.0]], "load": [[270.0]]}
}


@pytest.mark.parametrize("layout", [CWRU_LAYOUT, MFPT_LAYOUT], ids=["cwru", "mfpt"])
def test_a_matlab_v73_file_reads_as_its_v7_copy_does(tmp_path, layout):
    """MATLAB's HDF5 files (save -v7.3, the default for large files) were refused with
    "save with -v7"; now each CWRU and MFPT layout gives the samples and what the file says
    (rate, speed, bearing, unit, variable) exactly as the same variables saved as v7 do."""
    from scipy import io as sio

    v7, v73 = tmp_path / "v7.mat", tmp_path / "v73.mat"
    sio.savemat(v7, layout)
    _save_mat_v73(v73, layout)
    with pytest.raises(NotImplementedError):  # scipy's own reader refuses it
        sio.loadmat(v73)
    x7, meta7 = read_recording(v7)
    x73, meta73 = read_recording(v73)
    np.testing.assert_array_equal(x73, x7)
    np.testing.assert_array_equal(x73, X)
    assert {**meta73, "file": v7.name} == {**meta7, "file": v7.name} and meta73["unit"] == "g"
    assert meta73["bearing"] == ("6205" if "X105RPM" in layout else "mfpt")
    if "bearing" in layout:
        assert meta73["fs_hz"] == 48828.0 and meta73["rpm"] == 1500.0
    else:
        assert meta73["rpm"] == 1797.0 and meta73["variable"] == "X105_DE_time"
        fan, _ = read_recording(v73, variable="X105_FE_time")
        np.testing.assert_array_equal(fan, 0.5 * X)


def test_a_matlab_v73_files_channels_text_and_cells(tmp_path):
    """A samples x channels matrix keeps its channels as a v7 file's do; text reads as text
    and a cell as its elements (scipy's loadmat of a v7 file gives the same)."""
    from cmtool.matlab_hdf5 import MatStruct, read_mat_v73

    both = np.column_stack([X, 2 * X])
    path = tmp_path / "logger.mat"
    _save_mat_v73(path, {"data": both, "note": "pump 3, DE", "runs": [[1.0, 2.0, 3.0], both]})
    second, meta = read_recording(path, variable="data", channel=1)
    np.testing.assert_array_equal(second, 2 * X)
    assert meta["channels"] == 2
    variables = read_mat_v73(path)
    assert set(variables) == {"data", "note", "runs"}  # MATLAB's #refs# group left out
    assert variables["note"] == "pump 3, DE"
    np.testing.assert_array_equal(variables["runs"][0], [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(variables["runs"][1], both)
    _save_mat_v73(path, {"s": {"a": [[1.0]], "b": "x"}})
    struct = read_mat_v73(path)["s"]
    assert isinstance(struct, MatStruct) and struct._fieldnames == ["a", "b"]
    assert struct.a == 1.0 and struct.b == "x"


def test_a_matlab_v73_file_cut_short_is_refused_by_name(tmp_path, capsys):
    path = tmp_path / "cut.mat"
    _save_mat_v73(path, CWRU_LAYOUT)
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    with pytest.raises(RecordingError, match=r"cut\.mat: not a readable MATLAB v7\.3 \(HDF5\)"):
        read_recording(path)
    assert main(["diagnose", str(path), "--fs", "12000"]) == 2
    assert "not a readable MATLAB v7.3" in capsys.readouterr().err


def test_the_measured_recordings_read_the_same_from_their_v73_copies(shared_data, tmp_path):
    """Each ../shared/data MAT-file (CWRU and MFPT layouts, as their owners publish them)
    written again as MATLAB v7.3 gives the same samples and the same rate, speed, bearing
    and unit."""
    from scipy import io as sio

    files = sorted(shared_data.rglob("*.mat"))
    assert files
    for path in files:
        variables = {}
        for name, value in sio.loadmat(path).items():
            if name.startswith("__"):
                continue
            if value.dtype.names:  # a 1 x 1 struct (MFPT's bearing)
                value = {field: value[field][0, 0] for field in value.dtype.names}
            variables[name] = value
        copy = tmp_path / path.name
        _save_mat_v73(copy, variables)
        x, meta = read_recording(path)
        x73, meta73 = read_recording(copy)
        np.testing.assert_array_equal(x73, x)
        assert {**meta73, "file": path.name} == {**meta, "file": path.name}, path.name


def test_a_record_that_drifts_is_said_to_swamp_its_velocity_figures():
    """An accelerometer settling after power-on, a drift or a step: most of the record's
    variance below the overall band's start (10 Hz here), where a machine's acceleration
    holds little; integrated, it swamps the velocity figures (ISO 10816 overall 0.3 -> 14
    mm/s), so it is said. Noise, a strong 1x line and a slow shaft's 1x are not."""
    from cmtool.diagnose import diagnose_signal
    from cmtool.quality import DRIFT_SHARE, check_drift, low_frequency_share

    n = 2 * N
    t = np.arange(n) / FS
    noise = 0.05 * np.random.default_rng(9).standard_normal(n)
    drifting = {
        "settling": 3.0 * np.exp(-t / 0.1),
        "drift": 0.5 * t,
        "step": np.where(t > 1.0, 0.5, 0.0),
    }
    plain = diagnose_signal(noise, FS, 1797.0, "6205", unit="g", waviness=False)
    assert not any("variance lies below" in w for w in plain.warnings)
    for name, added in drifting.items():
        d = diagnose_signal(noise + added, FS, 1797.0, "6205", unit="g", waviness=False)
        (said,) = [w for w in d.warnings if "variance lies below" in w]
        assert said.split(" % of")[0].isdigit() and "below 10 Hz" in said, name
        assert d.overall_velocity["rms_mm_s"] > 5 * plain.overall_velocity["rms_mm_s"], name
    shaft = noise + 2.0 * np.sin(2 * np.pi * 29.95 * t) + 0.5 * np.sin(2 * np.pi * 59.9 * t)
    d = diagnose_signal(shaft, FS, 1797.0, "6205", unit="g", waviness=False)
    assert not any("variance lies below" in w for w in d.warnings)
    # a 60 rpm shaft's 1 Hz line: below the 2 Hz band start, not below half the shaft rate
    slow = noise + 2.0 * np.sin(2 * np.pi * 1.0 * t)
    assert low_frequency_share(slow, FS, 2.0) > DRIFT_SHARE
    assert check_drift(slow, FS, 0.5) == []
    assert low_frequency_share(noise[:100], FS, 10.0) == 0.0  # no bin below 10 Hz


def test_no_measured_recording_is_said_to_drift(shared_data):
    """The CWRU and MFPT recordings: their share of variance below 10 Hz is far under the
    DRIFT_SHARE set from the physics (reported here, not tuned on)."""
    import pandas as pd

    from cmtool.quality import DRIFT_SHARE, low_frequency_share

    for file, fs in pd.read_csv(shared_data / "MANIFEST.csv")[["file", "sampling_rate_hz"]].values:
        x, _ = read_recording(shared_data / file)
        assert low_frequency_share(x, fs, 10.0) < DRIFT_SHARE / 10, file


def test_a_row_index_column_is_neither_a_channel_nor_a_time_axis(tmp_path, capsys):
    """pandas' to_csv writes the row index first (an unnamed column 0, 1, 2, ...), a logger
    a sample number: it was read as a time axis of 1 Hz ("--fs 12000 Hz differs from the
    file's 1 Hz", and without --fs a rate of 1 Hz). It is no channel and gives no rate."""
    import pandas as pd

    frames = {
        "index.csv": pd.DataFrame({"acc": X}),
        "sample.csv": pd.DataFrame({"sample": np.arange(1, N + 1), "acc": X}),
    }
    for name, frame in frames.items():
        path = tmp_path / name
        frame.to_csv(path, index=name == "index.csv")
        x, meta = read_recording(path)
        np.testing.assert_array_equal(x, X)
        assert "fs_hz" not in meta and meta["channels"] == 1 and meta["variable"] == "acc"
        argv = ["diagnose", str(path), "--rpm", "1797", "--bearing", "6205", "--json"]
        assert main(argv) == 2
        assert "holds no sample rate; give --fs" in capsys.readouterr().err
        assert main([*argv, "--fs", "12000"]) == 0
        assert json.loads(capsys.readouterr().out)["warnings"] == []
    # a first column rising in steps of a sample period stays the time axis
    pd.DataFrame({"": T, "acc": X}).to_csv(tmp_path / "time.csv", index=False)
    assert read_recording(tmp_path / "time.csv")[1]["fs_hz"] == pytest.approx(FS, rel=1e-9)


@pytest.mark.parametrize(
    ("header", "units", "size"),
    [
        ("time [ms],acc", None, 1e-3),
        ("t (ms),acc", None, 1e-3),
        ("time_ms,acc", None, 1e-3),
        ("Time [us],acc", None, 1e-6),
        ("time,acc", "ms,g", 1e-3),
        ("Time (s),acc", None, 1.0),
    ],
)
def test_a_time_column_in_milliseconds_gives_the_rate_in_hertz(tmp_path, header, units, size):
    """A time column written in ms or us (its bracketed unit, a suffix, the units row) was
    read as seconds: a rate of 12 Hz for 12 kHz. Its unit is now taken into account."""
    path = tmp_path / "rec.csv"
    rows = "\n".join(f"{t / size:.9g},{v:.6f}" for t, v in zip(T, X, strict=True))
    path.write_text(header + "\n" + (units + "\n" if units else "") + rows)
    x, meta = read_recording(path)
    np.testing.assert_allclose(x, X, atol=5e-7)
    assert meta["fs_hz"] == pytest.approx(FS, rel=1e-6)


def test_a_files_scalar_rate_and_speed_are_its_own(tmp_path, capsys):
    """MATLAB's `save rec.mat x fs` and numpy's `np.savez(..., x=x, fs=fs)`: the rate (or
    the interval dt) and the speed stored beside the record are the file's, as a CWRU file's
    X097RPM is; a .npz of one record and scalars needs no --variable. Before, --fs was asked
    for and such a .npz was refused with "choose a variable"."""
    from scipy.io import savemat

    cases = {
        "fs.mat": {"x": X, "fs": 12000.0, "rpm": 1797.0},
        "Fs.mat": {"acc": X, "Fs": np.int32(12000)},
        "dt.mat": {"x": X, "dt": 1 / 12000},
        "rate.npz": {"x": X, "sample_rate": 12000.0, "shaft_rpm": 1797.0},
    }
    for name, variables in cases.items():
        path = tmp_path / name
        if name.endswith(".mat"):
            savemat(path, variables)
        else:
            np.savez(path, **variables)
        x, meta = read_recording(path)
        np.testing.assert_array_equal(x, X)
        assert meta["fs_hz"] == pytest.approx(FS, rel=1e-12), name
        assert meta.get("rpm") == (1797.0 if "rpm" in str(variables.keys()) else None), name
    argv = ["diagnose", str(tmp_path / "fs.mat"), "--bearing", "6205", "--json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["assumptions"]["fs_hz"] == FS and d["assumptions"]["rpm_given"] == 1797.0
    assert main([*argv, "--fs", "25600"]) == 0
    said = json.loads(capsys.readouterr().out)["warnings"]
    assert "--fs 25600 Hz differs from the file's 12000 Hz; using --fs" in said
    # two rates that disagree give none (asked for), as a file without one
    savemat(tmp_path / "two.mat", {"x": X, "fs": 12000.0, "sr": 25600.0})
    assert "fs_hz" not in read_recording(tmp_path / "two.mat")[1]


@pytest.mark.parametrize(
    ("stamp", "separator"),
    [
        ("%Y-%m-%d %H:%M:%S.%f", ","),
        ("%Y-%m-%dT%H:%M:%S.%fZ", ","),
        ("%H:%M:%S.%f", ";"),
    ],
)
def test_a_loggers_time_stamps_give_the_rate(tmp_path, capsys, stamp, separator):
    """A logger's first column of date-times or clock times (to the microsecond): the rate
    from their span, as a time column in seconds gives it. Such a file was refused as "no
    row of numbers"."""
    import pandas as pd

    start = pd.Timestamp("2026-11-30 03:45:00")
    times = start + pd.to_timedelta(T, unit="s")
    path = tmp_path / "logger.csv"
    rows = "\n".join(
        f"{t.strftime(stamp)}{separator}{v:.6f}" for t, v in zip(times, X, strict=True)
    )
    path.write_text(f"timestamp{separator}acc\n" + rows)
    x, meta = read_recording(path)
    np.testing.assert_allclose(x, X, atol=5e-7)
    # stamps to the microsecond: the last one within 0.5 us of 11999 / 12000 s
    assert meta["fs_hz"] == pytest.approx(FS, rel=1e-6) and meta["variable"] == "acc"
    assert main(["diagnose", str(path), "--rpm", "1797", "--bearing", "6205", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["warnings"] == []
    # a column of other text is still refused by its line
    path.write_text("timestamp,acc\n" + "\n".join(f"t{k},{v:.6f}" for k, v in enumerate(X)))
    with pytest.raises(RecordingError, match="is no row of numbers"):
        read_recording(path)


def test_a_labview_tdms_recording_is_read_with_its_rate_unit_and_channels(tmp_path, capsys):
    """National Instruments' TDMS: a group of channels written as waveforms, each with its
    sampling interval and unit. The channel by --variable group/channel, --channel name or
    number; the rate and unit the file's; a tacho channel for --tacho. A cut file is refused
    by name. Before, ".tdms" was an unknown format."""
    from nptdms import ChannelObject, TdmsWriter

    rpm = 1750.0
    t = np.arange(2 * N) / FS
    x = np.random.default_rng(10).standard_normal(2 * N)
    tacho = np.where((rpm / 60 * t) % 1.0 < 0.05, 5.0, 0.0)
    path = tmp_path / "run.tdms"
    waveform = {"wf_increment": 1 / FS, "wf_start_offset": 0.0}
    with TdmsWriter(path) as writer:
        writer.write_segment(
            [
                ChannelObject("Vibration", "DE accel", x, {**waveform, "unit_string": "g"}),
                ChannelObject("Vibration", "Key", tacho, {**waveform, "unit_string": "V"}),
            ]
        )
    y, meta = read_recording(path)
    np.testing.assert_array_equal(y, x)
    assert meta["fs_hz"] == pytest.approx(FS, rel=1e-12) and meta["unit"] == "g"
    assert meta["variable"] == "Vibration/DE accel" and meta["channels"] == 2
    for asked in ({"channel": 1}, {"channel": "Key"}, {"variable": "Vibration/Key"}):
        k, meta = read_recording(path, **asked)
        np.testing.assert_array_equal(k, tacho)
        assert "unit" not in meta, asked  # volts: no vibration unit
    with pytest.raises(RecordingError, match=r"channel 'Other' not found; it holds \['Vib"):
        read_recording(path, channel="Other")
    argv = ["diagnose", str(path), "--bearing", "6205", "--tacho", "Key", "--json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["assumptions"]["rpm"] == pytest.approx(rpm, rel=2e-3)
    assert d["assumptions"]["unit"] == "g" and d["assumptions"]["fs_hz"] == FS
    # a file cut short: read as far as it goes, said (npTDMS's log, not printed as well)
    path.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    y, meta = read_recording(path)
    assert 0 < y.size < x.size
    np.testing.assert_array_equal(y, x[: y.size])
    assert any("less data than expected" in w for w in meta["warnings"]), meta
    assert meta["warnings"][0].startswith("run.tdms: ")
    assert "less data" not in capsys.readouterr().err
    path.write_bytes(b"not a TDMS file" * 20)
    with pytest.raises(RecordingError, match=r"run\.tdms: not a readable TDMS file"):
        read_recording(path)


def _uff58(name, data, fs, unit, *, func_type=1, binary=0, x=None):
    """A data-set 58 as pyuff writes it: a time response of ``data`` at ``fs`` in ``unit``."""
    import pyuff

    n = len(data)
    complex_data = np.iscomplexobj(data)
    return pyuff.prepare_58(
        binary=binary,
        id1=name,
        id2="cmtool test",
        id3="",
        id4="",
        id5="",
        func_type=func_type,
        ver_num=0,
        load_case_id=0,
        rsp_ent_name="pump",
        rsp_node=1,
        rsp_dir=3,
        ref_ent_name="NONE",
        ref_node=0,
        ref_dir=0,
        ord_data_type=6 if complex_data else 4,
        num_pts=n,
        abscissa_spacing=1 if x is None else 0,
        abscissa_min=0.0,
        abscissa_inc=1.0 / fs,
        z_axis_value=0.0,
        abscissa_spec_data_type=17 if func_type == 1 else 18,
        abscissa_axis_units_lab="s",
        ordinate_spec_data_type=12,
        ordinate_len_unit_exp=1,
        ordinate_axis_units_lab=unit,
        orddenom_spec_data_type=0,
        orddenom_axis_units_lab="",
        z_axis_spec_data_type=0,
        z_axis_axis_units_lab="",
        **{  # no force or temperature in any axis, no length in the others
            f"{axis}_{kind}_unit_exp": 0
            for axis in ("abscissa", "ordinate", "orddenom", "z_axis")
            for kind in ("len", "force", "temp")
            if (axis, kind) != ("ordinate", "len")
        },
        data=data,
        x=np.arange(n) / fs if x is None else x,
        return_full_dict=True,
    )


def test_a_universal_file_formats_time_records_are_read_with_their_rate_and_unit(tmp_path, capsys):
    """UFF data-set 58 (.uff/.unv), as modal and signal analysers export time records: the
    file's time responses by --variable (their ID line) or --channel (ID line or number), a
    frequency function beside them skipped; the rate one over the abscissa's step (the header
    keeps six significant digits of it: the rate of fewest digits that prints so, 12000 Hz, and
    MFPT's 97656.25 within 3e-6), the unit the ordinate's label; a tacho record for --tacho.
    Before, ".uff" was an unknown format."""
    import pyuff

    rpm = 1750.0
    t = np.arange(2 * N) / FS
    x = np.random.default_rng(11).standard_normal(2 * N)
    tacho = np.where((rpm / 60 * t) % 1.0 < 0.05, 5.0, 0.0)
    frf = np.fft.rfft(x)[:200]
    path = tmp_path / "route.uff"
    pyuff.UFF(str(path)).write_sets(
        [
            _uff58("H1 DE-FE", frf, 1.0, "g/N", func_type=4),  # an FRF: not a time record
            _uff58("DE accel", x, FS, "g"),
            _uff58("Key", tacho, FS, "V"),
        ],
        mode="overwrite",
    )
    y, meta = read_recording(path)
    np.testing.assert_allclose(y, x, rtol=1e-10)  # ASCII: E20.11
    assert meta["fs_hz"] == FS and meta["unit"] == "g"  # 8.33333e-05 s: 12000 Hz
    assert meta["variable"] == "DE accel" and meta["channels"] == 2
    for asked in ({"channel": 1}, {"channel": "Key"}, {"variable": "Key"}):
        k, meta = read_recording(path, **asked)
        np.testing.assert_allclose(k, tacho, atol=1e-5)
        assert "unit" not in meta, asked  # volts: no vibration unit
    with pytest.raises(
        RecordingError, match=r"record 'Other' not found; it holds 0: 'DE accel', 1: 'Key'$"
    ):
        read_recording(path, channel="Other")
    argv = ["diagnose", str(path), "--bearing", "6205", "--tacho", "Key", "--json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["assumptions"]["rpm"] == pytest.approx(rpm, rel=2e-3)
    assert d["assumptions"]["unit"] == "g"
    assert d["assumptions"]["fs_hz"] == FS
    # binary 58b keeps the samples in double precision (the increment as the header prints it)
    binary = tmp_path / "route.unv"
    # (pyuff 2.5 truncates a binary data-set's header in "overwrite": a new file, "add")
    pyuff.UFF(str(binary)).write_sets([_uff58("DE accel", x, FS, "m/s^2", binary=1)], "add")
    y, meta = read_recording(binary)
    np.testing.assert_array_equal(y, x)
    assert meta["fs_hz"] == FS and meta["unit"] == "m/s^2"
    mfpt = tmp_path / "mfpt.uff"
    pyuff.UFF(str(mfpt)).write_sets([_uff58("a", x[:N], 97656.25, "g")], "add")
    assert read_recording(mfpt)[1]["fs_hz"] == pytest.approx(97656.25, rel=3e-6)
    # the abscissa's values listed (uneven spacing): even steps give the rate, others refused
    for binary_flag, rel in ((1, 1e-9), (0, 1e-6)):  # ASCII lists six digits of each value
        listed = tmp_path / f"listed{binary_flag}.uff"
        sets = [_uff58("a", x[:N], FS, "g", binary=binary_flag, x=t[:N])]
        pyuff.UFF(str(listed)).write_sets(sets, "add")
        assert read_recording(listed)[1]["fs_hz"] == pytest.approx(FS, rel=rel)
        jittered = t[:N] + np.where(np.arange(N) == N // 2, 0.3 / FS, 0.0)
        listed = tmp_path / f"jittered{binary_flag}.uff"
        sets = [_uff58("a", x[:N], FS, "g", binary=binary_flag, x=jittered)]
        pyuff.UFF(str(listed)).write_sets(sets, "add")
        with pytest.raises(RecordingError, match=r"'a' is not evenly sampled"):
            read_recording(listed)
    only = tmp_path / "frf.uff"
    pyuff.UFF(str(only)).write_sets([_uff58("H1", frf, 1.0, "g/N", func_type=4)], "overwrite")
    with pytest.raises(RecordingError, match=r"frf\.uff: a UFF file with no time record .* 1 data"):
        read_recording(only)
    path.write_text("not a universal file\n" * 20)
    with pytest.raises(RecordingError, match=r"route\.uff: not a readable UFF file"):
        read_recording(path)


def test_an_excel_workbooks_table_is_read_as_a_csv_files_is(tmp_path, capsys):
    """A recording saved from Excel (.xlsx): lines of notes, a header, a units row, time in
    seconds or as Excel's date-times, a column of the channel. The samples, the rate and the
    unit are those of the same table as CSV. Before, ".xlsx" was an unknown format."""
    import datetime as dt

    from openpyxl import Workbook

    n = 2400  # 0.2 s: a workbook of a few thousand rows
    start = dt.datetime(2026, 11, 30, 3, 45)
    # Excel keeps a date-time to the millisecond: stamps of a 1 kHz logger resolve
    stamps = [start + dt.timedelta(milliseconds=k) for k in range(n)]
    for name, times, units, rate in (
        ("seconds.xlsx", list(T[:n]), ["s", "g"], FS),
        ("stamps.xlsx", stamps, None, 1000.0),
    ):
        book = Workbook()
        sheet = book.active
        sheet.append(["Pump 3 DE, run 7"])  # notes before the table
        sheet.append([])
        sheet.append(["time", "acc [g]"])
        if units:
            sheet.append(units)
        for t, v in zip(times, X[:n], strict=True):
            sheet.append([t, float(v)])
        book.save(tmp_path / name)
        x, meta = read_recording(tmp_path / name)
        np.testing.assert_allclose(x, X[:n], rtol=1e-15)  # as openpyxl writes a double
        assert meta["fs_hz"] == pytest.approx(rate, rel=1e-9), name
        assert meta["unit"] == "g" and meta["variable"] == "acc [g]", name
    argv = ["diagnose", str(tmp_path / "seconds.xlsx"), "--rpm", "1797", "--bearing", "6205"]
    assert main([*argv, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["assumptions"]["fs_hz"] == pytest.approx(FS)
    (tmp_path / "cut.xlsx").write_bytes((tmp_path / "seconds.xlsx").read_bytes()[:500])
    with pytest.raises(RecordingError, match=r"cut\.xlsx: not a readable Excel workbook"):
        read_recording(tmp_path / "cut.xlsx")


def test_a_time_column_that_gives_no_rate_leaves_it_to_fs(tmp_path, capsys):
    """A time column that falls, or stands still (Excel keeps time stamps to the millisecond:
    a 12 kHz record's stamps repeat): no rate is read from it, the reason is said, and --fs
    gives the rate. It was refused even with --fs given."""
    path = tmp_path / "rec.csv"
    for times, step in ((-T, "-8.333e-05"), (np.floor(T * 1e3) / 1e3, "0")):
        path.write_text(
            "time,acc\n" + "\n".join(f"{t:.8f},{v:.6f}" for t, v in zip(times, X, strict=True))
        )
        x, meta = read_recording(path)
        np.testing.assert_allclose(x, X, atol=5e-7)
        assert "fs_hz" not in meta
        (said,) = meta["warnings"]
        assert f"column 'time' is no time axis (its median step is {step} s" in said
        argv = ["diagnose", str(path), "--rpm", "1797", "--bearing", "6205", "--json"]
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert "holds no sample rate; give --fs" in err and "is no time axis" in err
        assert main([*argv, "--fs", "12000"]) == 0
        assert said in json.loads(capsys.readouterr().out)["warnings"]


@pytest.mark.parametrize("suffix", [".csv", ".mat", ".tdms"])
def test_a_recordings_second_channel_is_read_from_the_parse_kept(tmp_path, monkeypatch, suffix):
    """--tacho reads the vibration's channel and then the tachometer's from the same file: the
    file is parsed once (cmtool.last_file; until stop 78 it was parsed twice), the samples
    handed out are copies (changing one leaves the next read as the file is), and a file
    rewritten is parsed again."""
    import nptdms
    import scipy.io
    from nptdms import ChannelObject, TdmsWriter

    import cmtool.io

    parses = []

    def counted(module, name):
        original = getattr(module, name)

        def wrapper(*args, **kwargs):
            parses.append(name)
            return original(*args, **kwargs)

        monkeypatch.setattr(module, name, wrapper)

    counted(cmtool.io.pd, "read_csv")
    counted(scipy.io, "loadmat")
    counted(nptdms.TdmsFile, "read")
    tacho = np.where((30.0 * T) % 1.0 < 0.05, 5.0, 0.0)

    def write(path, x):
        if suffix == ".csv":
            rows = (f"{a:.17g},{b:.17g}" for a, b in zip(x, tacho, strict=True))
            path.write_text("acc,key\n" + "\n".join(rows))
        elif suffix == ".mat":
            scipy.io.savemat(path, {"X001_DE_time": x, "X001_FE_time": tacho})
        else:
            with TdmsWriter(path) as writer:
                writer.write_segment(
                    [ChannelObject("V", "acc", x), ChannelObject("V", "key", tacho)]
                )

    path = tmp_path / f"rec{suffix}"
    write(path, X)
    second = {"variable": "X001_FE_time"} if suffix == ".mat" else {"channel": 1}
    first, _ = read_recording(path, **({"variable": "X001_DE_time"} if suffix == ".mat" else {}))
    key, _ = read_recording(path, **second)
    np.testing.assert_array_equal(first, X)
    np.testing.assert_array_equal(key, tacho)
    assert len(parses) == 1, parses
    first[:] = 0.0  # a caller's change to its samples
    again, _ = read_recording(path, **({"variable": "X001_DE_time"} if suffix == ".mat" else {}))
    np.testing.assert_array_equal(again, X)
    write(path, 2.0 * X)  # the file rewritten: parsed again
    changed, _ = read_recording(path, **({"variable": "X001_DE_time"} if suffix == ".mat" else {}))
    np.testing.assert_array_equal(changed, 2.0 * X)
    assert len(parses) == 2, parses
