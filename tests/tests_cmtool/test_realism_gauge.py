"""The realism gauge (cmtool realism): simulated vs measured, grouped by recording."""

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cmtool.cli import main
from cmtool.datasets import read_dataset
from cmtool.realism import (
    REALISM_TREES,
    context_columns,
    feature_difference,
    realism,
    recording_segments,
)

SMALL = Path(__file__).resolve().parents[2] / "datasets" / "small"
#: Trees of the gauge's forests in the tests of its logic (the CLI's keep REALISM_TREES, 300):
#: a third of the time, the AUCs these tests read as clear of their bounds.
TREES = 100


@pytest.fixture(scope="module")
def small():
    return read_dataset(SMALL)


def _recordings(folder: Path, signals, rpm, fs) -> Path:
    """Write each list of signals as one .npy recording listed in a MANIFEST.csv."""
    folder.mkdir(parents=True, exist_ok=True)
    rows = []
    for i, (parts, speed) in enumerate(zip(signals, rpm, strict=True)):
        name = f"rec{i}.npy"
        np.save(folder / name, np.concatenate(parts))
        rows.append({"file": name, "sampling_rate_hz": fs, "shaft_rpm": speed, "bearing": "6205"})
    pd.DataFrame(rows).to_csv(folder / "MANIFEST.csv", index=False)
    return folder


def test_gauge_cannot_tell_a_simulation_from_itself_and_tells_noise_at_once(small, tmp_path):
    # "recordings" made of held-out signals of the same simulation (every class, every
    # operating point): indistinguishable
    held = small.sample(40, random_state=0)
    rest = small.drop(held.index)
    same = _recordings(tmp_path / "same", [[x] for x in held["signal"]], list(held["rpm"]), 6400.0)
    segments = recording_segments(same, 1.0)
    assert len(segments) == len(held) and segments["group"].nunique() == len(held)
    alike = realism(rest, segments, n_estimators=TREES)
    assert alike["auc"] < 0.75, alike["auc"]
    # white noise is nothing like a bearing: recognised at once
    rng = np.random.default_rng(3)
    noise = _recordings(
        tmp_path / "noise",
        [[rng.standard_normal(6400) for _ in range(2)] for _ in range(6)],
        [1800.0] * 6,
        6400.0,
    )
    unlike = realism(rest, recording_segments(noise, 1.0), n_estimators=TREES)
    assert unlike["auc"] > 0.95, unlike["auc"]
    assert unlike["folds"] == 5 and len(unlike["features"]) > 10
    assert unlike["trees"] == TREES


def test_gauge_needs_a_manifest_and_two_recordings(small, tmp_path):
    with pytest.raises(FileNotFoundError, match="MANIFEST.csv"):
        recording_segments(tmp_path, 1.0)
    one = _recordings(tmp_path / "one", [[np.ones(6400) + np.arange(6400)]], [1800.0], 6400.0)
    with pytest.raises(ValueError, match="at least two recordings"):
        realism(small, recording_segments(one, 1.0))
    two = _recordings(tmp_path / "two", [[np.ones(6400)], [np.zeros(6400)]], [1800.0] * 2, 6400.0)
    for trees in (0, 2.5, True):
        with pytest.raises(ValueError, match=rf"n_estimators = {trees!r} is outside .*\[1, inf\)"):
            realism(small, recording_segments(two, 1.0), n_estimators=trees)


def test_gauge_refuses_signals_too_short_for_the_fault_rates_by_name(small, tmp_path):
    """20 periods of the slowest fault rate, as the diagnosis. Before, the gauge compared the
    features of 0.016 s simulated records (or recordings) with the rest without a word."""
    rng = np.random.default_rng(4)
    long, short = rng.standard_normal(6400), rng.standard_normal(1000)  # 0.156 s at 6400 Hz
    folder = _recordings(tmp_path / "rec", [[long], [long], [short]], [1800.0] * 3, 6400.0)
    segments = recording_segments(folder, 1.0)
    with pytest.raises(ValueError, match=r"measured: a segment of 'rec2.npy' \(row 2\) is 0.156"):
        realism(small, segments, n_estimators=TREES)
    cut = small.copy()
    cut.at[7, "signal"] = cut.at[7, "signal"][:1000]
    message = rf"simulated: signal '{cut.at[7, 'id']}' \(row 7\) is 0.156 s long .* 1 of 192"
    with pytest.raises(ValueError, match=message):
        realism(cut, segments.iloc[:2], n_estimators=TREES)


