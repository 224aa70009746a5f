"""Inputs a new user tries: each gets a clear one-line error or the right reading (issue 19)."""

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from impact_trains import ringing_impact_train

from cmtool.cli import main

REPO = Path(__file__).resolve().parents[2]


def _one_line_error(capsys) -> str:
    err = capsys.readouterr().err
    assert "Traceback" not in err and err.count("\n") == 1, err
    return err


@pytest.fixture
def outer_race_csv(tmp_path, rng):
    """A header-less two-column CSV (time, value) of impacts at BPFO with jitter, 12 kHz."""
    from scipy import signal as sp_signal

    from generators import bearing, characteristic_frequencies

    fs, n = 12000.0, 24000
    f = characteristic_frequencies(bearing("6205"), 1797 / 60)
    times = np.arange(0.0, n / fs, 1 / f.bpfo)
    times = times + rng.normal(0.0, 0.01 / f.bpfo, times.size)
    x = np.zeros(n)
    x[np.clip((times * fs).astype(int), 0, n - 1)] = 1.0
    x = sp_signal.lfilter(*sp_signal.iirpeak(3000.0, 15.0, fs), x) + 0.05 * rng.standard_normal(n)
    path = tmp_path / "rec.csv"
    np.savetxt(path, np.c_[np.arange(n) / fs, x], delimiter=",")
    return path


def test_headerless_time_value_csv_is_read_on_its_value_column(outer_race_csv, capsys):
    assert main(["diagnose", str(outer_race_csv), "--rpm", "1797", "--bearing", "6205"]) == 0
    out = capsys.readouterr().out
    assert "outer race" in out.splitlines()[0] and "fs 12000 Hz" in out
    assert "channel column 1" in out


def test_inputs_that_cannot_be_diagnosed_are_errors(outer_race_csv, tmp_path, capsys):
    base = ["diagnose", str(outer_race_csv), "--rpm", "1797"]
    assert main(base) == 2  # the CSV does not say which bearing
    assert "give --bearing" in _one_line_error(capsys)
    assert main([*base, "--bearing", "6205", "--fs", "200"]) == 2
    assert "fs >= " in _one_line_error(capsys)
    short = tmp_path / "short.csv"
    np.savetxt(short, np.random.default_rng(0).standard_normal(100))
    assert (
        main(["diagnose", str(short), "--rpm", "1797", "--bearing", "6205", "--fs", "12000"]) == 2
    )
    assert "samples" in _one_line_error(capsys)
    assert main([*base, "--bearing", "6205", "--channel", "5"]) == 2
    assert "channel 5 is outside" in _one_line_error(capsys)
    for load in ("-5", "0", "1e8", "nan"):  # the healthy model's load for waviness
        assert main([*base, "--bearing", "6205", "--load", load]) == 2
        assert "--load = " in _one_line_error(capsys)
    from cmtool.diagnose import diagnose_signal
    from generators import ParameterError

    with pytest.raises(ParameterError, match=r"load_n = -5 N is outside the allowed range \(0, "):
        diagnose_signal(np.ones(12000), 12000.0, 1797.0, "6205", load_n=-5.0)
    report = tmp_path / "report.md"
    report.write_text("mine")
    assert main([*base, "--bearing", "6205", "--report", str(report)]) == 2
    assert "is a file" in _one_line_error(capsys)
    assert report.read_text() == "mine"


def test_a_clipped_record_is_refused_unless_allowed(outer_race_csv, tmp_path, capsys):
    """From 3 % of the samples at full scale the rule's verdict changes for more than 5 % of
    simulated records (docs/diagnosis.md, "Clipping"): diagnose refuses, --allow-clipping
    overrides; 1 % is diagnosed with a warning. The baseline is held to the same."""
    x = np.loadtxt(outer_race_csv, delimiter=",")[:, 1]
    paths = {}
    for share in (0.01, 0.05):
        level = np.quantile(np.abs(x), 1.0 - share)
        paths[share] = tmp_path / f"clipped-{share}.npy"
        np.save(paths[share], np.clip(x, -level, level))
    base = ["--rpm", "1797", "--bearing", "6205", "--fs", "12000"]
    assert main(["diagnose", str(paths[0.05]), *base]) == 2
    err = _one_line_error(capsys)
    assert "is clipped: 5.0% of its samples" in err and "--allow-clipping" in err
    assert main(["diagnose", str(paths[0.05]), *base, "--allow-clipping"]) == 0
    assert "signal looks clipped: 1200 samples (5.00%)" in capsys.readouterr().out
    assert main(["diagnose", str(paths[0.01]), *base]) == 0
    assert "signal looks clipped: 240 samples (1.00%)" in capsys.readouterr().out
    argv = ["diagnose", str(outer_race_csv), *base, "--baseline", str(paths[0.05])]
    assert main(argv) == 2
    assert "--baseline" in _one_line_error(capsys)
    # a 16-bit converter clips at -32768 and 32767: both ends count (about 2.5 % each)
    counts = np.round(x / np.quantile(np.abs(x), 0.95) * 32767.5 - 0.5)
    int16 = tmp_path / "int16.npy"
    np.save(int16, np.clip(counts, -32768, 32767).astype(np.int16))
    assert main(["diagnose", str(int16), *base]) == 2
    assert "(3.277e+04, -3.277e+04)" in _one_line_error(capsys)
    constant = tmp_path / "constant.npy"
    np.save(constant, np.ones(24000))  # every sample at full scale, but no signal at all
    assert main(["diagnose", str(constant), *base]) == 2
    assert "signal is constant" in _one_line_error(capsys)