@pytest.mark.realdata
def test_cli_realism_on_the_measured_recordings(shared_data, tmp_path, capsys):
    rc = main(["realism", str(SMALL), str(shared_data), "--out", str(tmp_path)])
    assert rc == 0
    out = capsys.readouterr().out
    assert "ROC AUC" in out and "gives the simulation away" in out
    result = json.loads((tmp_path / "realism.json").read_text())
    assert 0.0 <= result["auc"] <= 1.0 and result["recordings"] == 6
    assert (tmp_path / "realism.png").stat().st_size > 10000


def test_gauge_judges_signals_not_the_speed_grid(tmp_path):
    """The same white noise, 'simulated' at 1800 rpm and 'measured' at 1900 rpm: nothing in the
    signals differs, so the gauge must not tell them apart (with the shaft frequency among its
    features a forest separates them perfectly: AUC 1.0). The speeds are close enough that the
    kurtogram's narrowest band (3 x the fastest fault rate) falls on the same level of its tree:
    its band width carries the speed too (at 3000 rpm the gauge reaches 0.97 on this noise)."""
    from generators import bearing, characteristic_frequencies

    rng = np.random.default_rng(17)
    fs = 6400.0
    f = characteristic_frequencies(bearing("6205"), 1800.0 / 60.0)
    simulated = pd.DataFrame(
        {"signal": [rng.standard_normal(6400) for _ in range(60)], **context_columns(f, fs)}
    )
    measured = _recordings(
        tmp_path / "fast",
        [[rng.standard_normal(6400) for _ in range(3)] for _ in range(10)],
        [1900.0] * 10,
        fs,
    )
    reports: list = []
    result = realism(
        simulated,
        recording_segments(measured, 1.0),
        progress=lambda *r: reports.append(r),
        n_estimators=TREES,
    )
    assert reports[-1] == ("features", 90, 90)  # 60 simulated signals and 30 segments
    assert result["context_left_out"] == ["shaft_frequency"]
    assert "shaft_frequency" not in dict(result["features"])
    assert result["auc"] < 0.75, result["auc"]


def test_feature_difference_says_which_way_and_what_lies_outside_the_simulated_range():
    simulated = np.arange(100.0)  # its 1-99 % range: 0.99 to 98.01
    measured = np.array([150.0, 200.0, 50.0, 60.0])
    d = feature_difference(simulated, measured)
    # pairs with the measured value higher: 100 + 100 + 50.5 + 60.5 (a tie counts half)
    assert d["auc"] == pytest.approx(311 / 400)
    assert d["direction"] == "measured higher"
    assert d["measured_above_range"] == 0.5 and d["measured_below_range"] == 0.0
    assert d["simulated_median"] == 49.5 and d["measured_median"] == 105.0
    assert d["simulated_range"] == pytest.approx([0.99, 98.01])
    lower = feature_difference(simulated, -measured)
    assert lower["direction"] == "measured lower" and lower["auc"] == pytest.approx(0.0)
    assert lower["measured_below_range"] == 1.0
    alike = feature_difference(simulated, simulated[::-1].copy())
    assert alike["direction"] == "alike" and alike["auc"] == pytest.approx(0.5)


def test_gauge_says_which_way_a_telling_feature_differs(small, tmp_path, capsys):
    """'Recordings' that are the simulation's own healthy signals plus a tone at each one's
    BPFI, six times the signal's RMS: the plain spectrum's BPFI line is what differs, higher in
    the measured, outside what the simulation ever shows; the CLI and the plot say so."""
    from generators import bearing, characteristic_frequencies

    healthy = small[small["label"] == "healthy"]
    held = healthy.sample(12, random_state=1)
    rest = small.drop(held.index)
    signals = []
    for x, rpm in zip(held["signal"], held["rpm"], strict=True):
        bpfi = characteristic_frequencies(bearing("6205"), rpm / 60.0).bpfi
        t = np.arange(x.size) / 6400.0
        signals.append([x + 6.0 * np.std(x) * np.sqrt(2) * np.sin(2 * np.pi * bpfi * t)])
    tones = _recordings(tmp_path / "tones", signals, list(held["rpm"]), 6400.0)
    result = realism(rest, recording_segments(tones, 1.0), n_estimators=TREES)
    assert [d["feature"] for d in result["differences"]] == [n for n, _ in result["features"]]
    line = next(d for d in result["differences"] if d["feature"] == "spectrum_bpfi_h1_snr")
    assert line["direction"] == "measured higher" and line["unit"] == "dB"
    assert line["measured_above_range"] > 0.9, line
    assert line["measured_median"] > line["simulated_range"][1]
    rc = main(["realism", str(SMALL), str(tones), "--out", str(tmp_path / "out")])
    assert rc == 0
    out = capsys.readouterr().out
    assert "spectrum_bpfi_h1_snr" in out and "measured higher" in out
    saved = json.loads((tmp_path / "out" / "realism.json").read_text())
    assert saved["differences"][0]["feature"] == saved["features"][0][0]
    assert saved["trees"] == REALISM_TREES == 300  # the CLI's forests, as before stop 63


def test_gauge_reports_the_auc_per_rig_and_per_class(small, tmp_path, capsys):
    """Issue 17: per rig and per class, never only the total. Two "rigs" in one manifest:
    held-out signals of the simulation itself (its own classes) and white noise (labelled
    normal): the noise rig is recognised at once, the simulation's own is not; a class is
    compared with the simulated signals of the same class (like with like)."""
    held = small.sample(30, random_state=1)
    rest = small.drop(held.index)
    folder = tmp_path / "two-rigs"
    folder.mkdir()
    rng = np.random.default_rng(4)
    rows = []
    for i, (_, row) in enumerate(held.iterrows()):
        np.save(folder / f"sim{i}.npy", row["signal"])
        rows.append(("SIM", f"sim{i}.npy", row["rpm"], row["label"]))
    for i in range(6):
        np.save(folder / f"noise{i}.npy", rng.standard_normal(6400))
        rows.append(("NOISE", f"noise{i}.npy", 1800.0, "normal"))
    manifest = pd.DataFrame(rows, columns=["dataset", "file", "shaft_rpm", "fault_location"])
    manifest.assign(sampling_rate_hz=6400.0, bearing="6205").to_csv(
        folder / "MANIFEST.csv", index=False
    )
    segments = recording_segments(folder, 1.0)
    assert set(segments["rig"]) == {"SIM", "NOISE"}
    assert set(segments["label"]) == {"healthy", "inner race", "outer race", "ball"}
    result = realism(rest, segments, n_estimators=TREES)
    by_rig = result["auc_by"]["rig"]
    # (0.944-0.972 over forest seeds 0-2 at 100 and 300 trees: 0.95 was passed by 0.001)
    assert by_rig["NOISE"]["auc"] > 0.9 and by_rig["NOISE"]["segments"] == 6
    assert by_rig["SIM"]["auc"] < 0.8 and by_rig["SIM"]["segments"] == 30
    by_class = result["auc_by"]["label"]
    assert by_class["healthy"]["segments"] == 6 + int((held["label"] == "healthy").sum())
    assert sum(part["segments"] for part in by_class.values()) == 36
    for name, label in (("healthy", "healthy"), ("inner race", "inner"), ("ball", "ball")):
        assert by_class[name]["against"] == "same class"
        assert by_class[name]["simulated"] == int((rest["label"] == label).sum())
    # the simulation's own classes pass (0.27-0.39), the healthy one, half of it noise, not (0.80)
    others = [by_class[c]["auc"] for c in ("inner race", "outer race", "ball")]
    assert max(others) < 0.6 and by_class["healthy"]["auc"] > max(others) + 0.3
    # and what tells each class apart most: the healthy class's top features separate (the
    # noise half of it), the simulation's own classes' hardly
    telling = [abs(d["auc"] - 0.5) for d in by_class["healthy"]["differences"]]
    assert len(telling) == 5 and telling == sorted(telling, reverse=True)
    assert telling[0] > 0.2 and by_class["healthy"]["differences"][0]["direction"] != "alike"
    # the CLI prints them
    assert main(["realism", str(SMALL), str(folder)]) == 0
    printed = capsys.readouterr().out
    assert "rig NOISE: ROC AUC" in printed and "class ball: ROC AUC" in printed
    assert by_class["healthy"]["differences"][0]["feature"] in printed