def test_each_faults_margin_is_shown_against_a_baseline_and_not_weighed(
    outer_race_csv, tmp_path, rng, capsys
):
    """With --baseline, each fault's margin over its threshold in the record and in the
    baseline (its own band and threshold) are printed, written to the JSON and the report, and
    left out of the verdict (docs/diagnosis.md, "Local faults against a baseline"): a record
    against itself rises by 0 dB and keeps its verdict; a baseline too short for the rule gets
    a warning instead."""
    import json

    from scipy import signal as sp_signal

    ring = sp_signal.iirpeak(3000.0, 15.0, 12000.0)
    noise = sp_signal.lfilter(*ring, 0.02 * rng.standard_normal(24000))
    healthy = tmp_path / "healthy.npy"
    np.save(healthy, noise + 0.05 * rng.standard_normal(24000))
    base = [str(outer_race_csv), "--rpm", "1797", "--bearing", "6205", "--fs", "12000"]
    report = tmp_path / "report"
    assert main(["diagnose", *base, "--baseline", str(healthy), "--report", str(report)]) == 0
    out = capsys.readouterr().out
    assert "rec.csv: outer race (confidence" in out
    assert "against the baseline (2 s at 12000 Hz, its band " in out
    assert (
        "| fault | margin [dB] | baseline margin [dB] | rise [dB] |"
        in (report / "report.md").read_text()
    )
    assert main(["diagnose", *base, "--baseline", str(healthy), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    ours, theirs = d["baseline"]["fault_margin_db"], d["baseline"]["baseline_fault_margin_db"]
    assert set(ours) == set(theirs) == {"outer race", "inner race", "ball"}
    assert ours["outer race"] > 0 > theirs["outer race"]
    assert ours["outer race"] - theirs["outer race"] > 10
    said = d["baseline"]  # what the baseline's margins rest on
    assert (said["record_s"], said["fs_hz"]) == (2.0, 12000.0) and said["threshold_db"] > 0
    assert 0 <= said["band_hz"][0] < said["band_hz"][1] <= 6000
    assert main(["diagnose", *base, "--baseline", str(outer_race_csv), "--json"]) == 0
    same = json.loads(capsys.readouterr().out)
    assert same["verdict"] == "outer race"  # not weighed: no rise at all, the same verdict
    assert same["baseline"]["fault_margin_db"] == same["baseline"]["baseline_fault_margin_db"]
    short = tmp_path / "short.npy"
    np.save(short, np.load(healthy)[:1200])
    assert main(["diagnose", *base, "--baseline", str(short), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert "fault_margin_db" not in d["baseline"] and d["baseline"]["record_s"] == 0.1
    assert any(
        w.startswith("no fault margins for the baseline: the record is 0.1 s")
        for w in d["warnings"]
    )


def test_a_baselines_band_above_half_the_rate_is_left_out_of_strict_json(rng, tmp_path, capsys):
    """A slow machine recorded at 3 kHz: the ISO 15242 high band (1.8-10 kHz) lies above fs /
    2 for the record and for its baseline, and is left out of both (the baseline's was NaN,
    which is not JSON)."""
    import json

    from cmtool.diagnose import diagnose_signal

    x, baseline = rng.standard_normal(30000), rng.standard_normal(30000)
    d = diagnose_signal(x, 3000.0, 300.0, "6205", baseline=baseline)
    json.dumps(d.to_dict(), allow_nan=False)
    assert set(d.baseline["velocity_bands"]) == set(d.velocity_bands) == {"low", "medium"}
    # the command's JSON and diagnosis.json are strict JSON whatever a diagnosis holds
    np.save(tmp_path / "x.npy", x)
    np.save(tmp_path / "b.npy", baseline)
    argv = [str(tmp_path / "x.npy"), "--fs", "3000", "--rpm", "300", "--bearing", "6205"]
    argv += ["--baseline", str(tmp_path / "b.npy")]

    def refuse(constant):
        raise ValueError(f"{constant} in the JSON")

    assert main(["diagnose", *argv, "--json"]) == 0
    json.loads(capsys.readouterr().out, parse_constant=refuse)
    assert main(["diagnose", *argv, "--report", str(tmp_path / "r")]) == 0
    json.loads((tmp_path / "r" / "diagnosis.json").read_text(), parse_constant=refuse)


def test_a_quantised_tone_is_not_taken_for_clipping(tmp_path, capsys):
    """A clipped end is a plateau: a calibrator's 159.2 Hz tone of 100 counts on a 16-bit
    converter has 3.2 % of its samples at each extreme level but 2.3 % one count in, and is
    not clipped (until stop 46 it was refused as 6.4 % clipped); the same tone clipped at 80
    counts piles its peaks at the rail and is refused. A two-valued record is all plateau."""
    from cmtool.diagnose import clipped_share

    t = np.arange(24000) / 12000.0
    tone = np.round(100.0 * np.sin(2 * np.pi * 159.2 * t + 0.1))
    assert np.mean(tone == tone.max()) > 0.03  # what the old count refused
    assert clipped_share(tone) == 0.0
    assert clipped_share(np.clip(tone, -80, 80)) > 0.2
    assert clipped_share(np.sign(np.sin(2 * np.pi * 50.0 * t + 0.1))) == 1.0
    base = ["--rpm", "1797", "--bearing", "6205", "--fs", "12000"]
    path = tmp_path / "tone.npy"
    np.save(path, tone.astype(np.int16))
    assert main(["diagnose", str(path), *base]) == 0
    assert "looks clipped" not in capsys.readouterr().out
    np.save(path, np.clip(tone, -80, 80).astype(np.int16))
    assert main(["diagnose", str(path), *base]) == 2
    assert "is clipped" in _one_line_error(capsys)


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_cmtool_files_carry_rate_speed_bearing_and_unit(tmp_path, capsys, suffix):
    """A cmtool file, parquet (metadata in the file) or CSV (in its .csv.json sidecar), gives
    diagnose its rate, speed, bearing and unit (the CSV's were not read until stop 50)."""
    signal = tmp_path / f"sig{suffix}"
    argv = ["simulate", "--bearing", "6203", "--rpm", "2400", "--duration", "0.5", "--fs"]
    assert (
        main(
            [
                *argv,
                "12000",
                "--channels",
                "housing_acceleration_y,shaft_velocity_x",
                "--out",
                str(signal),
            ]
        )
        == 0
    )
    read = pd.read_parquet if suffix == ".parquet" else pd.read_csv
    assert list(read(signal).columns) == [
        "time",
        "housing_acceleration_y",
        "shaft_velocity_x",
    ]
    capsys.readouterr()
    assert main(["diagnose", str(signal), "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assumed = data["assumptions"]
    assert (assumed["bearing"], assumed["rpm"], assumed["fs_hz"]) == ("6203", 2400.0, 12000.0)
    assert assumed["channel"] == "housing_acceleration_y"
    assert set(data["velocity_bands_iso15242_mm_s"]) == {"low", "medium", "high"}


def test_a_csv_sidecar_counts_only_when_cmtool_wrote_it(tmp_path):
    from cmtool.io import RecordingError, read_recording

    csv = tmp_path / "pump.csv"
    pd.DataFrame({"time": np.arange(100) / 1000.0, "a": np.sin(np.arange(100))}).to_csv(
        csv, index=False
    )
    sidecar = tmp_path / "pump.csv.json"
    sidecar.write_text(json.dumps({"fs_hz": 5.0, "note": "a logger's own file"}))
    _, meta = read_recording(csv)
    assert meta["fs_hz"] == pytest.approx(1000.0) and "unit" not in meta  # from the time column
    sidecar.write_text("{not json")
    with pytest.raises(RecordingError, match=r"pump.csv.json: not a readable JSON sidecar"):
        read_recording(csv)


def test_truncated_mat_and_bad_outputs_are_refused_before_work(tmp_path, capsys):
    truncated = tmp_path / "x.mat"
    truncated.write_bytes(b"MATLAB 5.0 MAT-file" + bytes(100))
    assert (
        main(["diagnose", str(truncated), "--rpm", "1797", "--bearing", "6205", "--fs", "12000"])
        == 2
    )
    assert "not a readable MATLAB file" in _one_line_error(capsys)
    for flag, value in (("--out", "sig.txt"), ("--plot", "x.jpgx"), ("--channels", "bogus")):
        assert main(["simulate", "--duration", "5000", flag, str(tmp_path / value)]) == 2
        _one_line_error(capsys)  # refused at once: a 5000 s run would take minutes
    with pytest.raises(SystemExit) as stop:  # argparse's usage error
        main(
            [
                "generate",
                str(REPO / "datasets" / "small.toml"),
                "--out",
                str(tmp_path),
                "--workers",
                "0",
            ]
        )
    assert stop.value.code == 2
    assert "--workers: 0 is outside the allowed range [1, inf)" in capsys.readouterr().err


def test_an_interrupted_dataset_is_refused_unless_asked(tmp_path, capsys):
    copy = tmp_path / "small"
    shutil.copytree(REPO / "datasets" / "small", copy)
    (copy / "_dataset.json").unlink()
    assert main(["train", str(copy), "--out", str(tmp_path / "m.skops")]) == 2
    assert "--resume" in _one_line_error(capsys)
    assert main(["dataset", "info", str(copy)]) == 0
    assert "INCOMPLETE" in capsys.readouterr().out


def test_a_run_without_a_seed_draws_one_says_it_and_writes_it(tmp_path, capsys):
    """Slip makes a run random: without --seed one is drawn, printed and written with the
    signal, and --seed with it repeats the run to the bit (until stop 52 such a run could not
    be repeated)."""
    from cmtool.io import read_signal

    argv = ["simulate", "--duration", "0.2", "--random-slip", "0.01", "--fs", "12000"]
    argv += ["--defect", "outer:length=0.3e-3:depth=0.1e-3", "--channels", "housing_acceleration_y"]
    assert main([*argv, "--out", str(tmp_path / "first.parquet")]) == 0
    said = capsys.readouterr().out.splitlines()[0]
    seed = int(said.split()[2])
    assert said == f"random seed {seed} (drawn; --seed {seed} repeats this run)"
    first, meta = read_signal(tmp_path / "first.parquet")
    assert meta["parameters"]["seed"] == seed
    assert main([*argv, "--seed", str(seed), "--out", str(tmp_path / "again.parquet")]) == 0
    assert "random seed" not in capsys.readouterr().out  # a seed given is not announced
    again, _ = read_signal(tmp_path / "again.parquet")
    np.testing.assert_array_equal(again["housing_acceleration_y"], first["housing_acceleration_y"])
    assert (
        main([*argv, "--seed", str((seed + 1) % 2**32), "--out", str(tmp_path / "o.parquet")]) == 0
    )
    other, _ = read_signal(tmp_path / "o.parquet")
    assert not np.array_equal(other["housing_acceleration_y"], first["housing_acceleration_y"])


def test_a_streamed_run_that_diverges_at_its_default_step_runs_again_as_in_memory(
    tmp_path, monkeypatch, capsys
):
    """A run whose default RK4 step diverges (a dry `full` 6002 at 12,000 rpm and 0 N with a
    1 mm ball pit, docs/model.md 7.2) is made again at a shorter step when it streams, as in
    memory: the same step, and the same samples through the first block. (Further on the
    dry pit's impacts carry the blocks' last-bit differences onward, so the whole records
    agree only in level.) Before, the streamed run stopped."""
    import cmtool.commands.simulate as simulate_command
    import generators.stream as stream
    from cmtool.io import read_signal

    argv = ["simulate", "--bearing", "6002", "--rpm", "12000", "--load", "0", "--scene", "full"]
    argv += ["--no-ehl"]
    argv += ["--defect", "ball:length=1e-3:depth=2e-5:latitude=0", "--fs", "12000"]
    argv += ["--duration", "0.05", "--settle", "0.01", "--seed", "1"]
    argv += ["--channels", "housing_acceleration_y"]
    assert main([*argv, "--out", str(tmp_path / "whole.parquet")]) == 0
    said = capsys.readouterr()
    assert "diverged at its default RK4 step" in said.err
    monkeypatch.setattr(simulate_command, "STREAM_ABOVE_SAMPLES", 100)
    monkeypatch.setitem(stream.simulate_stream.__kwdefaults__, "block_samples", 200)
    assert main([*argv, "--out", str(tmp_path / "streamed.parquet")]) == 0
    streamed_said = capsys.readouterr()
    assert "streamed in blocks of 200 samples" in streamed_said.out
    warning = [line for line in streamed_said.err.splitlines() if "diverged" in line]
    assert warning and "integrated again at" in warning[0]
    whole, meta_whole = read_signal(tmp_path / "whole.parquet")
    streamed, meta_streamed = read_signal(tmp_path / "streamed.parquet")
    stats = meta_streamed["parameters"]["integrator_stats"]
    assert stats == meta_whole["parameters"]["integrator_stats"] and stats["step_halvings"] >= 1
    x = streamed["housing_acceleration_y"].to_numpy()
    reference = whole["housing_acceleration_y"].to_numpy()
    rms = np.sqrt(np.mean(reference**2))
    np.testing.assert_allclose(x[:200], reference[:200], rtol=1e-9, atol=1e-9 * rms)
    assert np.all(np.isfinite(x)) and np.sqrt(np.mean(x**2)) == pytest.approx(rms, rel=0.2)


@pytest.mark.parametrize("suffix", [".parquet", ".csv"])
def test_long_runs_stream_to_the_same_file(tmp_path, monkeypatch, capsys, suffix):
    """Above STREAM_ABOVE_SAMPLES simulate writes block by block; the file is the same one."""
    import cmtool.commands.simulate as simulate_command
    import generators.stream as stream
    from cmtool.io import read_signal

    argv = ["simulate", "--duration", "0.3", "--channels", "housing_acceleration_y", "--seed", "7"]
    assert main([*argv, "--out", str(tmp_path / f"whole{suffix}")]) == 0
    monkeypatch.setattr(simulate_command, "STREAM_ABOVE_SAMPLES", 1000)
    monkeypatch.setitem(stream.simulate_stream.__kwdefaults__, "block_samples", 1000)
    assert main([*argv, "--out", str(tmp_path / f"streamed{suffix}")]) == 0
    assert "streamed in blocks of 1,000 samples" in capsys.readouterr().out
    whole, meta_whole = read_signal(tmp_path / f"whole{suffix}")
    streamed, meta_streamed = read_signal(tmp_path / f"streamed{suffix}")
    assert list(streamed.columns) == ["time", "housing_acceleration_y"]
    np.testing.assert_array_equal(streamed["time"], whole["time"])
    x, reference = streamed["housing_acceleration_y"], whole["housing_acceleration_y"]
    rms = np.sqrt(np.mean(reference**2))
    # 8 blocks; the file's precision (CSV: 10 digits)
    np.testing.assert_allclose(x, reference, rtol=1e-9, atol=1e-9 * rms)  # the ends too
    assert meta_streamed["parameters"]["streamed_block_samples"] == 1000
    assert meta_streamed["parameters"]["seed"] == 7
    meta_streamed["parameters"].pop("streamed_block_samples")
    assert meta_streamed["parameters"] == meta_whole["parameters"]
    if suffix == ".parquet":
        import pyarrow.parquet as pq

        assert pq.ParquetFile(tmp_path / "streamed.parquet").num_row_groups == 8
    for flag in ("--plot", "--envelope-plot"):
        assert main([*argv, flag, str(tmp_path / "x.png")]) == 2
        assert "streams to disk" in _one_line_error(capsys)
    assert main([*argv, "--integrator", "dopri5"]) == 2
    assert "use --integrator rk4" in _one_line_error(capsys)
    assert not (tmp_path / "x.png").exists()


def test_an_output_larger_than_the_free_disk_is_refused_before_the_run(
    tmp_path, monkeypatch, capsys
):
    import collections

    usage = collections.namedtuple("usage", "total used free")
    monkeypatch.setattr(shutil, "disk_usage", lambda path: usage(10**9, 10**9 - 10**6, 10**6))
    out = tmp_path / "deep" / "sig.csv"
    assert main(["simulate", "--duration", "3600", "--fs", "51200", "--out", str(out)]) == 2
    message = _one_line_error(capsys)
    assert "writes about 43.13 GB" in message and "0.00 GB free" in message
    assert not out.exists()


def test_the_command_line_starts_without_the_numerical_stack():
    """``cmtool --help`` and argument errors load no numpy, scipy, numba or matplotlib."""
    import subprocess
    import sys

    code = (
        "import sys, cmtool.cli as c\n"
        "try:\n    c.main(['--help'])\nexcept SystemExit:\n    pass\n"
        "heavy = ('numpy', 'scipy', 'numba', 'matplotlib', 'pandas')\n"
        "heavy = [m for m in heavy if m in sys.modules]\n"
        "print(','.join(heavy))"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.splitlines()[-1] == ""  # the list of heavy modules loaded: none


@pytest.mark.parametrize(
    "argv",
    [
        ["frequencies", "--rpm", "{rpm}"],
        ["simulate", "--rpm", "{rpm}", "--duration", "0.01"],
        ["diagnose", "{recording}", "--rpm", "{rpm}", "--bearing", "6205", "--fs", "12000"],
    ],
)
def test_one_shaft_speed_range_in_rpm_for_every_command(argv, tmp_path, capsys):
    recording = tmp_path / "x.npy"
    np.save(recording, np.random.default_rng(0).standard_normal(24000))
    argv = [a.format(rpm="130000", recording=recording) for a in argv]
    assert main(argv) == 2
    message = _one_line_error(capsys)
    assert "--rpm = 130000 rpm is outside the allowed range" in message
    assert "120000] rpm" in message


def test_recipes_take_the_same_shaft_speed_range(tmp_path):
    import tomllib

    from generators import ParameterError
    from generators.params import MAX_SHAFT_SPEED_RPM
    from generators.recipe import validate_recipe

    recipe = tomllib.loads((REPO / "datasets" / "small.toml").read_text())
    recipe["operating"]["rpm"] = [MAX_SHAFT_SPEED_RPM]
    validate_recipe(recipe)
    recipe["operating"]["rpm"] = [MAX_SHAFT_SPEED_RPM + 1]
    with pytest.raises(ParameterError, match=r"in \(0, 120000\] rpm"):
        validate_recipe(recipe)


def test_recording_readers_wav_npy_npz_parquet(tmp_path):
    """Every format reads back the samples written, the asked channel, and refuses others."""
    from scipy.io import wavfile

    from cmtool.io import RecordingError, read_recording

    rng = np.random.default_rng(1)
    stereo = rng.uniform(-0.5, 0.5, (4000, 2))
    wavfile.write(tmp_path / "s.wav", 8000, stereo.astype(np.float32))
    x, meta = read_recording(tmp_path / "s.wav", channel=1)
    np.testing.assert_allclose(x, stereo[:, 1], rtol=1e-6)
    assert meta["fs_hz"] == 8000.0
    pcm = (stereo[:, 0] * 32767).astype(np.int16)
    wavfile.write(tmp_path / "m.wav", 8000, pcm)
    x, _ = read_recording(tmp_path / "m.wav")
    np.testing.assert_allclose(x, pcm / 32767.0)  # integer PCM scaled to [-1, 1]
    np.save(tmp_path / "a.npy", stereo)
    np.testing.assert_array_equal(read_recording(tmp_path / "a.npy", channel=1)[0], stereo[:, 1])
    np.savez(tmp_path / "b.npz", accel=stereo[:, 0], other=stereo[:, 1])
    x, meta = read_recording(tmp_path / "b.npz", variable="other")
    np.testing.assert_array_equal(x, stereo[:, 1])
    assert meta["variable"] == "other"
    with pytest.raises(RecordingError, match="choose a variable"):
        read_recording(tmp_path / "b.npz")
    frame = pd.DataFrame({"time": np.arange(4000) / 8000.0, "accel": stereo[:, 0]})
    frame.to_parquet(tmp_path / "c.parquet")
    np.testing.assert_array_equal(read_recording(tmp_path / "c.parquet")[0], stereo[:, 0])
    for name in ("m.wav", "a.npy"):
        channel = 5 if name == "a.npy" else 1
        with pytest.raises(RecordingError, match=f"channel {channel} is outside"):
            read_recording(tmp_path / name, channel=channel)
    # channels x samples, as numpy and MATLAB users often store them: the shorter axis
    np.save(tmp_path / "rows.npy", stereo.T)
    np.testing.assert_array_equal(read_recording(tmp_path / "rows.npy", channel=1)[0], stereo[:, 1])
    np.testing.assert_array_equal(read_recording(tmp_path / "rows.npy")[0], stereo[:, 0])
    np.save(tmp_path / "cube.npy", stereo.reshape(2, 2000, 2))
    with pytest.raises(RecordingError, match=r"shape \(2, 2000, 2\)"):
        read_recording(tmp_path / "cube.npy")
    (tmp_path / "empty.csv").write_text("")
    with pytest.raises(RecordingError, match="empty.csv: the file holds no data"):
        read_recording(tmp_path / "empty.csv")


def test_a_file_that_is_not_what_its_suffix_says_is_refused_by_name(tmp_path):
    """A recording whose content does not match its suffix, or holds no numbers, is a
    RecordingError naming the file (before: scipy's, numpy's and pyarrow's own errors, some
    without the file's name, and "choose a variable" for a MATLAB file with no numbers)."""
    from scipy.io import savemat

    from cmtool.io import RecordingError, read_recording

    (tmp_path / "x.wav").write_bytes(b"RIFFxxxx")
    (tmp_path / "x.parquet").write_bytes(b"PAR1 not parquet")
    np.save(tmp_path / "words.npy", np.array(["a", "b"]))
    savemat(tmp_path / "text.mat", {"note": "calibrated 2024"})
    for name, said in (
        ("x.wav", r"x\.wav: cannot be read as a wav recording \(Not a WAV file"),
        ("x.parquet", r"x\.parquet: cannot be read as a parquet recording"),
        ("words.npy", r"words\.npy: cannot be read as a npy recording \(could not convert"),
        ("text.mat", r"text\.mat: no numeric array of more than 16 samples; it holds \['note'\]"),
    ):
        with pytest.raises(RecordingError, match=said):
            read_recording(tmp_path / name)


def test_diagnose_reads_the_asked_variable_of_an_npz(outer_race_csv, tmp_path, capsys):
    """--variable picks the array of an .npz (and is refused when it names none)."""
    x = np.loadtxt(outer_race_csv, delimiter=",")[:, 1]
    archive = tmp_path / "two.npz"
    np.savez(archive, noise=np.random.default_rng(2).standard_normal(x.size), accel=x)
    base = ["diagnose", str(archive), "--rpm", "1797", "--bearing", "6205", "--fs", "12000"]
    assert main([*base, "--variable", "accel", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["verdict"] == "outer race"
    assert main([*base, "--variable", "nosuch"]) == 2
    assert "variable 'nosuch' not found; it holds ['noise', 'accel']" in _one_line_error(capsys)


def test_form_waviness_flag_simulates_the_bearings_own_form_errors(tmp_path, capsys):
    """``--form-waviness INNER,OUTER,BALL`` adds generators.form_waviness's rows (the lines of
    a real bearing's form errors) to the run; amplitudes outside [0, 2 um] or not three are
    refused naming the flag and the component."""
    from cmtool.commands.specs import parse_form_waviness
    from cmtool.io import read_recording

    assert parse_form_waviness("1e-7, 0, 5e-8") == (1e-7, 0.0, 5e-8)
    argv = ["simulate", "--duration", "0.5", "--fs", "12000", "--rpm", "1797"]
    argv += ["--load", "400", "--clearance", "5e-6", "--channels", "housing_acceleration_y"]
    assert main([*argv, "--out", str(tmp_path / "perfect.parquet")]) == 0
    form = ["--form-waviness", "1e-7,0,0", "--seed", "2"]
    assert main([*argv, *form, "--out", str(tmp_path / "form.parquet")]) == 0
    spectra = []
    for name in ("perfect", "form"):
        x, _ = read_recording(tmp_path / f"{name}.parquet", channel="housing_acceleration_y")
        x = np.asarray(x, dtype=float)
        spectra.append(np.abs(np.fft.rfft(x * np.hanning(x.size))))
    # the inner race's order-Z form error: a line at BPFI (162.2 Hz; 2 Hz bins) 20 dB up
    i = round(162.19 / 2.0)
    assert 20 * np.log10(spectra[1][i - 1 : i + 2].max() / spectra[0][i - 1 : i + 2].max()) > 20
    capsys.readouterr()
    with pytest.raises(SystemExit):
        main([*argv, "--form-waviness", "1e-7,0,1e-3", "--out", str(tmp_path / "x.parquet")])
    assert "BALL = 0.001 m is outside the allowed range [0, 2e-06] m" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main([*argv, "--form-waviness", "1e-7,0", "--out", str(tmp_path / "x.parquet")])
    assert "expected INNER,OUTER,BALL" in capsys.readouterr().err


def test_a_cwru_file_with_two_records_gives_the_one_its_name_numbers(tmp_path):
    """A CWRU .mat may hold a second record's channels; the drive-end variable read is the one
    whose number the file's name carries, and a name that says neither is refused (rather than
    diagnosing the other record)."""
    from scipy.io import savemat

    from cmtool.io import RecordingError, read_recording

    rng = np.random.default_rng(3)
    own, other = rng.standard_normal(400), rng.standard_normal(400)
    content = {"X098_DE_time": other, "X099_DE_time": own, "X099RPM": 1750.0, "X098RPM": 1772.0}
    for name in ("99.mat", "Normal_2_099.mat", "12k_Normal_99.mat"):
        savemat(tmp_path / name, content)
        x, meta = read_recording(tmp_path / name)
        np.testing.assert_array_equal(x, own)
        assert meta["variable"] == "X099_DE_time" and meta["rpm"] == 1750.0
    savemat(tmp_path / "baseline.mat", content)
    with pytest.raises(RecordingError, match="choose a variable"):
        read_recording(tmp_path / "baseline.mat")
    x, meta = read_recording(tmp_path / "baseline.mat", variable="X098_DE_time")
    np.testing.assert_array_equal(x, other)
    # one drive-end record: read whatever the file is called
    savemat(tmp_path / "renamed.mat", {"X105_DE_time": own, "X105_FE_time": other})
    assert read_recording(tmp_path / "renamed.mat")[1]["variable"] == "X105_DE_time"


def test_a_bearing_not_in_the_catalog_is_given_by_its_geometry(outer_race_csv, capsys):
    """--geometry: the catalog 6205's numbers give the 6205's rates and verdict, stated as given."""
    from generators import bearing

    g = bearing("6205")
    spec = (
        f"my6205:balls={g.ball_count}:ball_diameter={g.ball_diameter!r}:"
        f"pitch_diameter={g.pitch_diameter!r}:contact_angle_deg=0"
    )
    assert main(["frequencies", "--rpm", "1797", "--json"]) == 0
    catalog = json.loads(capsys.readouterr().out)
    assert main(["frequencies", "--rpm", "1797", "--json", "--geometry", spec]) == 0
    given = json.loads(capsys.readouterr().out)
    assert given["bearing"] == "my6205"
    assert given["frequencies_hz"] == pytest.approx(catalog["frequencies_hz"], rel=1e-12)
    base = ["diagnose", str(outer_race_csv), "--rpm", "1797", "--json"]
    assert main([*base, "--bearing", "6205"]) == 0
    by_name = json.loads(capsys.readouterr().out)
    assert main([*base, "--geometry", spec]) == 0
    by_geometry = json.loads(capsys.readouterr().out)
    assert by_geometry["verdict"] == by_name["verdict"] == "outer race"
    assert by_geometry["candidates"] == by_name["candidates"]
    assert by_geometry["assumptions"]["bearing"] == "my6205"
    assert "given: 9 balls" in by_geometry["assumptions"]["bearing_geometry"]
    # the rest is BearingGeometry's defaults, stated from the object the waviness model gets
    stated = by_geometry["assumptions"]["bearing_geometry"]
    assert "radial clearance 10 um, AISI 52100 balls" in stated
    # another bearing moves the rates the lines are searched at
    assert (
        main([*base, "--geometry", "6310:balls=8:ball_diameter=20.64e-3:pitch_diameter=77.5e-3"])
        == 0
    )
    other = json.loads(capsys.readouterr().out)
    assert other["frequencies"]["bpfo"] != pytest.approx(by_name["frequencies"]["bpfo"], rel=0.01)
    for bad, message in (
        ("x:balls=8:ball_diameter=2e-3", "pitch_diameter= is missing"),
        (":balls=8:ball_diameter=2e-3:pitch_diameter=1e-2", "designation is missing"),
        ("x:balls=8:ball_diameter=2e-3:pitch_diameter=1e-2:contact_angle_deg=60", "[0, 45] deg"),
        ("x:balls=8:ball_diameter=2e-2:pitch_diameter=1e-2", "must exceed ball_diameter"),
        ("x:balls=0:ball_diameter=2e-3:pitch_diameter=1e-2", "ball_count = 0 is outside"),
    ):
        assert main(["diagnose", str(outer_race_csv), "--rpm", "1797", "--geometry", bad]) == 2
        assert message in _one_line_error(capsys)


def test_a_folder_with_a_manifest_is_diagnosed_recording_by_recording(
    outer_race_csv, tmp_path, capsys, monkeypatch
):
    """Each listed recording is diagnosed with its own rate, speed and bearing; one that cannot
    be is reported in its row and the rest go on; --report writes a report each and a table."""
    folder = tmp_path / "route"
    (folder / "pump").mkdir(parents=True)
    x = np.loadtxt(outer_race_csv, delimiter=",")[:, 1]
    np.save(folder / "pump" / "de.npy", x)
    np.save(folder / "quiet.npy", np.random.default_rng(2).standard_normal(x.size))
    np.save(folder / "clipped.npy", np.clip(x, -0.1 * x.max(), 0.1 * x.max()))
    pd.DataFrame(
        {
            "file": ["pump/de.npy", "quiet.npy", "clipped.npy"],
            "sampling_rate_hz": 12000,
            "shaft_rpm": 1797,
            "bearing": "6205",
            "fault_location": ["outer", "", ""],
        }
    ).to_csv(folder / "MANIFEST.csv", index=False)
    out = tmp_path / "reports"
    assert main(["diagnose", str(folder), "--report", str(out)]) == 1  # one was refused
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("pump/de.npy: outer race (confidence ")
    assert lines[1].startswith("quiet.npy: healthy")
    assert lines[2].startswith("clipped.npy: not diagnosed: ") and "is clipped" in lines[2]
    table = pd.read_csv(out / "verdicts.csv")
    assert list(table["file"]) == ["pump/de.npy", "quiet.npy", "clipped.npy"]
    assert list(table["verdict"].fillna("-")) == ["outer race", "healthy", "-"]
    assert table["margin_db"].iloc[0] > 0 > table["margin_db"].iloc[1]
    assert table["manifest_label"].iloc[0] == "outer race" and table["error"].notna().tolist() == [
        False,
        False,
        True,
    ]
    assert (out / "pump__de" / "report.md").is_file() and (out / "quiet" / "envelope.png").is_file()
    index = (out / "index.md").read_text()
    assert (
        "| pump/de.npy |  |  | outer race | " in index and "[report](pump__de/report.md)" in index
    )
    assert "| clipped.npy |  |  | not diagnosed: " in index and "nan" not in index
    # the same verdict as the file diagnosed alone
    assert (
        main(
            [
                "diagnose",
                str(folder / "pump" / "de.npy"),
                "--fs",
                "12000",
                "--rpm",
                "1797",
                "--bearing",
                "6205",
                "--json",
            ]
        )
        == 0
    )
    alone = json.loads(capsys.readouterr().out)
    assert main(["diagnose", str(folder), "--json", "--allow-clipping"]) == 0
    batch = json.loads(capsys.readouterr().out)
    assert [d["verdict"] for d in batch][:2] == ["outer race", "healthy"]
    assert batch[0]["candidates"] == alone["candidates"]
    assert batch[0]["assumptions"]["file"] == "pump/de.npy"
    # each object names its recording first, as one not diagnosed does ({"file", "error"}),
    # and what the manifest says of it last
    assert [list(d)[0] for d in batch] == ["file"] * len(batch)
    assert batch[0]["file"] == "pump/de.npy"
    assert {k: v for k, v in batch[0].items() if k not in ("file", "manifest")} == alone | {
        "assumptions": batch[0]["assumptions"]
    }
    assert batch[0]["manifest"] == {
        "bearing": "6205",
        "rpm": 1797.0,
        "fs_hz": 12000.0,
        "manifest_label": "outer race",
    }
    # two processes give the same answers, in the manifest's order
    assert main(["diagnose", str(folder), "--json", "--allow-clipping", "--workers", "2"]) == 0
    assert json.loads(capsys.readouterr().out) == batch
    # a warning raised while a worker diagnoses is shown once by the command, not by each
    # worker (the forked workers inherit this patch)
    import warnings

    import cmtool.commands.analysis as analysis

    diagnose_one = analysis._diagnose_one

    def warning_diagnose_one(*args, **kwargs):
        warnings.warn("a caveat of every recording", UserWarning, stacklevel=2)
        return diagnose_one(*args, **kwargs)

    monkeypatch.setattr(analysis, "_diagnose_one", warning_diagnose_one)
    assert main(["diagnose", str(folder), "--json", "--allow-clipping", "--workers", "2"]) == 0
    assert capsys.readouterr().err.count("a caveat of every recording") == 1
    # the manifest gives rate, speed and bearing: the flags that would contradict it are refused
    for flag in (["--rpm", "1797"], ["--bearing", "6205"], ["--fs", "12000"]):
        assert main(["diagnose", str(folder), *flag]) == 2
        assert "cannot be given with it" in _one_line_error(capsys)


def test_velocity_bands_in_mm_s_when_the_recordings_unit_is_known(tmp_path, capsys):
    """ISO 15242 bands in mm/s: a 1 kHz tone of 1 m/s velocity amplitude reads 707 mm/s."""
    from scipy.io import savemat

    from cmtool.diagnose import diagnose_signal

    fs = 25600.0
    t = np.arange(int(fs)) / fs
    tone = 2 * np.pi * 1000 * np.cos(2 * np.pi * 1000 * t)  # m/s^2; velocity sin(2 pi 1000 t)
    si = diagnose_signal(tone, fs, 1797.0, "6205", unit="m/s^2", waviness=False)
    assert si.velocity_bands_mm_s["medium"] == pytest.approx(1e3 / np.sqrt(2), rel=2e-3)
    in_g = diagnose_signal(tone / 9.80665, fs, 1797.0, "6205", unit="g", waviness=False)
    assert in_g.velocity_bands_mm_s["medium"] == pytest.approx(si.velocity_bands_mm_s["medium"])
    assert (
        in_g.assumptions["unit"] == "g"
        and "unit" not in diagnose_signal(tone, fs, 1797.0, "6205", waviness=False).assumptions
    )
    # the overall vibration, ISO 10816-3's 10-1000 Hz (2-1000 Hz at 600 rpm or less)
    slow = 2 * np.pi * 100 * np.cos(2 * np.pi * 100 * t)  # velocity sin(2 pi 100 t) [m/s]
    for rpm, band in ((1797.0, [10.0, 1000.0]), (600.0, [2.0, 1000.0])):
        overall = diagnose_signal(slow, fs, rpm, "6205", unit="m/s^2", waviness=False)
        assert overall.overall_velocity["band_hz"] == band
        assert overall.overall_velocity["rms_mm_s"] == pytest.approx(1e3 / np.sqrt(2), rel=2e-3)
    assert si.overall_velocity["rms_mm_s"] < 1.0  # the 1 kHz tone lies outside it
    with pytest.raises(ValueError, match="unit = 'mm' is not one of g, m/s"):
        diagnose_signal(tone, fs, 1797.0, "6205", unit="mm")
    # a CWRU-layout file says g: the command line gives mm/s without being told
    savemat(tmp_path / "12k_Drive_End_X.mat", {"X100_DE_time": (tone / 9.80665)[:, None]})
    args = ["diagnose", str(tmp_path / "12k_Drive_End_X.mat"), "--fs", "25600", "--rpm", "1797"]
    assert main([*args, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["velocity_bands_iso15242_mm_s"]["medium"] == pytest.approx(707.1, rel=2e-3)
    assert main(args) == 0
    assert "velocity RMS (ISO 15242 bands, mm/s, the signal in g): low" in capsys.readouterr().out
    np.save(tmp_path / "tone.npy", tone)  # a file that does not say: asked for
    assert main(["diagnose", str(tmp_path / "tone.npy"), *args[2:], "--bearing", "6205"]) == 0
    assert "--unit for mm/s" in capsys.readouterr().out


def test_a_velocity_record_is_diagnosed_as_its_acceleration_is(tmp_path, capsys):
    """A velocity transducer's record (mm/s, in/s; --unit, a CSV's bracketed unit, a
    manifest's unit): its derivative is diagnosed, so an outer-race pit's record gives the
    verdict, confidence and ISO bands its acceleration gives. Before, mm/s was no unit: the
    record's integral was reported as its velocity bands, in "signal unit x s"."""
    from scipy import signal as sp_signal

    from cmtool.diagnose import diagnose_signal
    from generators import bearing, characteristic_frequencies

    fs, n = 12000.0, 24000
    bpfo = characteristic_frequencies(bearing("6205"), 1797 / 60).bpfo
    rng = np.random.default_rng(8)
    times = np.arange(0.0, n / fs, 1 / bpfo)
    impacts = np.zeros(n)
    impacts[
        np.clip(((times + rng.normal(0.0, 0.01 / bpfo, times.size)) * fs).astype(int), 0, n - 1)
    ] = 50.0
    acceleration = sp_signal.lfilter(*sp_signal.iirpeak(3000.0, 15.0, fs), impacts)
    acceleration += rng.standard_normal(n) + 3.0 * np.sin(2 * np.pi * 29.95 * np.arange(n) / fs)
    acceleration -= acceleration.mean()
    # the velocity [mm/s] whose derivative it is (m/s^2 -> mm/s)
    f = np.fft.rfftfreq(n, 1 / fs)
    spec = np.fft.rfft(acceleration)
    spec[1:] /= 2j * np.pi * f[1:]
    spec[0] = 0.0
    velocity = 1e3 * np.fft.irfft(spec, n)
    ours = diagnose_signal(acceleration, fs, 1797.0, "6205", unit="m/s^2", waviness=False)
    given = diagnose_signal(velocity, fs, 1797.0, "6205", unit="mm/s", waviness=False)
    assert ours.verdict == "outer race" and given.verdict == ours.verdict
    assert given.confidence == pytest.approx(ours.confidence, abs=0.01)
    for band, value in ours.velocity_bands_mm_s.items():
        assert given.velocity_bands_mm_s[band] == pytest.approx(value, rel=1e-3), band
    assert given.overall_velocity["rms_mm_s"] == pytest.approx(
        ours.overall_velocity["rms_mm_s"], rel=1e-3
    )
    assert "its derivative [mm/s/s] is diagnosed" in given.assumptions["quantity"]
    inches = diagnose_signal(velocity / 25.4, fs, 1797.0, "6205", unit="in/s", waviness=False)
    assert inches.velocity_bands_mm_s["low"] == pytest.approx(given.velocity_bands_mm_s["low"])
    # the command line: a CSV's "[mm/s]" column, --unit, a manifest's unit column
    path = tmp_path / "v.csv"
    path.write_text(
        "t [s],v [mm/s]\n" + "\n".join(f"{k / fs:.8f},{v:.6f}" for k, v in enumerate(velocity))
    )
    np.save(tmp_path / "v.npy", velocity)
    argv = ["--rpm", "1797", "--bearing", "6205", "--json"]
    for file, extra in (("v.csv", []), ("v.npy", ["--fs", "12000", "--unit", "mm/s"])):
        assert main(["diagnose", str(tmp_path / file), *argv, *extra]) == 0
        d = json.loads(capsys.readouterr().out)
        assert d["verdict"] == "outer race" and d["assumptions"]["unit"] == "mm/s", file
        low = d["velocity_bands_iso15242_mm_s"]["low"]
        assert low == pytest.approx(ours.velocity_bands_mm_s["low"], rel=1e-3), file
    (tmp_path / "MANIFEST.csv").write_text(
        "file,sampling_rate_hz,shaft_rpm,bearing,unit\nv.npy,12000,1797,6205,mm/s\n"
    )
    assert main(["diagnose", str(tmp_path), "--json"]) == 0
    (d,) = json.loads(capsys.readouterr().out)
    assert d["verdict"] == "outer race" and d["assumptions"]["unit"] == "mm/s"
    # the realism gauge and cmtool bench read it as its acceleration too (what they compare
    # it with, simulations and detectors, are accelerations)
    import features
    from cmtool.realism import recording_segments

    (segment,) = recording_segments(tmp_path, 2.0)["signal"]
    np.testing.assert_allclose(segment, features.acceleration_from_velocity(velocity, fs))
    with pytest.raises(ValueError, match="unit = 'ips' is not one of g, m/s\\^2, m/s2, mm/s"):
        diagnose_signal(velocity, fs, 1797.0, "6205", unit="ips")


def test_dated_recordings_of_a_machine_give_its_trend(tmp_path, capsys):
    """The manifest's time and machine: per-fault margins in verdicts.csv and a trend per
    machine, the margin of a growing outer-race fault rising through the threshold."""
    from scipy import signal as sp_signal

    from cmtool.io import RecordingError
    from cmtool.manifest import read_manifest
    from generators import bearing, characteristic_frequencies

    rng = np.random.default_rng(3)
    fs, n = 12000.0, 24000
    bpfo = characteristic_frequencies(bearing("6205"), 1797 / 60).bpfo
    folder = tmp_path / "route"
    folder.mkdir()
    rows = []
    for machine in ("pump", "fan"):
        for month, amplitude in enumerate((0.0, 1.0, 4.0), start=1):
            times = np.arange(0.0, n / fs, 1 / bpfo)
            times = times + rng.normal(0.0, 0.01 / bpfo, times.size)  # slip: 1 % jitter
            x = np.zeros(n)
            x[np.clip((times * fs).astype(int), 0, n - 1)] = amplitude if machine == "pump" else 0
            x = sp_signal.lfilter(*sp_signal.iirpeak(3000.0, 15.0, fs), x)
            np.save(folder / f"{machine}{month}.npy", x + 0.05 * rng.standard_normal(n))
            rows.append(
                {
                    "file": f"{machine}{month}.npy",
                    "sampling_rate_hz": fs,
                    "shaft_rpm": 1797,
                    "bearing": "6205",
                    "machine": machine,
                    "time": f"2026-{month:02d}-01T08:00",
                    # each recording against its machine's first (a baseline of the same
                    # machine): reported beside the verdict, never weighed in it
                    "baseline": f"{machine}1.npy",
                }
            )
    pd.DataFrame(rows).to_csv(folder / "MANIFEST.csv", index=False)
    out = tmp_path / "out"
    assert main(["diagnose", str(folder), "--report", str(out), "--unit", "g"]) == 0
    printed = capsys.readouterr().out
    assert "trend_pump.png" in printed and "trend_fan.png" in printed
    assert (out / "trend_pump.png").stat().st_size > 10000
    assert "![trend_pump](trend_pump.png)" in (out / "index.md").read_text()
    table = pd.read_csv(out / "verdicts.csv", parse_dates=["time"])
    pump = table[table["machine"] == "pump"].sort_values("time")
    margins = pump["outer_race_margin_db"].to_numpy()
    assert margins[0] < 0 < margins[1] < margins[2], margins
    assert list(pump["verdict"]) == ["healthy", "outer race", "outer race"]
    assert (table["velocity_unit"] == "mm/s").all()
    assert (table[table["machine"] == "fan"]["verdict"] == "healthy").all()
    # the ISO 15242 bands' change in dB against the baseline, the high band (where the
    # impacts ring) rising with the fault
    frame = pd.read_csv(folder / "MANIFEST.csv")
    change = table.set_index("file")["velocity_high_change_db"]
    assert change["pump1.npy"] == 0.0 and 0.0 < change["pump2.npy"] < change["pump3.npy"]
    assert abs(change["fan3.npy"]) < 1.0 and (table["baseline"] == frame["baseline"]).all()
    # and each fault's margin in the baseline: every pump recording's is pump1's own margin
    rows = table.set_index("file")
    for fault in ("outer_race", "inner_race", "ball"):
        theirs = rows.loc[["pump1.npy", "pump2.npy", "pump3.npy"], f"{fault}_baseline_margin_db"]
        assert (theirs == rows.loc["pump1.npy", f"{fault}_margin_db"]).all(), fault
    frame.loc[0, "baseline"] = "gone.npy"
    frame.to_csv(folder / "MANIFEST.csv", index=False)
    with pytest.raises(FileNotFoundError, match=r"line 2 \(pump1.npy\): baseline .*gone.npy"):
        read_manifest(folder)
    # a time that is not one is named with its line
    frame = pd.read_csv(folder / "MANIFEST.csv")
    frame.loc[0, "baseline"] = None
    frame.loc[2, "time"] = "last tuesday"
    frame.to_csv(folder / "MANIFEST.csv", index=False)
    with pytest.raises(RecordingError, match=r"line 4 \(pump3.npy\): time = 'last tuesday'"):
        read_manifest(folder)


def test_training_on_one_label_is_refused_before_any_feature(small_dataset):
    from cmtool.classifier import train

    healthy = small_dataset[small_dataset["label"] == "healthy"]
    with pytest.raises(ValueError, match=r"have 1 label\(s\) \(healthy; .*needs at least two"):
        train(healthy, recipe=None)


def test_a_machine_whose_recordings_mix_units_gets_no_trend_and_is_told(tmp_path, capsys):
    """A CWRU-layout file (g) and a bare array (unit unknown) of one machine: no trend drawn
    from mixed units, a line on stderr says so, and --unit makes them one."""
    from scipy.io import savemat

    folder = tmp_path / "route"
    folder.mkdir()
    x = np.random.default_rng(6).standard_normal(24000)
    savemat(folder / "12k_Drive_End_A.mat", {"X100_DE_time": x[:, None]})
    np.save(folder / "b.npy", x)
    pd.DataFrame(
        {
            "file": ["12k_Drive_End_A.mat", "b.npy"],
            "sampling_rate_hz": 12000,
            "shaft_rpm": 1797,
            "machine": "pump",
            "time": ["2026-01-01", "2026-02-01"],
        }
    ).to_csv(folder / "MANIFEST.csv", index=False)
    out = tmp_path / "out"
    assert main(["diagnose", str(folder), "--report", str(out)]) == 0
    assert "no trend of pump: their velocity units differ" in capsys.readouterr().err
    assert not (out / "trend.png").exists()
    assert main(["diagnose", str(folder), "--report", str(out), "--unit", "g"]) == 0
    capsys.readouterr()
    assert (out / "trend.png").is_file()
    # or the manifest says it, row by row
    (out / "trend.png").unlink()
    frame = pd.read_csv(folder / "MANIFEST.csv")
    frame["unit"] = ["", "m/s^2"]
    frame.to_csv(folder / "MANIFEST.csv", index=False)
    assert main(["diagnose", str(folder), "--report", str(out)]) == 0
    capsys.readouterr()
    table = pd.read_csv(out / "verdicts.csv")
    assert (table["velocity_unit"] == "mm/s").all() and (out / "trend.png").is_file()
    # the same samples read as g and as m/s^2: 9.81 times apart
    low = table["velocity_low"].to_numpy()
    assert low[0] / low[1] == pytest.approx(9.80665, rel=1e-9)
    frame["unit"] = ["", "mm"]
    frame.to_csv(folder / "MANIFEST.csv", index=False)
    assert main(["diagnose", str(folder)]) == 2
    assert "line 3 (b.npy): unit = 'mm' is not one of g" in _one_line_error(capsys)
    assert json.loads((out / "12k_Drive_End_A" / "diagnosis.json").read_text())["verdict"]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["train", "DATA", "--out", "m.skops", "--seed", "-1"], "--seed: -1 is outside"),
        (["train", "DATA", "--out", "m.skops", "--seed", "4294967296"], "[0, 4294967295]"),
        (["train", "DATA", "--out", "m.skops", "--min-fault-snr", "nan"], "not a finite number"),
        (["train", "DATA", "--out", "m.skops", "--min-fault-snr", "inf"], "not a finite number"),
        (["simulate", "--seed", "-3"], "--seed: -3 is outside the allowed range"),
        (["fidelity", "--f-max", "-5"], "--f-max: -5 is outside the allowed range (0, inf)"),
        (["fidelity", "--f-max", "nan"], "--f-max: 'nan' is not a finite number"),
    ],
)
def test_seeds_and_numbers_out_of_range_are_usage_errors(argv, message, capsys):
    """Found by probing the command line: a negative seed failed in numpy or scikit-learn
    (after the features) without naming --seed; --min-fault-snr nan or inf trained a model
    filtering nothing or everything; fidelity ran with --f-max -5."""
    with pytest.raises(SystemExit) as stop:
        main(argv)
    assert stop.value.code == 2
    assert message in capsys.readouterr().err


def test_fidelity_names_a_list_entry_that_is_no_number_and_f_max_above_nyquist(capsys):
    assert main(["fidelity", "--levels", "shaft", "--steps", "1e-5,abc"]) == 2
    assert "--steps '1e-5,abc': 'abc' is not a number" in _one_line_error(capsys)
    from cmtool.fidelity import fidelity_study
    from generators import OperatingCondition, ParameterError, SimulationSettings, bearing

    with pytest.raises(ParameterError, match=r"f_max = 7000 Hz .* \(0, 6000\] Hz"):
        fidelity_study(
            bearing("6205"),
            OperatingCondition.from_rpm(1800, 500.0),
            settings=SimulationSettings(fs=12000.0, duration=0.05),
            f_max=7000.0,
        )


def test_train_checks_its_seed_and_fault_snr_floor_before_any_feature(small_dataset):
    from cmtool.classifier import train

    with pytest.raises(ValueError, match=r"min_fault_snr_db = nan is not a finite number"):
        train(small_dataset, recipe=None, min_fault_snr_db=float("nan"))
    with pytest.raises(ValueError, match=r"random_state = -1 is outside the allowed range"):
        train(small_dataset, recipe=None, random_state=-1)


def test_a_geometry_given_in_millimetres_is_told_the_unit(capsys):
    """A maker's table gives diameters in mm; --geometry takes m: the error says so."""
    spec = "6205:balls=9:ball_diameter=7.94:pitch_diameter=39.04"
    assert main(["frequencies", "--geometry", spec, "--rpm", "1800"]) == 2
    err = _one_line_error(capsys)
    assert "ball_diameter = 7.94 m is outside" in err and "diameters are in m" in err
    assert (
        main(
            [
                "frequencies",
                "--geometry",
                "x:balls=0:ball_diameter=8e-3:pitch_diameter=0.04",
                "--rpm",
                "1800",
            ]
        )
        == 2
    )
    assert "diameters are in m" not in _one_line_error(capsys)  # a count error: no hint


def test_a_file_of_several_channels_says_which_one_was_diagnosed(tmp_path, capsys):
    """A stereo WAV, a channels x samples array, a CSV of two columns: without --channel the
    first is diagnosed, and the output says so (it was stated only as "channel first")."""
    from scipy.io import wavfile

    rng = np.random.default_rng(8)
    wavfile.write(
        tmp_path / "two.wav", 12000, (3000 * rng.standard_normal((24000, 2))).astype(np.int16)
    )
    np.save(tmp_path / "two.npy", rng.standard_normal((2, 24000)))
    pd.DataFrame({"ax": rng.standard_normal(24000), "ay": rng.standard_normal(24000)}).to_csv(
        tmp_path / "two.csv", index=False
    )
    rate = {"two.wav": [], "two.npy": ["--fs", "12000"], "two.csv": ["--fs", "12000"]}
    for name, extra in rate.items():
        argv = ["diagnose", str(tmp_path / name), "--rpm", "1800", "--bearing", "6205", *extra]
        assert main([*argv, "--json"]) == 0
        data = json.loads(capsys.readouterr().out)
        first = "ax" if name.endswith(".csv") else "0 (the first of 2)"
        assert data["assumptions"]["channel"] == first
        assert f"{name} holds 2 channels; channel {first} was diagnosed" in " ".join(
            data["warnings"]
        )
        assert main([*argv, "--json", "--channel", "1"]) == 0
        data = json.loads(capsys.readouterr().out)
        assert data["assumptions"]["channel"] in ("1", "ay")
        assert not any("channels;" in w for w in data["warnings"])


@pytest.mark.parametrize(
    ("argv", "kind", "message"),
    [
        (["train", "SMALL", "--out", "OUT"], "dir", "is a folder; give a model file"),
        (["evaluate", "MODEL", "SMALL", "--out", "OUT"], "file", "is a file; give a folder"),
        (["realism", "SMALL", "SMALL", "--out", "OUT"], "file", "is a file; give a folder"),
        (["fidelity", "--levels", "shaft", "--out", "OUT"], "dir", "is a folder; give a CSV"),
        (["fidelity", "--levels", "shaft", "--plot", "OUT"], "dir", "is a folder; give a PNG"),
        (["generate", "RECIPE", "--out", "OUT"], "file", "is a file; give a folder"),
        (["demo", "--out", "OUT"], "file", "is a file; give a folder"),
        (["bench", "SMALL", "--out", "OUT"], "file", "is a file; give a folder"),
    ],
)
def test_an_output_of_the_wrong_kind_is_refused_before_any_work(
    argv, kind, message, tmp_path, capsys
):
    """Found by probing: train --out DIR failed with a traceback after training, fidelity
    --out DIR after the whole study, evaluate/realism/generate/demo --out FILE with
    FileExistsError or NotADirectoryError tracebacks."""
    out = tmp_path / "out"
    out.mkdir() if kind == "dir" else out.write_text("keep me")
    names = {
        "OUT": str(out),
        "SMALL": str(REPO / "datasets" / "small"),
        "MODEL": str(tmp_path / "absent.skops"),
        "RECIPE": str(REPO / "datasets" / "small.toml"),
    }
    assert main([names.get(a, a) for a in argv]) == 2
    assert message in _one_line_error(capsys)
    assert out.is_dir() if kind == "dir" else out.read_text() == "keep me"


def test_fidelity_refuses_a_plot_format_before_the_study(tmp_path, capsys):
    """Before: matplotlib's "Format 'txt' is not supported" after the whole study."""
    plot = tmp_path / "study.txt"
    argv = ["fidelity", "--levels", "shaft", "--steps", "1e-5", "--plot", str(plot)]
    assert main(argv) == 2
    assert "--plot" in (said := _one_line_error(capsys)) and "must end in one of .png" in said
    assert not plot.exists()


@pytest.mark.parametrize(
    ("given", "said"),
    [
        ({"baseline_fs": -1.0}, r"baseline_fs = -1\.0 Hz is outside the allowed range"),
        ({"baseline_fs": 0.0}, r"baseline_fs = 0\.0 Hz is outside the allowed range"),
        ({"baseline": "short"}, r"baseline has 10 samples: its velocity bands need at least 16"),
        ({"baseline": "two"}, r"baseline has shape \(2, 50\): give one record"),
    ],
)
def test_a_baseline_that_cannot_be_read_is_refused_by_its_own_name(rng, given, said):
    """diagnose_signal names the baseline and its rate, not the record's ``x`` and ``fs``
    (before: "fs = -1.0 Hz", "x has 10 samples"; a rate of 0 was taken as the record's)."""
    from cmtool.diagnose import diagnose_signal

    x = rng.standard_normal(12000)
    baseline = {"short": x[:10], "two": np.ones((2, 50))}.get(given.get("baseline"), x)
    rate = given.get("baseline_fs")
    with pytest.raises(ValueError, match=said):
        diagnose_signal(
            x, 12000.0, 1797, "6205", waviness=False, baseline=baseline, baseline_fs=rate
        )


def test_the_python_api_refuses_worker_counts_and_folds_before_any_work(small_dataset, tmp_path):
    """train, evaluate, run_bench and generate_dataset name a worker count that is no
    positive integer, and train a fold count outside [2, operating points], before they
    compute anything (before: joblib's "n_jobs == 0 has no meaning", a silent 0 or -1 taken
    as one thread, n_splits = 0 taken as the default, scikit-learn's messages after the
    features). The small dataset has 12 operating points."""
    from cmtool.bench import run_bench
    from cmtool.classifier import evaluate, train
    from cmtool.datasets import generate_dataset
    from generators import ParameterError

    repo = Path(__file__).resolve().parents[2]
    refused = {
        r"workers = 0 is outside the allowed range \[1, inf\]": [
            lambda: train(small_dataset, workers=0),
            lambda: evaluate({"pipeline": None}, small_dataset, workers=0),
            lambda: run_bench(repo / "datasets" / "small", workers=0),
            lambda: generate_dataset(repo / "datasets" / "small.toml", tmp_path / "d", workers=0),
        ],
        r"workers = 2\.5 is not an integer": [
            lambda: generate_dataset(repo / "datasets" / "small.toml", tmp_path / "d", workers=2.5)
        ],
        r"n_splits = 0 is outside the allowed range \[2, 12\]": [
            lambda: train(small_dataset, n_splits=0)
        ],
        r"n_splits = 13 is outside the allowed range \[2, 12\]": [
            lambda: train(small_dataset, n_splits=13)
        ],
    }
    for said, calls in refused.items():
        for call in calls:
            with pytest.raises(ParameterError, match=said):
                call()
    assert not (tmp_path / "d").exists()


def test_train_and_the_realism_gauge_name_the_columns_a_table_lacks(small_dataset):
    """Before: KeyError 'label' (or 'operating_point_id', 'fs_hz', 'group'), and an
    AttributeError for a table that is no DataFrame. train reads TRAINING_COLUMNS."""
    from cmtool.classifier import TRAINING_COLUMNS, train
    from cmtool.realism import realism

    with pytest.raises(ValueError, match=r"frame has no column 'label' \(cmtool\.datasets"):
        train(small_dataset.drop(columns=["label"]))
    with pytest.raises(ValueError, match=r"frame has no columns 'operating_point_id', 'fs_hz'"):
        train(small_dataset.drop(columns=["fs_hz", "operating_point_id"]))
    with pytest.raises(ValueError, match=r"frame is a list, not a DataFrame"):
        train([1.0, 2.0])
    with pytest.raises(ValueError, match=r"measured has no column 'group' \(recording_segments"):
        realism(small_dataset, small_dataset)
    assert set(TRAINING_COLUMNS) <= set(small_dataset.columns)


def test_train_and_evaluate_name_a_signal_too_short_for_the_fault_rates(
    small_dataset, small_bundle
):
    """The diagnosis's bound (20 periods of the slowest fault rate) for a model's signals.
    Before, train stopped with the rule's message, naming no signal, and evaluate scored
    0.016 s records (a 64 Hz resolution for lines 1.4 % apart) without a word."""
    from cmtool.classifier import evaluate, train

    frame = small_dataset.copy()
    frame.at[2, "signal"] = frame.at[2, "signal"][:1000]  # 0.16 s; 0.28 s needed at 1200 rpm
    who = frame.at[2, "id"]
    assert frame.at[2, "rpm"] == 1200
    message = rf"signal '{who}' \(row 2\) is 0.156 s long \(1000 samples at 6400 Hz; 1 of 192"
    with pytest.raises(ValueError, match=message):
        train(frame)
    with pytest.raises(ValueError, match=message + r".* at least 20 periods .*: 0.279 s"):
        evaluate(small_bundle, frame)


def test_evaluate_on_one_class_counts_in_the_models_classes(small_dataset, small_bundle):
    """Healthy signals only: the confusion matrix has every class the model knows (zeros
    where none), not one cell, and scikit-learn's warning about a single label is gone."""
    import warnings

    from cmtool.classifier import evaluate

    healthy = small_dataset[small_dataset["label"] == "healthy"].head(8)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = evaluate(small_bundle, healthy.reset_index(drop=True))
    assert result["labels"] == ["ball", "healthy", "inner", "outer"]
    confusion = np.array(result["confusion"])
    assert confusion.shape == (4, 4) and confusion.sum() == 8
    assert confusion[[0, 2, 3]].sum() == 0


def test_train_and_bench_name_a_signal_that_holds_nan(small_dataset, tmp_path):
    """A dataset edited after it was written (cmtool generate writes no NaN: a diverging run
    is a recorded failure). Before: "x contains 6400 non-finite values", naming no signal."""
    import pyarrow as pa
    import pyarrow.parquet as pq

    from cmtool.bench import run_bench
    from cmtool.classifier import train

    frame = small_dataset.copy()
    frame.at[5, "signal"] = np.where(np.arange(6400) == 7, np.inf, frame.at[5, "signal"])
    who = frame.at[5, "id"]
    with pytest.raises(ValueError, match=rf"frame: signal '{who}' \(row 5\) has 1 non-finite"):
        train(frame)
    small = Path(__file__).resolve().parents[2] / "datasets" / "small" / "data"
    table = pq.read_table(small / "part-00001.parquet")
    signals = table.column("signal").to_pylist()
    signals[2][100] = float("nan")
    column = pa.array(signals, type=table.schema.field("signal").type)
    (tmp_path / "data").mkdir()
    pq.write_table(
        table.set_column(table.schema.get_field_index("signal"), "signal", column),
        tmp_path / "data" / "part-00001.parquet",
    )
    who = table.column("id")[2].as_py()
    with pytest.raises(ValueError, match=rf"signal '{who}' \(row 2\) has 1 non-finite values"):
        run_bench(tmp_path, allow_incomplete=True)


@pytest.mark.parametrize(
    ("argv", "warned"),
    [
        (["--fs", "200", "--duration", "0.2"], "lie at or above fs / 2 = 100 Hz"),
        (["--waviness", "ball:order=5:amplitude=1e-6"], "odd order 5 does not change"),
        (["--waviness", "ball:order=5:amplitude=1e-6", "--scene", "full"], None),
    ],
)
def test_cmtool_simulate_says_what_its_record_cannot_show(tmp_path, capsys, argv, warned):
    out = tmp_path / "s.parquet"
    assert main(["simulate", "--duration", "0.05", "--out", str(out), *argv]) == 0
    err = capsys.readouterr().err
    if warned is None:
        assert "warning" not in err, err
    else:
        assert "cmtool simulate: warning:" in err and warned in err, err


def test_cmtool_generate_says_what_a_recipes_signals_cannot_show(tmp_path, capsys):
    text = (REPO / "datasets" / "small.toml").read_text()
    text = text.replace("count = 48", "count = 1").replace("fs_hz = 6400", "fs_hz = 400")
    text = text.replace("order = [2, 4, 6]", "order = [3]")
    (tmp_path / "recipe.toml").write_text(text)
    argv = ["generate", str(tmp_path / "recipe.toml"), "--out", str(tmp_path / "d")]
    assert main([*argv, "--workers", "1"]) == 0
    err = capsys.readouterr().err
    assert "warning: recipe bearing 6205: fs = 400 Hz: at 2400 rpm" in err, err
    assert "warning: recipe conditions[3] ('ball'): ball waviness of odd order 3" in err, err


def test_a_simulated_files_radial_load_sets_the_waviness_prediction(tmp_path, capsys):
    """A `cmtool simulate` file holds the load it was simulated at: without --load the healthy
    model's lines for race waviness are predicted about that load (0.7-1.4 x, as for a load
    given) and the assumptions say it is the file's; --load wins, with a warning where it
    differs; a file without one keeps the assumed 500 N (125-2000 N)."""
    sim = tmp_path / "sim.parquet"
    argv = ["simulate", "--duration", "0.5", "--rpm", "1800", "--load", "1500", "--out", str(sim)]
    assert main(argv) == 0
    capsys.readouterr()

    def said(path, *extra):
        assert main(["diagnose", str(path), "--json", *extra]) == 0
        return json.loads(capsys.readouterr().out)

    d = said(sim)
    assert d["verdict"] == "healthy"
    assert "1050-2100 N (given 1500 N)" in d["assumptions"]["waviness_reference"]
    assert d["assumptions"]["load_n"].startswith("1500 N, the file's")
    d = said(sim, "--load", "500")
    assert "350-700 N (given 500 N)" in d["assumptions"]["waviness_reference"]
    assert "--load 500 N differs from the file's 1500 N; using --load" in d["warnings"]
    assert "load_n" not in d["assumptions"]
    from scipy.io import wavfile

    x = np.random.default_rng(3).standard_normal(12000)
    wavfile.write(tmp_path / "rec.wav", 12000, x.astype(np.float32))
    d = said(tmp_path / "rec.wav", "--rpm", "1800", "--bearing", "6205")
    assert "125-2000 N (assumed; --load 500 N)" in d["assumptions"]["waviness_reference"]


def test_a_rate_or_speed_given_against_the_files_own_is_warned_of(tmp_path, capsys):
    """--fs and --rpm win over the file's, with a warning where they differ; a rate read
    from a CSV's time column written to microseconds does not differ from the one it means."""
    from scipy.io import wavfile

    x = np.random.default_rng(9).standard_normal(24000)
    wavfile.write(tmp_path / "rec.wav", 12000, x.astype(np.float32))
    argv = ["diagnose", str(tmp_path / "rec.wav"), "--bearing", "6205", "--json"]

    def said(*extra):
        assert main([*argv, "--rpm", "1797", *extra]) == 0
        return json.loads(capsys.readouterr().out)

    d = said("--fs", "48000")
    assert d["assumptions"]["fs_hz"] == 48000.0
    assert "--fs 48000 Hz differs from the file's 12000 Hz; using --fs" in d["warnings"]
    assert not any("differs" in w for w in said("--fs", "12000")["warnings"])
    # 0.2 s: the last time written 3.3e-7 s off, the rate 1.7e-6 off the one meant
    times = "\n".join(f"{k / 12000:.6f},{v:.6f}" for k, v in enumerate(x[:2400]))
    (tmp_path / "rec.csv").write_text("time,acc\n" + times)
    argv[1] = str(tmp_path / "rec.csv")
    assert not any("differs" in w for w in said("--fs", "12000")["warnings"])
    # a simulated file holds its speed
    sim = tmp_path / "sim.parquet"
    assert main(["simulate", "--duration", "0.5", "--rpm", "1800", "--out", str(sim)]) == 0
    capsys.readouterr()
    argv[1] = str(sim)
    assert "--rpm 1797 rpm differs from the file's 1800 rpm; using --rpm" in said()["warnings"]
    # a folder: the manifest's rate against the file's, in verdicts.csv
    folder = tmp_path / "route"
    folder.mkdir()
    shutil.copy(tmp_path / "rec.wav", folder / "rec.wav")
    (folder / "MANIFEST.csv").write_text("file,sampling_rate_hz,shaft_rpm\nrec.wav,48000,1797\n")
    assert main(["diagnose", str(folder), "--report", str(tmp_path / "out")]) == 0
    table = pd.read_csv(tmp_path / "out" / "verdicts.csv")
    assert (
        "the manifest's sampling_rate_hz 48000 Hz differs from the file's 12000 Hz"
        in (table.loc[0, "warnings"])
    )


def test_the_speed_from_a_tacho_channel(tmp_path, capsys):
    """An outer-race train at 1750 rpm recorded with its key-phasor; --rpm says 1797 (a
    nameplate's 2.7 % off). With --tacho the fault rates come from the pulses, the speed
    is stated and --rpm's is warned of; the tacho never stands in for the vibration."""

    from generators import bearing, characteristic_frequencies

    fs, n, rpm = 12000.0, 24000, 1750.0
    t = np.arange(n) / fs
    bpfo = characteristic_frequencies(bearing("6205"), rpm / 60).bpfo
    rng = np.random.default_rng(5)
    x = ringing_impact_train(bpfo, fs, n, rng)
    x = x + 0.05 * rng.standard_normal(n)
    tacho = np.where((rpm / 60 * t) % 1.0 < 0.05, 5.0, 0.0)
    path = tmp_path / "rec.csv"
    pd.DataFrame({"acc [g]": x, "key [V]": tacho}).to_csv(path, index=False)
    argv = ["diagnose", str(path), "--fs", "12000", "--bearing", "6205", "--rpm", "1797"]
    assert main([*argv, "--tacho", "1", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["verdict"] == "outer race"
    assert d["assumptions"]["rpm"] == pytest.approx(rpm, rel=1e-4)
    assert d["assumptions"]["speed_source"] == "given"
    assert d["assumptions"]["speed_measured"].startswith("tacho channel 1: 58 pulses at 1 per")
    assert (
        "--rpm 1797 rpm is 2.7 % from the tacho's 1750.0 rpm; using the tacho's" in (d["warnings"])
    )
    assert main([*argv, "--tacho", "1"]) == 0
    assert "1750.03 rpm (from the tacho channel 1: 58 pulses" in capsys.readouterr().out
    # the channel diagnosed is no tacho; a folder's speeds are its manifest's
    assert main([*argv, "--tacho", "0"]) == 2
    assert "tacho channel 0 is the channel diagnosed" in capsys.readouterr().err
    # another vibration channel given as the tacho (a CWRU file's fan end): refused
    pd.DataFrame({"acc": x, "fan end": rng.standard_normal(n)}).to_csv(path, index=False)
    assert main([*argv, "--tacho", "1"]) == 2
    assert "no tachometer's pulse train (a vibration's channel?" in capsys.readouterr().err
    assert main(["diagnose", str(tmp_path), "--tacho", "1"]) == 2
    assert "--tacho reads one recording's speed" in capsys.readouterr().err


def test_order_tracking_keeps_a_drifting_machines_fault_lines(tmp_path, capsys):
    """Outer-race impacts at a fixed order of a shaft ramping 25 -> 33 Hz over 4 s (1 %
    jitter in angle): read at the mean speed the lines smear over +/-14 % and the rule
    calls it healthy; resampled to constant speed (--order-track) the fault stands out. A
    record of noise stays healthy either way."""
    from scipy import signal as sp_signal

    from generators import bearing, characteristic_frequencies

    fs, seconds = 12000.0, 4.0
    t = np.arange(int(seconds * fs)) / fs
    phase = np.cumsum(25.0 + 2.0 * t) / fs
    order = characteristic_frequencies(bearing("6205"), 1.0).bpfo  # BPFO per shaft Hz
    rng = np.random.default_rng(5)
    k = np.arange(0, phase[-1] * order)
    times = np.interp((k + rng.normal(0.0, 0.01, k.size)) / order, phase, t)
    impacts = np.zeros(t.size)
    impacts[np.clip((times * fs).astype(int), 0, t.size - 1)] = 1.0
    x = sp_signal.lfilter(*sp_signal.iirpeak(3000.0, 15.0, fs), impacts)
    noise = 0.05 * rng.standard_normal(t.size)
    tacho = np.where(phase % 1.0 < 0.05, 5.0, 0.0)
    verdicts = {}
    for name, signal in (("fault", x + noise), ("noise", noise)):
        path = tmp_path / f"{name}.csv"
        pd.DataFrame({"acc": signal, "tacho": tacho}).to_csv(path, index=False)
        for extra in ([], ["--order-track"]):
            argv = ["diagnose", str(path), "--fs", "12000", "--bearing", "6205", "--json"]
            assert main([*argv, "--tacho", "1", *extra]) == 0
            d = json.loads(capsys.readouterr().out)
            verdicts[name, bool(extra)] = d["verdict"]
            if extra:
                assert (
                    "; order-tracked: resampled to a constant" in d["assumptions"]["speed_measured"]
                )
            else:
                assert any("order tracking (--order-track" in w for w in d["warnings"])
    assert verdicts == {
        ("fault", False): "healthy",
        ("fault", True): "outer race",
        ("noise", False): "healthy",
        ("noise", True): "healthy",
    }
    assert main(["diagnose", str(tmp_path / "noise.csv"), "--fs", "12000", "--order-track"]) == 2
    assert "--order-track needs --tacho" in capsys.readouterr().err
    # a folder: each row's tacho_channel, pulses_per_rev and order_track
    rows = "file,sampling_rate_hz,shaft_rpm,tacho_channel,pulses_per_rev,order_track\n"
    rows += "fault.csv,12000,1800,tacho,1,true\nnoise.csv,12000,1800,tacho,,\n"
    (tmp_path / "MANIFEST.csv").write_text(rows)
    assert main(["diagnose", str(tmp_path), "--report", str(tmp_path / "out")]) == 0
    capsys.readouterr()
    table = pd.read_csv(tmp_path / "out" / "verdicts.csv").set_index("file")
    assert list(table["verdict"]) == ["outer race", "healthy"]
    assert table["rpm"].to_numpy() == pytest.approx(60 * 29.0, rel=2e-3)  # the tacho's mean
    assert "shaft_rpm 1800 rpm is 3.4 % from the tacho's" in table.loc["fault.csv", "warnings"]
    assert "order tracking (--order-track" in table.loc["noise.csv", "warnings"]
    # cmtool bench and the realism gauge read the folder's speeds as diagnose does: the
    # tacho's, the fault's record order-tracked (they read shaft_rpm, 1800, and the smear)
    from cmtool.bench import run_bench
    from cmtool.realism import recording_segments

    labelled = rows.replace("order_track\n", "order_track,fault_location\n")
    labelled = labelled.replace(",true\n", ",true,outer\n").replace(",,\n", ",,,normal\n")
    (tmp_path / "MANIFEST.csv").write_text(labelled)
    bench = run_bench(tmp_path, detectors=[]).set_index(["detector", "id"])
    assert bench.loc[("envelope", "fault.csv"), "verdict"] == "outer race"
    assert bench.loc[("envelope", "noise.csv"), "verdict"] == "healthy"
    segments = recording_segments(tmp_path, 1.0)
    assert segments["shaft_frequency_hz"].to_numpy() == pytest.approx(29.0, rel=2e-3)
    # a row whose tacho channel is its own vibration's is that row's error, not the
    # folder's (it stopped the whole folder, no verdicts written)
    (tmp_path / "MANIFEST.csv").write_text(
        rows.replace("fault.csv,12000,1800,tacho", "fault.csv,12000,1800,acc")
    )
    assert main(["diagnose", str(tmp_path), "--json"]) == 1
    fault, noise = json.loads(capsys.readouterr().out)  # in the manifest's order
    assert fault["file"] == "fault.csv"
    assert "tacho channel acc is the channel diagnosed" in fault["error"]
    assert noise["verdict"] == "healthy"
    # each object says what the manifest says of its recording, diagnosed or not
    assert fault["verdict"] is None
    for obj in (fault, noise):
        assert obj["manifest"] == {"bearing": "6205", "rpm": 1800.0, "fs_hz": 12000.0}
    for cells, said in (
        ("fault.csv,12000,1800,tacho,0,true", "pulses_per_rev = '0' is not an integer"),
        ("fault.csv,12000,1800,tacho,1,maybe", "order_track = 'maybe' is not one of"),
        ("fault.csv,12000,1800,,1,true", "order_track needs tacho_channel"),
    ):
        (tmp_path / "MANIFEST.csv").write_text(rows.splitlines()[0] + "\n" + cells + "\n")
        assert main(["diagnose", str(tmp_path), "--report", str(tmp_path / "out2")]) == 2
        assert said in capsys.readouterr().err


class _ReadsGain:
    """A model of one's own that reads a further column, ``gain``: outer race above 1."""

    classes_ = np.array(["healthy", "outer race"])
    seen: list = []

    def predict(self, frame):
        return np.where(frame["gain"] > 1, "outer race", "healthy")

    def predict_proba(self, frame):
        _ReadsGain.seen.append(frame["gain"].tolist())
        outer = (frame["gain"].to_numpy() > 1).astype(float)
        return np.column_stack([1.0 - outer, outer])


def test_context_extra_reaches_a_model_that_reads_it_and_is_refused_where_it_would_be_lost(
    small_bundle,
):
    """``diagnose_signal(context_extra=...)``: its columns reach a pipeline of one's own; a
    column that would replace one computed from fs, rpm and the bearing is refused (the rule's
    rates and the model's would differ), and so is any for a cmtool model, whose features read
    no other column (stop 88 found them silently ignored), or with no model at all."""
    from cmtool import diagnose_signal

    x = np.random.default_rng(8).standard_normal(24000)
    custom = _ReadsGain()
    report = diagnose_signal(x, 12000.0, 1797, "6205", model=custom, context_extra={"gain": 2})
    assert report.model_verdict["label"] == "outer race" and _ReadsGain.seen[-1] == [2]
    cases = [
        (small_bundle, {"gain": 2}, "context_extra\\['gain'\\]: a cmtool model's features read"),
        (custom, {"bpfo_hz": 100.0}, "context_extra\\['bpfo_hz'\\] would replace a column"),
        (small_bundle, {"fs_hz": 1.0}, "context_extra\\['fs_hz'\\] would replace a column"),
        (None, {"gain": 2}, "gives a model further columns, and no model is given"),
        (custom, [("gain", 2)], "is not a mapping of column name to value"),
    ]
    for model, extra, message in cases:
        with pytest.raises(ValueError, match=message):
            diagnose_signal(x, 12000.0, 1797, "6205", model=model, context_extra=extra)
    # nothing or an empty mapping: as before
    assert diagnose_signal(x, 12000.0, 1797, "6205", model=small_bundle, context_extra={})


def test_a_commands_stage_bars_count_what_each_stage_counts(monkeypatch):
    """``StageBars``: one bar per stage, the one before closed when the next reports, each
    counting its own unit (``cmtool train``: signals, then model fits)."""
    import cmtool.commands.common as common
    from cmtool.fits import FIT_STAGE

    made = []

    class Bar:
        def __init__(self, total, desc, unit):
            self.total, self.desc, self.unit, self.n, self.closed = total, desc, unit, 0, False
            made.append(self)

        def update(self, step):
            self.n += step

        def close(self):
            self.closed = True

    monkeypatch.setattr(common, "progress_bar", Bar)
    with common.StageBars("train", units={FIT_STAGE: "fit"}) as progress:
        progress("features and rule evidence", 10, 20)
        progress("features and rule evidence", 20, 20)
        progress(FIT_STAGE, 3, 25)
        assert made[0].closed and not made[1].closed
    assert [(b.desc, b.unit, b.n, b.total) for b in made] == [
        ("train: features and rule evidence", "signal", 20, 20),
        (f"train: {FIT_STAGE}", "fit", 3, 25),
    ]
    assert made[1].closed
