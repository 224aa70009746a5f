"""Training, evaluation, model files and diagnosis (simulated and measured signals)."""

import json
import pickle
import re
import shutil
import zipfile
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from impact_trains import ringing_impact_train

import features
from cmtool.classifier import (
    ModelFormatError,
    ModelVersionError,
    evaluate,
    load_model,
    save_model,
)
from cmtool.cli import main
from cmtool.diagnose import (
    DETECTION_DB,
    RANDOMNESS_ASSUMED,
    SPEED_WARNING,
    diagnose_signal,
    write_report,
)
from cmtool.io import read_recording
from generators import ParameterError

REPO = Path(__file__).resolve().parents[2]
SMALL = REPO / "datasets" / "small"


@pytest.fixture
def small(small_dataset):
    return small_dataset


@pytest.fixture
def bundle(small_bundle):
    return small_bundle


def _use_light_forests(monkeypatch) -> None:
    """``train``'s candidates with forests of 30 trees instead of 300 and 500."""
    import cmtool.classifier as classifier_module

    shipped = classifier_module.candidate_classifiers

    def lighter(random_state=0, class_weight=classifier_module.CLASS_WEIGHT):
        candidates = shipped(random_state, class_weight)
        for name in ("random_forest", "extra_trees"):
            candidates[name].set_params(n_estimators=30)
        return candidates

    monkeypatch.setattr(classifier_module, "candidate_classifiers", lighter)


@pytest.fixture
def light_forests(monkeypatch):
    """``train``'s candidates with forests of 30 trees instead of 300 and 500, for tests of
    what is kept and written rather than of how well it classifies."""
    _use_light_forests(monkeypatch)


def test_committed_small_dataset_matches_its_recipe(small):
    assert len(small) == 192
    assert small["label"].value_counts().to_dict() == {
        "healthy": 48,
        "inner": 48,
        "outer": 48,
        "ball": 48,
    }


def test_training_reports_grouped_scores_and_keeps_the_best(bundle):
    assert set(bundle["scores"]) >= {"random_forest", "extra_trees", "logistic_regression"}
    assert bundle["best"] == max(bundle["scores"], key=bundle["scores"].get)
    # far above chance (0.25) on operating points never seen in training
    assert bundle["scores"][bundle["best"]] > 0.8
    assert set(bundle["extrapolation"]) >= {"rpm_above_training", "radial_load_n_above_training"}
    assert bundle["classes"] == ["ball", "healthy", "inner", "outer"]


def test_extrapolation_holds_out_a_tenth_of_a_random_range_and_a_grids_extreme_level(small):
    """A randomised recipe's extreme speed is one signal (an accuracy of 0 or 1, as `cmtool
    train` printed on datasets/universal until stop 45); the small recipe's grid keeps its
    extreme level whole (a quarter of the speeds, a third of the loads)."""
    from cmtool.classifier import extreme_masks

    speeds = np.random.default_rng(0).uniform(600.0, 3000.0, 500)
    top, bottom = extreme_masks(speeds)
    assert 0.09 <= top.mean() <= 0.12 and 0.09 <= bottom.mean() <= 0.12
    assert speeds[top].min() > speeds[~top].max() and speeds[bottom].max() < speeds[~bottom].min()
    for column, share in (("rpm", 1 / 4), ("radial_load_n", 1 / 3)):
        values = small[column].to_numpy()
        top, bottom = extreme_masks(values)
        assert (top == (values == values.max())).all() and top.mean() == pytest.approx(share)
        assert (bottom == (values == values.min())).all()


def test_model_round_trip_and_version_check(bundle, small, tmp_path):
    import skops.io as sio

    path = save_model(bundle, tmp_path / "m.skops")
    assert zipfile.is_zipfile(path)  # a skops archive, not a pickle
    loaded = load_model(path)
    np.testing.assert_array_equal(
        loaded["pipeline"].predict(small.head(8)), bundle["pipeline"].predict(small.head(8))
    )
    summary = json.loads(path.with_suffix(".skops.json").read_text())
    assert summary["best"] == bundle["best"]
    assert summary["training_fingerprint"] == bundle["training_fingerprint"]
    old = dict(bundle, versions={**bundle["versions"], "sklearn": "0.1"})
    sio.dump(old, tmp_path / "old.skops")
    with pytest.raises(ModelVersionError, match="sklearn 0.1"):
        load_model(tmp_path / "old.skops")
    sio.dump({"not": "a model"}, tmp_path / "junk.skops")
    with pytest.raises(ModelFormatError, match="not a cmtool model of format 2"):
        load_model(tmp_path / "junk.skops")
    sio.dump(dict(bundle, training_fingerprint="x"), tmp_path / "nofp.skops")
    with pytest.raises(ModelFormatError, match="fingerprint"):
        load_model(tmp_path / "nofp.skops")


class _RunsCodeOnLoad:
    """A pickle payload that creates a file when unpickled."""

    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return (Path.touch, (Path(self.marker),))


def test_crafted_model_files_run_no_code_and_are_refused(tmp_path, capsys):
    import skops.io as sio

    marker = tmp_path / "pwned"
    evil = tmp_path / "evil.joblib"
    evil.write_bytes(pickle.dumps({"format": 2, "payload": _RunsCodeOnLoad(marker)}))
    with pytest.raises(ModelFormatError, match="not a cmtool model file"):
        load_model(evil)
    junk = tmp_path / "random.skops"
    junk.write_bytes(np.random.default_rng(0).bytes(4096))
    with pytest.raises(ModelFormatError, match="not a cmtool model file"):
        load_model(junk)
    # a skops archive that would build a type cmtool does not trust (a user class)
    sio.dump({"format": 2, "payload": _RunsCodeOnLoad(marker)}, tmp_path / "foreign.skops")
    with pytest.raises(ModelFormatError, match="does not trust"):
        load_model(tmp_path / "foreign.skops")
    truncated = tmp_path / "truncated.skops"
    whole = (tmp_path / "foreign.skops").read_bytes()
    truncated.write_bytes(whole[: len(whole) // 2])
    with pytest.raises(ModelFormatError):
        load_model(truncated)
    csv = tmp_path / "rec.csv"
    pd.DataFrame({"accel": np.random.default_rng(1).standard_normal(12000)}).to_csv(csv)
    for path in (evil, junk, tmp_path / "foreign.skops", truncated):
        for argv in (
            ["evaluate", str(path), str(SMALL)],
            [
                "diagnose",
                str(csv),
                "--fs",
                "12000",
                "--rpm",
                "1800",
                "--bearing",
                "6205",
                "--model",
                str(path),
            ],
        ):
            assert main(argv) == 2
            err = capsys.readouterr().err
            assert "Traceback" not in err and err.count("\n") == 1, err
            assert f"model {path}" in err, err
    assert not marker.exists()


def test_evaluate_metrics(bundle, small):
    # two rigs: the features read the context columns, so renaming a bearing changes only the
    # grouping of the per-rig scores (issue 17: per rig and per class)
    third = np.arange(len(small)) % 3 == 0
    result = evaluate(bundle, small.assign(bearing=np.where(third, "6203", "6205")))
    assert set(result["per_class"]) == {"ball", "healthy", "inner", "outer"}
    cm = np.array(result["confusion"])
    assert cm.sum() == len(small)
    assert result["accuracy"] == pytest.approx(np.trace(cm) / cm.sum())
    pickle.dumps(result)
    by_rig = result["by_rig"]
    assert {k: v["signals"] for k, v in by_rig.items()} == {"6203": 64, "6205": 128}
    right = np.array(result["predictions"]) == small["label"].to_numpy()
    for rig, mine in (("6203", third), ("6205", ~third)):
        assert by_rig[rig]["accuracy"] == pytest.approx(right[mine].mean())
        inner = mine & (small["label"] == "inner").to_numpy()
        assert by_rig[rig]["recall"]["inner"] == pytest.approx(right[inner].mean())
    one = small.groupby("label").head(2)  # one bearing: the totals say it all
    assert evaluate(bundle, one)["by_rig"] == {}


def test_evaluate_on_two_workers_gives_the_same_result_and_leaves_the_bundle_as_it_came(
    bundle, small, monkeypatch
):
    """``evaluate(workers=2)`` extracts the features in two processes: the same metrics as in
    one, and the bundle's own extractor keeps its ``n_jobs`` (a bundle saved afterwards is the
    one that was loaded). With ``progress`` it reports chunk by chunk up to its total (the
    command shows a bar: 700 signals took 40-70 s without a word), the result unchanged."""
    import cmtool.classifier as classifier_module

    extractor = bundle["pipeline"][0]
    before = extractor.n_jobs
    part = small.iloc[::4]
    one = evaluate(bundle, part)
    assert evaluate(bundle, part, workers=2) == one
    assert extractor.n_jobs == before
    monkeypatch.setattr(classifier_module, "PROGRESS_CHUNK", 5)
    reports: list[tuple[str, int, int]] = []
    assert evaluate(bundle, part, workers=2, progress=lambda *r: reports.append(r)) == one
    assert reports == [("features", done, 48) for done in (10, 20, 30, 40, 48)]


def test_cli_train_evaluate(tmp_path, capsys, light_forests):
    """train, evaluate and bench through the CLI (forests of 30 trees, on a third of the
    small dataset's parts: every label at every operating point; the test is about the
    commands, not the model's quality)."""
    model = tmp_path / "model.skops"
    data = tmp_path / "third"
    (data / "data").mkdir(parents=True)
    for name in sorted((SMALL / "data").glob("*.parquet"))[::3]:
        shutil.copy(name, data / "data" / name.name)
    assert main(["train", str(data), "--out", str(model), "--feature-set", "envelope"]) == 0
    out = capsys.readouterr().out
    assert "grouped" in out and "<- kept" in out
    assert "at each end of the speed and load ranges" in out and "extrapolation rpm_above" in out
    assert load_model(model)["feature_set"] == "envelope"  # --feature-set reached the bundle
    # scoring a model on its own training signals is refused ...
    assert main(["evaluate", str(model), str(data)]) == 2
    assert "100% of the signals" in capsys.readouterr().err
    assert main(["bench", str(data), "--model", str(model)]) == 2
    assert "--allow-training-data" in capsys.readouterr().err
    # ... unless asked for, and then every output says so
    argv = ["evaluate", str(model), str(data), "--out", str(tmp_path / "ev")]
    assert main([*argv, "--allow-training-data"]) == 0
    out = capsys.readouterr().out
    assert "confusion matrix" in out and "precision" in out and "IN-SAMPLE" in out
    assert json.loads((tmp_path / "ev" / "evaluation.json").read_text())["in_sample_fraction"] == 1
    assert (tmp_path / "ev" / "confusion.png").stat().st_size > 5000
    # bench on four of the training parts (32 signals): refused, then labelled in-sample
    part = tmp_path / "part" / "data"
    part.mkdir(parents=True)
    for name in sorted((data / "data").glob("*.parquet"))[::2]:
        shutil.copy(name, part / name.name)
    bench = ["bench", str(part.parent), "--model", str(model), "--out", str(tmp_path / "b")]
    assert main(bench) == 2
    assert "--allow-training-data" in capsys.readouterr().err
    assert main([*bench, "--allow-training-data", "--workers", "2"]) == 0
    assert "IN-SAMPLE" in capsys.readouterr().out
    summary = pd.read_csv(tmp_path / "b" / "summary.csv")
    assert {"model", "combined"} <= set(summary["detector"]) and summary["in_sample"].all()


def test_diagnose_synthetic_impulses_and_noise(rng):
    fs, n = 12000.0, 24000
    t = np.arange(n) / fs
    from generators import bearing, characteristic_frequencies

    f = characteristic_frequencies(bearing("6205"), 1800 / 60)
    x = np.zeros(n)
    x[(np.arange(0, n / fs, 1 / f.bpfi) * fs).astype(int)] = 1.0
    ring = np.exp(-t[:120] * 1500) * np.sin(2 * np.pi * 3000 * t[:120])
    x = np.convolve(x, ring)[:n] * (1 + 0.5 * np.cos(2 * np.pi * f.shaft * t))
    d = diagnose_signal(x / x.std() + rng.standard_normal(n), fs, 1800.0, "6205")
    assert d.verdict == "inner race"
    assert d.candidates[0]["envelope_snr_db"][0] >= DETECTION_DB
    # single impacts have no entry event to time: a fault verdict says that its size is not
    # estimated, and why; a healthy one says nothing
    severity = d.to_dict()["severity"]
    assert set(severity) == {"estimated", "reason"} and severity["estimated"] is False
    assert severity["reason"].startswith("not estimated: ")
    noise = diagnose_signal(rng.standard_normal(n), fs, 1800.0, "6205")
    assert noise.verdict == "healthy"
    assert noise.severity is None and "severity" not in noise.to_dict()


def test_a_diagnosis_is_the_same_in_any_unit_of_the_record():
    """A simulated record (a 9-lobe inner race, 1 um, 1200 rpm, 300 N), noise-free and in
    noise, in m/s^2, in g and in mm/s^2, should give the same verdict, confidence and weighed
    evidence. Until stop 76 it did not: the separation's instrument floor was drawn from the
    record's first samples, and the noise-free record's margin read +11.4, +6.6 and +11.8 dB in
    the three units (benchmarks/floor_units.py; docs/diagnosis.md, "Verdicts the instrument
    floor decides")."""
    from generators import OperatingCondition, SimulationSettings, Waviness, bearing, simulate

    g = bearing("6205", radial_internal_clearance=5e-6)
    channel = "housing_acceleration_y"
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=(channel,))
    wavy = Waviness(surface="inner", order=9, amplitude=1e-6)
    op = OperatingCondition.from_rpm(1200, 300.0)
    x = simulate(g, op, wavy, settings=settings, random_state=2)[channel]
    noisy = x + np.random.default_rng(75).normal(0.0, 0.05 * np.std(x), x.size)
    for record in (x, noisy):
        reads = []
        for scale in (1.0, 1.0 / 9.80665, 1000.0):
            d = diagnose_signal(scale * record, 12000.0, 1200, g, waviness=False)
            reads.append((d.verdict, d.confidence, [c["evidence_db"] for c in d.candidates]))
        for verdict, confidence, evidence in reads[1:]:
            assert (verdict, confidence) == reads[0][:2]
            assert evidence == pytest.approx(reads[0][2], abs=1e-6)


def test_a_diagnosis_states_whether_it_added_an_instrument_floor(tmp_path, capsys):
    """A noise-free record (a shaft's harmonics) is judged with a good chain's floor added, and
    its assumptions say so, with the floor in the evidence, as does the command's text; a
    record in noise gets none, and the text no line on it."""
    fs, rpm = 12000.0, 1797.0
    t = np.arange(12000) / fs
    periodic = sum(np.cos(2 * np.pi * k * rpm / 60 * t + k) / k for k in range(1, 30))
    noisy = periodic + 0.3 * np.random.default_rng(76).standard_normal(t.size)
    for x, added in ((periodic, True), (noisy, False)):
        d = diagnose_signal(x, fs, rpm, "6205", waviness=False)
        stated = d.assumptions["instrument_floor"]
        assert stated.startswith("added" if added else "none added"), stated
        assert "50 dB under the RMS" in stated
        ctx = {**d.frequencies, "shaft": rpm / 60}
        floor_rms = features.fault_evidence(x, fs, ctx).instrument_floor_rms
        assert floor_rms == (pytest.approx(np.std(x) * 10**-2.5) if added else 0.0)
        np.save(tmp_path / "rec.npy", x)
        argv = ["diagnose", str(tmp_path / "rec.npy"), "--fs", "12000", "--rpm", "1797"]
        assert main([*argv, "--bearing", "6205"]) == 0
        assert ("instrument floor added:" in capsys.readouterr().out) is added


def test_a_pits_impacts_show_through_their_randomness_and_the_records_length():
    """What the rule assumes (docs/diagnosis.md, "What the rule needs"): a CWRU-size outer-race
    pit in the load zone, noise at 3 x the RMS. Strictly periodic, it is removed as machine
    vibration at 1 and 5 s; with 0.2 % of slip it is found in 5 s but not in 1 s (margins of
    5-6 dB either way in benchmarks/rule_slip_length.py); the diagnosis states the assumption."""
    from generators import (
        LocalizedDefect,
        OperatingCondition,
        SimulationSettings,
        bearing,
        simulate,
    )

    g = bearing("6205", radial_internal_clearance=5e-6)
    pit = LocalizedDefect(surface="outer", length=1.8e-4, depth=2.8e-4, position=-np.pi / 2)
    settings = SimulationSettings(fs=12000.0, duration=5.0, channels=("housing_acceleration_y",))
    verdicts = {}
    for slip in (0.0, 0.002):
        op = OperatingCondition.from_rpm(1797, 400.0, random_slip=slip)
        x = simulate(g, op, pit, settings=settings, random_state=4)["housing_acceleration_y"]
        x = x + np.random.default_rng(0).normal(0.0, 3.0 * x.std(), x.size)
        for seconds in (1, 5):
            d = diagnose_signal(x[: 12000 * seconds], 12000.0, 1797, g, waviness=False)
            verdicts[slip, seconds] = d.verdict
            assert d.assumptions["randomness"] == RANDOMNESS_ASSUMED
    assert verdicts == {
        (0.0, 1): "healthy",
        (0.0, 5): "healthy",
        (0.002, 1): "healthy",
        (0.002, 5): "outer race",
    }


def test_cli_diagnose_says_a_faults_size_is_not_estimated(tmp_path, capsys, rng):
    """Text and report of a fault verdict carry the size statement (docs/diagnosis.md)."""
    from generators import bearing, characteristic_frequencies

    fs, n = 12000.0, 24000
    f = characteristic_frequencies(bearing("6205"), 1800 / 60)
    x = np.zeros(n)
    # impacts at BPFO whose spacing jitters by 1 % (slip): a pit's train is not periodic
    spacing = (1 + 0.01 * rng.standard_normal(400)) / f.bpfo
    times = np.cumsum(spacing)
    x[(times[times < n / fs] * fs).astype(int)] = 1.0
    t = np.arange(120) / fs
    x = np.convolve(x, np.exp(-t * 1500) * np.sin(2 * np.pi * 3000 * t))[:n]
    x = x / x.std() + rng.standard_normal(n)
    npy = tmp_path / "rec.npy"
    np.save(npy, x)
    args = ["diagnose", str(npy), "--fs", "12000", "--rpm", "1800", "--bearing", "6205"]
    assert main([*args, "--report", str(tmp_path / "rep")]) == 0
    out = capsys.readouterr().out
    assert "outer race" in out and "fault size: not estimated" in out
    report = (tmp_path / "rep" / "report.md").read_text()
    section = report.split("## Fault size", 1)[1].split("##", 1)[0]
    assert section.strip().startswith("not estimated: ") and "Severity" in section


def test_cli_diagnose_shows_the_balls_cage_line(tmp_path, capsys, rng):
    """A ball pit's impacts come in bursts once per cage turn: the ball's line in the text says
    how far its cage-rate line stands over the floor, beside 1x/2x/3x (docs/diagnosis.md)."""
    from generators import bearing, characteristic_frequencies

    fs, n = 12000.0, 24000
    f = characteristic_frequencies(bearing("6205"), 1797 / 60)
    times = np.cumsum((1 + 0.015 * rng.standard_normal(800)) / f.two_bsf)
    times = times[(times < n / fs - 0.02) & ((times * f.ftf) % 1.0 < 1.0 / 3.0)]
    x = np.zeros(n)
    x[(times * fs).astype(int)] = np.sin(3.0 * np.pi * ((times * f.ftf) % 1.0))
    t = np.arange(200) / fs
    x = np.convolve(x, np.exp(-800.0 * t) * np.sin(2 * np.pi * 3200.0 * t))[:n]
    x = x + x.std() * rng.standard_normal(n)
    np.save(tmp_path / "ball.npy", x)
    args = ["diagnose", str(tmp_path / "ball.npy"), "--fs", "12000", "--rpm", "1797"]
    assert main([*args, "--bearing", "6205"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("ball.npy: ball")
    ball = next(line for line in out.splitlines() if line.strip().startswith("ball "))
    assert "cage rate" in ball and "DETECTED" in ball
    assert not any("cage rate" in line for line in out.splitlines() if "race" in line)


def test_diagnose_bad_input(rng):
    with pytest.raises(ValueError, match="constant"):
        diagnose_signal(np.ones(5000), 12000.0, 1800.0)
    with pytest.raises(
        ValueError, match=r"rpm = 150000 rpm is outside the allowed range \(0, 120000\]"
    ):
        diagnose_signal(rng.standard_normal(5000), 12000.0, 150000.0)
    fast = diagnose_signal(rng.standard_normal(48000), 48000.0, 20000.0, "6205")
    assert any("above the catalogue limiting speed" in w for w in fast.warnings)
    clipped = np.clip(rng.standard_normal(24000), -1.5, 1.5)
    assert any("clipped" in w for w in diagnose_signal(clipped, 12000.0, 1800.0).warnings)


def test_a_record_longer_than_the_limit_is_diagnosed_on_its_first_part(monkeypatch):
    """Found by probing: a 60 s record at 48 kHz took 0.8 GB and 19 s, about 270 bytes a
    sample, so an hour's would not fit in memory. The first MAX_RECORD_SAMPLES are
    diagnosed, and the warning and the assumptions say so."""
    import cmtool.diagnose as D

    monkeypatch.setattr(D, "MAX_RECORD_SAMPLES", 24000)
    x = np.random.default_rng(5).standard_normal(36000)
    long, first = (
        D.diagnose_signal(x, 12000.0, 1800.0),
        D.diagnose_signal(x[:24000], 12000.0, 1800.0),
    )
    assert long.assumptions["samples"] == 24000 and long.assumptions["record_s"] == 2.0
    assert long.assumptions["record_total_s"] == 3.0 and "record_total_s" not in first.assumptions
    assert long.candidates == first.candidates and long.velocity_bands == first.velocity_bands
    assert [w for w in long.warnings if w not in first.warnings] == [
        "the record is 3 s (36000 samples): its first 2 s (24000 samples) are diagnosed "
        "(memory grows by about 270 bytes a sample)"
    ]


@pytest.mark.parametrize("bad", [np.inf, -np.inf, np.nan])
@pytest.mark.parametrize("allow_clipping", [False, True])
def test_a_record_with_an_inf_or_nan_is_refused_as_such(bad, allow_clipping, tmp_path, capsys):
    """Found by probing: one inf in a record was read as its largest value, and the record
    refused as "100 % clipped" (with --allow-clipping: numpy warnings, then an error)."""
    x = np.random.default_rng(3).standard_normal(12000)
    x[100] = bad
    np.save(tmp_path / "rec.npy", x)
    argv = ["diagnose", str(tmp_path / "rec.npy"), "--fs", "12000", "--rpm", "1800"]
    argv += ["--bearing", "6205"] + (["--allow-clipping"] if allow_clipping else [])
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Warning" not in err, err
    assert "contains 1 non-finite values (NaN or inf)" in err and "clipped" not in err
    with pytest.raises(ValueError, match="baseline contains 1 non-finite"):
        diagnose_signal(
            np.random.default_rng(4).standard_normal(12000), 12000.0, 1800.0, baseline=x
        )


def test_cli_diagnose_csv_json_and_model(tmp_path, capsys, rng, bundle):
    x = rng.standard_normal(12000)
    csv = tmp_path / "rec.csv"
    pd.DataFrame({"time": np.arange(x.size) / 12000.0, "accel": x}).to_csv(csv, index=False)
    model = save_model(bundle, tmp_path / "m.skops")
    assert (
        main(
            [
                "diagnose",
                str(csv),
                "--rpm",
                "1800",
                "--bearing",
                "6205",
                "--json",
                "--model",
                str(model),
                "--report",
                str(tmp_path / "rep"),
            ]
        )
        == 0
    )
    data = json.loads(capsys.readouterr().out)
    assert data["verdict"] == "healthy"
    assert {
        "verdict",
        "confidence",
        "candidates",
        "frequencies",
        "warnings",
        "model_verdict",
    } <= set(data)
    assert data["frequencies"]["bpfo"] == pytest.approx(107.54, abs=0.01)
    report = (tmp_path / "rep" / "report.md").read_text()
    assert report.startswith("# Diagnosis")
    assert "![waveform](waveform.png)" in report
    assert (tmp_path / "rep" / "waveform.png").read_bytes().startswith(b"\x89PNG")
    # the model's verdict in words, its class named with what it was trained on, no raw dict
    verdict = data["model_verdict"]
    kind = {"waviness": " waviness", "localized": " local fault"}.get(
        verdict.get("class_kinds", {}).get(verdict["label"], ""), ""
    )
    worded = (
        f"{verdict['label']}{kind} (probability {verdict['probabilities'][verdict['label']]:.2f}"
    )
    assert f"Model verdict: **{worded.split(' (')[0]}** (" in report
    assert (
        main(["diagnose", str(csv), "--rpm", "1800", "--bearing", "6205", "--model", str(model)])
        == 0
    )
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("  model: "))
    assert line.startswith(f"  model: {worded}") and "{" not in line, line
    assert line.endswith("1 segment of the record averaged"), line
    assert main(["diagnose", str(csv)]) == 2  # no rpm in a CSV
    assert "give --rpm" in capsys.readouterr().err


#: The measured recordings in ../shared/data (file, bearing, expected verdict); the files
#: themselves are read only when present.
MEASURED = [
    ("cwru/12k_Drive_End_B021_0_222.mat", "6205", "ball"),
    ("cwru/12k_Drive_End_IR007_0_105.mat", "6205", "inner race"),
    ("cwru/12k_Drive_End_OR007@6_0_130.mat", "6205", "outer race"),
    ("cwru/normal_0_97.mat", "6205", "healthy"),
    ("mfpt/InnerRaceFault_vload_1.mat", "mfpt", "inner race"),
    ("mfpt/OuterRaceFault_vload_2.mat", "mfpt", "outer race"),
]


@pytest.mark.realdata
@pytest.mark.parametrize(("name", "bearing_name", "expected"), MEASURED)
def test_measured_recordings_get_their_labelled_fault(shared_data, name, bearing_name, expected):
    row = pd.read_csv(shared_data / "MANIFEST.csv").set_index("file").loc[name]
    x, _ = read_recording(shared_data / name)
    d = diagnose_signal(x, float(row.sampling_rate_hz), float(row.shaft_rpm), bearing_name)
    assert d.verdict == expected, (name, d.candidates)
    assert d.assumptions["fs_hz"] == float(row.sampling_rate_hz)
    assert d.assumptions["record_s"] == pytest.approx(x.size / float(row.sampling_rate_hz))
    # the 1x line is found, and warned of exactly when it lies more than SPEED_WARNING (set on
    # simulated records) from the manifest's speed: the CWRU records' tachometer speeds agree
    # with it, the MFPT records' nominal 1500 rpm does not (docs/diagnosis.md, "The speed the
    # rates come from": their lines lie 0.86-0.95 % below it)
    line_rpm = d.assumptions["spectrum_rpm"]
    assert line_rpm is not None
    off = abs(line_rpm / float(row.shaft_rpm) - 1.0)
    warned = [w for w in d.warnings if "1x line" in w]
    assert len(warned) == int(off > SPEED_WARNING), (off, d.warnings)
    assert off < SPEED_WARNING if name.startswith("cwru/") else len(warned) == 1


@pytest.mark.realdata
def test_no_measured_recording_is_refused_as_clipped(shared_data):
    """`cmtool diagnose` refuses records with 3 % or more of their samples at full scale (a
    threshold from simulation); none of the measured recordings is one."""
    from cmtool.diagnose import check_clipping

    for name in pd.read_csv(shared_data / "MANIFEST.csv")["file"]:
        x, _ = read_recording(shared_data / name)
        check_clipping(x, name)


def test_demo_runs_end_to_end(tmp_path, capsys, monkeypatch, small_dataset, small_bundle):
    """The demo end to end; its training is the ``small_bundle`` fixture's own ``train`` call
    (the same function on the same recipe), so the test checks that the demo generates the
    committed small dataset and hands it to ``train``, then goes on with the model that call
    makes (trained once per test run, not twice).

    The committed files were written under the numba and LLVM of 28 November; generated
    under later versions a signal moves by at most 2.4e-7 of its RMS (float32 roundings the
    other way) and ``noise_rms`` by 1e-14 relative: the tolerances are 1e-6 and 1e-9.
    """
    import cmtool.classifier as classifier_module

    handed = []

    def train_once(frame, *, recipe, **kwargs):
        assert not kwargs and recipe == (SMALL / "recipe.toml").read_text()
        signals = ["signal"]
        pd.testing.assert_frame_equal(
            frame.drop(columns=signals),
            small_dataset.drop(columns=signals),
            check_exact=False,
            rtol=1e-9,
        )
        for ours, committed in zip(frame["signal"], small_dataset["signal"], strict=True):
            np.testing.assert_allclose(ours, committed, rtol=0, atol=1e-6 * committed.std())
        handed.append(len(frame))
        return small_bundle

    monkeypatch.setattr(classifier_module, "train", train_once)
    assert main(["demo", "--out", str(tmp_path)]) == 0
    assert handed == [192]
    out = capsys.readouterr().out
    assert "grouped-CV balanced accuracy" in out
    assert (tmp_path / "confusion.png").exists()
    assert (tmp_path / "diagnosis_simulated" / "report.md").exists()
    assert (tmp_path / "diagnosis_local_defect" / "report.md").exists()
    # the simulated inner-race pit is called inner race by the rule-based envelope detector
    assert "inner-race pit 0.18 mm: rule-based verdict inner race" in out
    # the bridged pit is not sized, the 3 mm spall is (docs/diagnosis.md, Severity)
    (pit_line,) = [line for line in out.splitlines() if "inner-race pit 0.18 mm" in line]
    assert pit_line.endswith("fault size not estimated")
    assert "spall 3 mm: rule-based verdict inner race; fault size spall length about" in out
    assert (tmp_path / "diagnosis_spall" / "entry_exit.png").exists()
    # the simulations are in m/s^2: their velocity bands and overall vibration read in mm/s
    for name in ("diagnosis_simulated", "diagnosis_local_defect"):
        report = json.loads((tmp_path / name / "diagnosis.json").read_text())
        assert set(report["velocity_bands_iso15242_mm_s"]) == {"low", "medium", "high"}
        assert report["overall_velocity_iso10816"]["rms_mm_s"] > 0
    # the measured CWRU record, where ../shared is beside the checkout, is judged in ISO
    # 10816-1 class I (the rig's 2 hp motor): its zone in the output and its report's JSON
    from cmtool.demo import SHARED_RECORDING

    if SHARED_RECORDING.is_file():
        report = json.loads((tmp_path / "diagnosis_cwru_ir007" / "diagnosis.json").read_text())
        zone = report["overall_velocity_iso10816"]["zone"]
        assert zone["machine_class"] == "class-I" and zone["zone"] in "ABCD"
        (zone_line,) = [line for line in out.splitlines() if "its vibration zone:" in line]
        assert zone_line.strip().startswith(f"its vibration zone: {zone['zone']} (")


def test_simulated_healthy_bearings_are_healthy_and_slipping_pits_are_found(small):
    """Issue 18's target: >= 95 % of simulated healthy bearings healthy, pits detected.

    A loaded bearing's varying compliance is periodic: the separation takes it out. A pit's
    impacts jitter (random slip, docs/realism.md): they stay.
    """
    from generators import (
        LocalizedDefect,
        OperatingCondition,
        SimulationSettings,
        bearing,
        simulate,
    )

    healthy = small[small["label"] == "healthy"]
    verdicts = [
        diagnose_signal(x, fs, rpm, "6205").verdict
        for x, fs, rpm in zip(healthy["signal"], healthy["fs_hz"], healthy["rpm"], strict=True)
    ]
    assert verdicts.count("healthy") >= 0.95 * len(verdicts), verdicts
    g = bearing("6205")
    clean = SimulationSettings(fs=25600.0, duration=1.0, channels=("housing_acceleration_y",))
    for rpm in (1200, 1800, 3000):
        run = simulate(g, OperatingCondition.from_rpm(rpm, 500.0), settings=clean)
        d = diagnose_signal(run["housing_acceleration_y"], run.fs, rpm, g)
        assert d.verdict == "healthy", (rpm, d.candidates)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    slipping = OperatingCondition.from_rpm(1797, 300.0, random_slip=0.01, ball_jitter=0.005)
    for surface, verdict in (("inner", "inner race"), ("outer", "outer race")):
        pit = LocalizedDefect(surface=surface, length=0.1778e-3, depth=0.28e-3)
        run = simulate(g, slipping, pit, settings=settings, random_state=2)
        x = run["housing_acceleration_y"]
        x = x + np.random.default_rng(2).normal(0.0, 0.3 * np.std(x), x.size)
        d = diagnose_signal(x, run.fs, 1797.0, g)
        assert d.verdict == verdict, (surface, d.candidates)


def test_an_inner_race_pits_lines_are_not_read_as_a_ball_fault(tmp_path, monkeypatch):
    """A 0.3 mm inner-race pit with 1 % random slip (6205, 1797 rpm, 400 N, 12 kHz, 2 s): the
    ball's 3x and lower sideband searched within the slip find the pit's own lines (3 BPFI - 2
    f_s, BPFI - f_s); counted for the ball they make it a detected second fault. The report
    gives them to the inner race and says so."""
    from features.evidence import explain_shared_lines
    from generators import (
        LocalizedDefect,
        OperatingCondition,
        SimulationSettings,
        bearing,
        simulate,
    )

    g = bearing("6205")
    op = OperatingCondition.from_rpm(1797, 400.0, random_slip=0.01)
    pit = LocalizedDefect(surface="inner", length=0.3e-3, depth=0.1e-3)
    settings = SimulationSettings(fs=12000.0, duration=2.0, channels=("housing_acceleration_y",))
    x = simulate(g, op, pit, settings=settings, random_state=1)["housing_acceleration_y"]
    d = diagnose_signal(x, 12000.0, 1797.0, g)
    assert d.verdict == "inner race"
    ball = next(c for c in d.candidates if c["fault"] == "ball")
    assert not ball["detected"], ball
    assert {(e["line"], e["by"]) for e in ball["explained"]} == {
        ("3x", "inner race"),
        ("1x-", "inner race"),
    }
    # weighed with those lines, the ball would have been a detected fault
    ctx = {k: d.frequencies[k] for k in ("shaft", "ftf", "bpfo", "bpfi", "two_bsf")}
    evidence = features.fault_evidence(x, 12000.0, ctx)
    family = evidence.families["two_bsf"]
    floor = min(fam[0][1][3] for fam in evidence.families.values())
    df = float(evidence.envelope_frequencies[1])
    bands = len(evidence.selection.bands)
    alone = explain_shared_lines({"two_bsf": family}, bands, family[0][1][2], floor, df)
    assert alone["two_bsf"]["evidence_db"] >= d.threshold_db > ball["evidence_db"]
    import cmtool.plots

    figures = []
    close = cmtool.plots.plt.close
    monkeypatch.setattr(cmtool.plots.plt, "close", lambda fig: figures.append(fig))
    report = write_report(d, tmp_path, title="inner race pit", x=x, fs=12000.0)
    monkeypatch.setattr(cmtool.plots.plt, "close", close)
    assert "3x: inner race 3x" in report.read_text()
    # the envelope plot marks the verdict's lines, solid, over its whole span (to 5 x BPFI),
    # and the shaft-rate sidebands of the first three
    envelope = next(f for f in figures if "envelope spectrum" in f.axes[0].get_title())
    ax = envelope.axes[0]
    assert [t.get_text() for t in ax.get_legend().get_texts()].count("bpfi (verdict)") == 1
    lines = [line for line in ax.get_lines() if len(set(line.get_xdata())) == 1]
    solid = sorted(line.get_xdata()[0] for line in lines if line.get_linestyle() == "-")
    dotted = sorted(line.get_xdata()[0] for line in lines if line.get_linestyle() == ":")
    bpfi, shaft = d.frequencies["bpfi"], d.frequencies["shaft"]
    span = ax.get_xlim()[1]
    assert span == pytest.approx(5 * bpfi)
    np.testing.assert_allclose(solid, [k * bpfi for k in range(1, 6)])
    np.testing.assert_allclose(
        dotted, sorted(h * bpfi + s * shaft for h in (1, 2, 3) for s in (-1, 1))
    )
    for fig in figures:
        close(fig)


@pytest.mark.validation
def test_clean_healthy_simulations_across_the_catalog_are_healthy():
    """Issue 18's 95 % on clean ``simulate`` runs, beyond one bearing and speed.

    Every catalog bearing at 600-3000 rpm, 100-2000 N, 12-48 kHz, noise-free, default
    settings. Before the harmonic families were fitted jointly 17 of these 24 were called
    "outer race": a ball-pass harmonic half a bin from a shaft harmonic was shared between
    the two fits and left in, and the step-rate alias products of the integration (50 dB
    under the RMS at 600 rpm, 2000 N) stood above a 60 dB instrument floor.
    """
    import itertools

    from generators import OperatingCondition, SimulationSettings, bearing, simulate

    loads, rates = (100.0, 500.0, 2000.0), (12000.0, 25600.0, 48000.0)
    grid = itertools.product(
        ("6205", "6203", "6305", "6002", "6308", "mfpt"), (600, 1200, 1797, 3000)
    )
    wrong = []
    for i, (name, rpm) in enumerate(grid):
        load, fs = loads[i % 3], rates[(i // 3 + i) % 3]
        g = bearing(name)
        settings = SimulationSettings(fs=fs, duration=1.0, channels=("housing_acceleration_y",))
        x = simulate(g, OperatingCondition.from_rpm(rpm, load), settings=settings)
        verdict = diagnose_signal(x["housing_acceleration_y"], fs, rpm, g).verdict
        if verdict != "healthy":
            wrong.append((name, rpm, load, fs, verdict))
    assert len(wrong) <= 1, wrong  # 95 % of 24


@pytest.mark.parametrize("ehl", [True, False])
def test_a_noise_free_records_faint_content_does_not_move_its_fault_rates(ehl):
    """A clean healthy 6205 (5 um clearance, 2880 rpm, 400 N, 12 kHz, 1 s) has no shaft line:
    within 6 % of the shaft rate its spectrum holds nothing over 140 dB under its RMS. A
    peak of that, at 45 Hz, was taken for the 1x line 6.3 % under the speed given: `auto`
    moved every fault rate there, the ball-pass harmonics stayed in the random part and the
    rule said "outer race" at confidence 1.00. Over a good chain's floor no line stands out:
    the speed given is kept, and it is healthy."""
    from generators import OperatingCondition, Scene, SimulationSettings, bearing, simulate

    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(2880, 400.0)
    x = simulate(g, op, scene=Scene(level="shaft", ehl=ehl), settings=settings)
    d = diagnose_signal(x["housing_acceleration_y"], 12000.0, 2880, g)
    assert d.assumptions["spectrum_rpm"] is None and d.assumptions["rpm"] == 2880
    assert d.verdict == "healthy", (d.verdict, d.warnings)


@pytest.mark.parametrize(
    ("name", "rpm", "load", "clearance", "level", "ehl"),
    [
        ("6002", 879, 116.0, 40e-6, "full", False),
        ("6002", 4638, 2800.0, 40e-6, "shaft+housing", False),
        ("6205", 2880, 408.0, 5e-6, "shaft", False),
        ("6305", 1042, 557.0, 10e-6, "full", False),
        ("6308", 6586, 174.0, 20e-6, "full", False),
        ("6203", 1468, 429.0, 20e-6, "shaft", True),
        ("6203", 5089, 434.0, 2e-6, "shaft+housing", True),
        ("6002", 1314, 1752.0, 40e-6, "shaft", True),
        ("mfpt", 1701, 3599.0, 40e-6, "full", False),
    ],
)
def test_clean_healthy_simulations_out_to_the_models_extremes_are_healthy(
    name, rpm, load, clearance, level, ehl
):
    """Issue 18's 95 % beyond the catalog's defaults (benchmarks/sweep_healthy_extremes.py:
    312 of 319 healthy). These nine, drawn by the sweep at 12 kHz (the 6002 at 4638 rpm drawn
    at 4230 N, here under its C0r), were all called faulty when a peak 128-159 dB under the
    RMS was taken for the shaft's line and moved the fault rates (checked: each fails so)."""
    from generators import OperatingCondition, Scene, SimulationSettings, bearing, simulate

    g = bearing(name, radial_internal_clearance=clearance)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(rpm, load)
    x = simulate(g, op, scene=Scene(level=level, ehl=ehl), settings=settings)
    d = diagnose_signal(x["housing_acceleration_y"], 12000.0, rpm, g, waviness=False)
    assert d.verdict == "healthy", (d.verdict, d.warnings)


def test_rule_and_model_give_one_verdict_that_says_what_it_rests_on(bundle, small):
    from cmtool.diagnose import calibrated_confidence, rule_probabilities

    row = small[small["label"] == "healthy"].iloc[0]
    d = diagnose_signal(row["signal"], row["fs_hz"], row["rpm"], "6205", model=bundle)
    assert d.rule_verdict["label"] == "healthy"
    assert set(d.probabilities) == {"healthy", "inner race", "outer race", "ball"}
    assert sum(d.probabilities.values()) == pytest.approx(1.0, abs=1e-3)
    assert d.verdict == max(d.probabilities, key=d.probabilities.get)
    # the pooled verdict's confidence goes through the model's own calibration
    calibration = bundle.get("pooled_calibration")
    expected = calibrated_confidence(d.probabilities[d.verdict], calibration)
    assert d.confidence == pytest.approx(expected, abs=2e-3)
    assert ("calibrated" in d.basis) == bool(calibration)
    model_says = {"healthy": "healthy"}.get(d.model_verdict["label"], d.model_verdict["label"])
    assert ("agree" in d.basis) == (model_says == "healthy")
    # the rule's own probabilities: a clear line makes its fault likely, none makes healthy
    clear = [
        {"fault": "outer race", "confidence": 0.99},
        {"fault": "inner race", "confidence": 0.01},
        {"fault": "ball", "confidence": 0.02},
    ]
    p = rule_probabilities(clear)
    assert max(p, key=p.get) == "outer race" and p["outer race"] > 0.9
    quiet = [dict(c, confidence=0.01) for c in clear]
    assert max(rule_probabilities(quiet), key=rule_probabilities(quiet).get) == "healthy"
    # disagreement is stated
    disagree = diagnose_signal(row["signal"], row["fs_hz"], row["rpm"], "6205")
    disagree.model_verdict = {"label": "outer", "probabilities": {"outer": 0.9, "healthy": 0.1}}
    from cmtool.pooling import combine_verdicts

    combine_verdicts(disagree)
    assert "disagree" in disagree.basis and "outer race (0.90)" in disagree.basis


def test_a_model_trained_on_waviness_reads_it_as_no_local_fault(bundle):
    """``datasets/small``'s classes are race and ball waviness: ``cmtool train`` records that
    (``class_kinds``), and ``diagnose`` pools the model's waviness classes as healthy, not as
    a local fault of that surface. The demo's fresh inner-race waviness (N_w = 9, 2100 rpm,
    550 N) was "inner race" by rule and model together; it is healthy, the model's reading
    stated. A bundle without the kinds (older files) reads labels by name, as before."""
    from cmtool.diagnose import model_label_verdict, verdict_probabilities
    from generators import (
        OperatingCondition,
        Scene,
        SimulationSettings,
        Waviness,
        bearing,
        simulate,
    )

    kinds = bundle["class_kinds"]
    assert kinds == {"healthy": "none", **{k: "waviness" for k in ("inner", "outer", "ball")}}
    assert model_label_verdict("inner", kinds) == "healthy"
    assert model_label_verdict("inner") == "inner race"
    assert verdict_probabilities({"inner": 0.7, "healthy": 0.3}, kinds) == {"healthy": 1.0}
    g = bearing("6205")
    fresh = simulate(
        g,
        OperatingCondition.from_rpm(2100, 550.0),
        [Waviness(surface="inner", order=9, amplitude=1e-6)],
        scene=Scene(level="shaft+housing", ehl=True),
        settings=SimulationSettings(fs=6400.0, duration=1.0, settle_time=0.1),
        random_state=1,
    )
    x = fresh["housing_acceleration_y"]
    x = x + np.random.default_rng(1).normal(0, 10 ** (-10 / 20) * x.std(), x.size)
    d = diagnose_signal(x, fresh.fs, 2100.0, g, model=bundle)
    assert d.model_verdict["label"] == "inner"
    assert d.verdict == "healthy", d.basis
    assert "the model reads inner waviness" in d.basis
    old = {k: v for k, v in bundle.items() if k != "class_kinds"}
    before = diagnose_signal(x, fresh.fs, 2100.0, g, model=old)
    assert before.verdict == "inner race"  # what the demo said until stop 39


def test_a_model_that_learnt_no_local_fault_does_not_hide_one(bundle):
    """datasets/small's model learnt waviness only: it has no class for any local fault, so it
    cannot weigh against one. A 0.3 mm inner-race pit that the rule finds keeps the rule's
    verdict and confidence, and the basis says why (until stop 52 the pooled verdict was
    "healthy", 0.50: with a model that learnt no local fault, none could be reported)."""
    from generators import (
        LocalizedDefect,
        OperatingCondition,
        SimulationSettings,
        bearing,
        simulate,
    )

    g = bearing("6205")
    op = OperatingCondition.from_rpm(1797, 400.0, random_slip=0.01)
    pit = LocalizedDefect(surface="inner", length=0.3e-3, depth=0.1e-3)
    settings = SimulationSettings(fs=6400.0, duration=1.0, channels=("housing_acceleration_y",))
    x = simulate(g, op, [pit], settings=settings, random_state=3)["housing_acceleration_y"]
    alone = diagnose_signal(x, 6400.0, 1797, g)
    assert alone.verdict == "inner race"
    pooled = diagnose_signal(x, 6400.0, 1797, g, model=bundle)
    assert pooled.model_verdict["label"] != "inner"  # the model reads some waviness
    assert (pooled.verdict, pooled.confidence) == (alone.verdict, alone.confidence)
    assert "the model learnt no inner race: the verdict and confidence are the rule's" in (
        pooled.basis
    )


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="issue 18: lattice lines m f_s + n BPFO of a wavy bearing leak into the random part "
    "(docs/diagnosis.md, 'Waviness read as a local fault')",
)
def test_inner_race_waviness_across_speeds_is_no_local_fault():
    """Inner-race waviness N_w = 9 (1 um) is periodic, no local fault: at 900 rpm (25.6 kHz) and
    1500 rpm (12 kHz), 500 N, 5 % noise, the rule detector should call it healthy. It calls
    both "outer race" (benchmarks/sweep_waviness_verdicts.py: 2 of 24 such cases healthy at
    stop 31; 13 of 24 since stop 72 fits the race's lattice slices, the 900 rpm cases and
    some at 1500 rpm still not, their slices beyond what a 1 s record resolves). With the
    film's entrainment at light load (an option since stop 73, docs/model.md 4.6) both are
    healthy: tests_generators/test_entrainment.py."""
    from generators import OperatingCondition, SimulationSettings, Waviness, bearing, simulate

    g = bearing("6205")
    noise = np.random.default_rng(18)
    verdicts = []
    for rpm, fs in ((900, 25600.0), (1500, 12000.0)):
        settings = SimulationSettings(fs=fs, duration=1.0, channels=("housing_acceleration_y",))
        op = OperatingCondition.from_rpm(rpm, 500.0)
        wav = Waviness(surface="inner", order=9, amplitude=1e-6)
        x = simulate(g, op, wav, settings=settings, random_state=3)["housing_acceleration_y"]
        x = x + noise.normal(0.0, 0.05 * np.std(x), x.size)
        verdicts.append(diagnose_signal(x, fs, rpm, g).verdict)
    assert verdicts == ["healthy", "healthy"]


@pytest.mark.parametrize("rig_name", ["default", "heavy"])
def test_inner_race_waviness_of_z_lobes_is_no_outer_race_fault_at_2400_rpm(
    rig_name, monkeypatch, tmp_path, capsys
):
    """Inner-race waviness of Z = 9 lobes (1 um, 500 N, 2400 rpm, 12 kHz, 5 % noise) puts its
    lines on the series k BPFI + n BPFO, whose beats fall at BPFO: fitted as slices of the
    line lattice where the record holds them (features.lattice), it is healthy; without the
    slices the rule reads it as an outer-race fault (docs/diagnosis.md, stop 72)."""
    import features.evidence
    from generators import (
        OperatingCondition,
        Rig,
        SimulationSettings,
        Waviness,
        bearing,
        characteristic_frequencies,
        simulate,
    )

    rigs = {
        "default": Rig(),
        "heavy": Rig(housing_mass=6.0, pedestal_stiffness=2e8, shaft_mass=2.5),
    }
    g = bearing("6205")
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(2400, 500.0)
    wav = Waviness(surface="inner", order=9, amplitude=1e-6)
    x = simulate(g, op, wav, rig=rigs[rig_name], settings=settings, random_state=3)
    x = x["housing_acceleration_y"]
    x = x + np.random.default_rng(72).normal(0.0, 0.05 * np.std(x), x.size)
    d = diagnose_signal(x, 12000.0, 2400, g, waviness=False)
    assert d.verdict == "healthy"
    # the assumptions say which series k BPFI + n BPFO were fitted (k = 1 among them)
    assert (
        1 in d.assumptions["lattice_slices"]
        and "k BPFI + n BPFO" in d.assumptions["band_selection"]
    )
    # the library's automatic band offers the same slices: the command's band
    f = characteristic_frequencies(g, 40.0)
    rates = {"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf, "shaft": f.shaft}
    _, _, band = features.envelope_spectrum(x, 12000.0, fault_frequencies=rates, return_band=True)
    assert band == pytest.approx(d.band_hz)
    # the command's text states the slices fitted, as the JSON does
    np.save(tmp_path / "wavy.npy", x)
    argv = ["diagnose", str(tmp_path / "wavy.npy"), "--fs", "12000", "--rpm", "2400"]
    argv += ["--bearing", "6205"]
    assert main(argv) == 0
    said = [line for line in capsys.readouterr().out.splitlines() if "k BPFI + n BPFO" in line]
    assert len(said) == 1 and "k = +1, -1" in said[0], said
    monkeypatch.setattr(features.evidence, "inner_race_lattice_offsets", lambda *args: ())
    monkeypatch.setattr(features.evidence, "inner_race_lattice_orders", lambda *args: ())
    without = diagnose_signal(x, 12000.0, 2400, g, waviness=False)
    assert without.verdict == "outer race" and without.assumptions["lattice_slices"] == []
    assert main(argv) == 0
    assert "k BPFI + n BPFO" not in capsys.readouterr().out  # none held, none stated


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="issue 18: a bearing's own form errors (0.1 um on the inner race or the balls) make "
    "impulsive events at multiples of 1/BPFO that the rule reads as a local fault "
    "(docs/diagnosis.md, 'Form errors read as a local fault')",
)
def test_a_healthy_bearing_with_form_errors_is_no_local_fault():
    """A healthy 6205 whose inner race and balls carry ordinary form errors (0.1 um at order Z
    and order 2, generators.form_waviness), 1797 rpm, clearance 5 um, 100 and 400 N, should be
    called healthy. The rule calls them "outer race" (stop 32: margins 12-32 dB over the
    threshold; the same bearing perfect or with outer-race form errors: healthy). With the
    film's entrainment (stop 73, an option) most are healthy in noise, not all noise-free:
    benchmarks/entry_kink.py."""
    from generators import OperatingCondition, SimulationSettings, bearing, form_waviness, simulate

    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    verdicts = []
    for load in (100.0, 400.0):
        op = OperatingCondition.from_rpm(1797, load)
        for form in (form_waviness(9, 1e-7, 0.0, 0.0), form_waviness(9, 0.0, 0.0, 1e-7)):
            x = simulate(g, op, form, settings=settings, random_state=2)["housing_acceleration_y"]
            verdicts.append(diagnose_signal(x, 12000.0, 1797, g, waviness=False).verdict)
    assert verdicts == ["healthy"] * 4


@pytest.mark.parametrize("rpm, load_n", [(370, 62.0), (526, 1583.0)])
def test_a_clean_lubricated_bearing_with_ball_masses_is_healthy_at_low_speed(rpm, load_n):
    """Scene full with its film at 370 and 526 rpm (6205, 5 um, 12 kHz, noise-free): healthy.
    Until the film between ball and race apart was modelled its unloaded balls chattered, and
    the rule read their aperiodic impacts as an outer-race fault (docs/model.md 7.4)."""
    from generators import OperatingCondition, Scene, SimulationSettings, bearing, simulate

    g = bearing("6205", radial_internal_clearance=5e-6)
    settings = SimulationSettings(fs=12000.0, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(rpm, load_n)
    x = simulate(g, op, scene=Scene(level="full", ehl=True), settings=settings)
    d = diagnose_signal(x["housing_acceleration_y"], 12000.0, rpm, g, load_n=load_n)
    assert d.verdict == "healthy", d.basis


def test_race_waviness_is_reported_against_a_healthy_baseline():
    """Outer-race waviness N_w = 9 (2 um) against the same machine healthy: a waviness hint of
    the right surface and order far over the baseline, and the ISO 15242 low band up."""
    from generators import (
        OperatingCondition,
        SimulationSettings,
        Waviness,
        bearing,
        simulate,
    )

    g = bearing("6205")
    settings = SimulationSettings(fs=25600.0, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(1800, 500.0)
    noise = np.random.default_rng(1)
    signals = []
    for wav in (None, Waviness(surface="outer", order=9, amplitude=2e-6)):
        x = simulate(g, op, wav, settings=settings)["housing_acceleration_y"]
        signals.append(x + noise.normal(0.0, 0.1 * np.std(x), x.size))
    healthy, wavy = signals
    d = diagnose_signal(wavy, 25600.0, 1800.0, g, baseline=healthy)
    assert d.verdict == "healthy"  # waviness is no local fault
    assert d.waviness["surface"] == "outer" and d.waviness["order"] == 9
    assert d.waviness["over_baseline_db"] > 20
    change = d.baseline["velocity_bands_change_db"]
    assert change["low"] > 10 and set(change) == {"low", "medium", "high"}
    same = diagnose_signal(healthy, 25600.0, 1800.0, g, baseline=healthy)
    assert all(abs(v) < 1e-9 for v in same.baseline["velocity_bands_change_db"].values())


def test_race_waviness_without_a_baseline_is_judged_against_the_models_healthy_lines():
    """Through rigs other than the model's (housings of 0.8 and 6 kg, other pedestals), with
    the load unknown (assumed 500 N, the prediction spanning 125-2000 N): a healthy bearing at
    2000 N, whose 3 BPFI - 2 f_s line a single 500 N prediction took for inner-race waviness
    of order 25, reports none; inner (order 8) and outer (order 18) race waviness are
    reported with their surface and order, over the prediction."""
    from cmtool.waviness import MODEL_EXCESS_DB
    from generators import OperatingCondition, Rig, SimulationSettings, Waviness, bearing, simulate

    g = bearing("6205")
    fs = 25600.0
    settings = SimulationSettings(fs=fs, duration=1.0, channels=("housing_acceleration_y",))
    noise = np.random.default_rng(5)

    def diagnose(rig, rpm, load, waviness):
        op = OperatingCondition.from_rpm(rpm, load)
        x = simulate(g, op, waviness, settings=settings, rig=rig)["housing_acceleration_y"]
        x = x + noise.normal(0.0, 0.1 * np.std(x), x.size)
        return diagnose_signal(x, fs, rpm, g)

    light = Rig(housing_mass=0.8, pedestal_stiffness=2e7)
    heavy = Rig(housing_mass=6.0, pedestal_stiffness=2e8, shaft_mass=2.5)
    healthy = diagnose(light, 1200, 2000.0, None)
    assert healthy.verdict == "healthy" and healthy.waviness is None
    assert "125-2000 N" in healthy.assumptions["waviness_reference"]
    inner = diagnose(heavy, 1800, 500.0, Waviness(surface="inner", order=8, amplitude=0.5e-6))
    assert inner.waviness["surface"] == "inner" and inner.waviness["order"] == 8
    assert inner.waviness["over_model_db"] > 20
    outer = diagnose(light, 3000, 500.0, Waviness(surface="outer", order=18, amplitude=1e-6))
    assert outer.waviness["surface"] == "outer" and outer.waviness["order"] == 18
    # a line the healthy bearing also has (2 BPFO): over the largest healthy share of 125-2000 N
    assert outer.waviness["over_model_db"] > MODEL_EXCESS_DB


def test_plain_line_false_alarm_bounds_what_noise_makes_in_a_plain_spectrum():
    """A Hann-windowed amplitude spectrum of white noise: the lines it makes at a 6205's race
    waviness candidates (cmtool.waviness' bins) stand at least as high as a probability of
    1e-2 or 1e-3 says at most about as often as that (measured 0.36-0.88 of it), in 1 s and in
    10 s records (the envelope's calibrated model undercounts the 10 s ones by 1.6x at 1e-2)."""
    import features
    from cmtool.waviness import _line, candidate_lines, line_false_alarm
    from generators import bearing
    from generators.kinematics import characteristic_frequencies

    geometry = bearing("6205")
    lines = [c.frequency for c in candidate_lines(characteristic_frequencies(geometry, 29.95), 9)]
    rng = np.random.default_rng(2048)
    for seconds, records in ((1.0, 300), (10.0, 60)):
        p = []
        for _ in range(records):
            f, a = features.amplitude_spectrum(rng.standard_normal(int(12000 * seconds)), 12000.0)
            p += [line_false_alarm(f, line, _line(f, a, line)[0]) for line in lines]
        p = np.array(p)
        for nominal in (1e-2, 3e-3):
            measured = np.mean(p <= nominal)
            assert 0.2 * nominal < measured < 1.2 * nominal, (seconds, nominal, measured)


def test_white_noise_gives_no_waviness_hint():
    """Gaussian noise has no lines: 12 dB over the floor alone let 3-5 % of 1 s noise records
    through as waviness (these two among them: "inner race, order 6, 99 dB over its healthy
    share"); the candidates' false-alarm test keeps them at about 1e-3 of records."""
    from generators import bearing

    g = bearing("6205")
    for x in (
        np.random.default_rng(28).standard_normal(12000),
        np.random.default_rng(0).standard_normal((12000, 2))[:, 0],
    ):
        d = diagnose_signal(x, 12000.0, 1797.0, g)
        assert d.waviness is None, d.waviness


def test_a_faint_line_of_a_noise_free_record_is_no_race_waviness():
    """A noise-free record has no floor of its own: a line 100 dB under its RMS stood far over
    its local floor, and 26 of 164 healthy verdicts of clean simulations carried a waviness
    hint. Read over a good chain's floor (cmtool.waviness.chain_floor, the median of white
    noise INSTRUMENT_FLOOR_DB under the RMS), that line is none; the same line 40 dB under
    the RMS is read, with its surface and order."""
    import features
    from cmtool.waviness import candidate_lines, chain_floor, race_waviness
    from generators import bearing, characteristic_frequencies

    fs, n = 12000.0, 12000
    t = np.arange(n) / fs
    g = bearing("6205")
    freqs = characteristic_frequencies(g, 29.95)
    healthy = sum(np.sin(2 * np.pi * q * freqs.bpfo * t + q) for q in (1, 2, 3))
    reference = [features.amplitude_spectrum(healthy, fs)]  # the healthy lines, as a baseline
    # the highest inner-race candidate (3 BPFI + 3 f_s, 576 Hz): far from the lines' skirts
    inner = max(
        (c for c in candidate_lines(freqs, 9) if c.surface == "inner"), key=lambda c: c.frequency
    )
    rms = np.std(healthy)
    white = np.random.default_rng(7).normal(0.0, rms * 10 ** (-50 / 20), n)
    median = np.median(features.amplitude_spectrum(white, fs)[1][10:-10])
    assert median == pytest.approx(chain_floor(rms, n), rel=0.05)
    for bad, match in (((-1.0, n), "rms = -1.0"), ((np.nan, n), "rms = nan"), ((rms, 3), "n = 3")):
        with pytest.raises(features.FeatureError, match=match):
            chain_floor(*bad)
    for level_db, read in ((-100.0, False), (-40.0, True)):
        line = np.sqrt(2) * rms * 10 ** (level_db / 20) * np.sin(2 * np.pi * inner.frequency * t)
        f, a = features.amplitude_spectrum(healthy + line, fs)
        assert race_waviness(f, a, freqs, g, reference)["order"] == inner.order  # local floor
        found = race_waviness(f, a, freqs, g, reference, chain_floor(np.std(healthy + line), n))
        assert (found is not None) is read, (level_db, found)
        if read:
            assert (found["surface"], found["order"]) == ("inner", inner.order)
    # and in diagnose_signal: a clean healthy 6203 (20 um, 2736 rpm, 829 N given, dry, scene
    # shaft) whose line 87 dB under its RMS was read as inner-race waviness of order 27
    from generators import OperatingCondition, Scene, SimulationSettings, simulate

    g = bearing("6203", radial_internal_clearance=20e-6)
    settings = SimulationSettings(fs=25600.0, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(2736, 829.0)
    x = simulate(g, op, scene=Scene(level="shaft", ehl=False), settings=settings)
    d = diagnose_signal(x["housing_acceleration_y"], 25600.0, 2736, g, load_n=829.0)
    assert d.verdict == "healthy" and d.waviness is None, d.waviness


def test_a_mains_harmonic_is_not_read_as_race_waviness():
    """The MFPT bearing's BPFI at a 25 Hz shaft, 118.88 Hz, lies 1.1 bins from the 120 Hz mains
    harmonic in a 1 s record: a healthy bearing with a strong 120 Hz line gets no waviness
    hint (it did: inner race, order 8); inner-race waviness of order 9 (BPFI + f_s, 143.9 Hz)
    with the same mains line is still reported; in a 4 s record 120 Hz is told from BPFI."""
    from cmtool.waviness import mains_harmonic_near
    from generators import OperatingCondition, SimulationSettings, Waviness, bearing, simulate

    g = bearing("mfpt")
    fs = 25600.0
    settings = SimulationSettings(fs=fs, duration=1.0, channels=("housing_acceleration_y",))
    op = OperatingCondition.from_rpm(1500, 1000.0)
    noise = np.random.default_rng(7)

    def diagnose(waviness):
        x = simulate(g, op, waviness, settings=settings)["housing_acceleration_y"]
        t = np.arange(x.size) / fs
        mains = 2.0 * np.std(x) * np.sin(2 * np.pi * 120.0 * t)
        return diagnose_signal(x + mains + noise.normal(0.0, 0.1 * np.std(x), x.size), fs, 1500, g)

    healthy = diagnose(None)
    assert healthy.verdict == "healthy" and healthy.waviness is None
    wavy = diagnose(Waviness(surface="inner", order=9, amplitude=1e-6))
    assert wavy.waviness["surface"] == "inner" and wavy.waviness["order"] == 9
    bpfi = 118.876
    assert mains_harmonic_near(bpfi, 1.0) == 120.0
    assert mains_harmonic_near(bpfi, 0.25) is None


@pytest.fixture(scope="module")
def bundle_by_label_names(small_dataset):
    """``cmtool train`` on a quarter of ``datasets/small`` without its ``defect_kind``
    column: the labels read by name (inner -> inner race), as every bundle did before stop
    39. (Forests of 30 trees: the test reads the calibration's fit, not the model's skill.)"""
    from cmtool.classifier import train

    part = small_dataset.drop(columns="defect_kind").groupby("label").head(24)
    with pytest.MonkeyPatch.context() as monkeypatch:
        _use_light_forests(monkeypatch)
        return train(part.reset_index(drop=True), n_splits=3)


def test_the_pooled_verdicts_confidence_is_calibrated_at_training(bundle, bundle_by_label_names):
    """``cmtool train`` fits P(the pooled verdict is right) on its out-of-fold predictions and
    the rule evidence of every signal, the faint faults left out of training included. (On
    ``datasets/small`` as it is, whose classes are waviness, the model learnt no local fault
    and the rule alone weighs those: its local-fault calls on wavy bearings, 19 of the 144,
    are the pooled verdicts that are wrong, and the calibration is fitted on all 192 signals;
    until stop 52 every pooled verdict there was healthy, and none was fitted.)"""
    from cmtool.diagnose import calibrated_confidence

    assert bundle["pooled_calibration"]["signals"] == 192
    calibration = bundle_by_label_names["pooled_calibration"]
    assert bundle_by_label_names["class_kinds"] == {}
    assert calibration["signals"] == 4 * 24
    assert calibration["slope"] > 0  # a more probable pooled verdict is more often right
    # the logistic fit does not make the in-sample calibration worse (10-bin ECE)
    assert calibration["ece_calibrated"] <= calibration["ece_pooled"] + 0.02
    # the mapping: identity without a calibration, monotone with one, inside (0, 1)
    assert calibrated_confidence(0.37, None) == 0.37
    values = [calibrated_confidence(p, calibration) for p in (0.3, 0.5, 0.7, 0.9, 0.99)]
    assert all(0.0 < v < 1.0 for v in values) and values == sorted(values)


def test_train_on_two_workers_makes_the_same_model_and_reports_its_progress(
    small, light_forests, monkeypatch
):
    """``train(workers=2)`` extracts the features and weighs the rule detector's evidence for
    the pooled calibration in two processes, chunk by chunk, then fits the models in two
    processes: the bundle is the one a single process makes (scores, out-of-fold
    predictions, calibration, extrapolation, probabilities on other signals), and each pass
    reports its progress up to its total. (Chunks of 5 signals per worker here, so that
    several chunks meet their order; the labels read by name, so that a calibration is
    fitted: see the test above.)"""
    from sklearn.ensemble import ExtraTreesClassifier

    import cmtool.classifier as classifier_module
    from cmtool.fits import FIT_STAGE

    monkeypatch.setattr(classifier_module, "PROGRESS_CHUNK", 5)
    part = small.drop(columns="defect_kind").groupby("label").head(12).reset_index(drop=True)
    reports: list[tuple[str, int, int]] = []
    one = classifier_module.train(part, n_splits=3, workers=1)
    two = classifier_module.train(
        part, n_splits=3, workers=2, progress=lambda *r: reports.append(r)
    )
    assert one["pooled_calibration"] is not None and one["extrapolation"]
    for key in ("scores", "cv_predictions", "pooled_calibration", "extrapolation"):
        assert one[key] == two[key], key
    assert one["feature_names"] == two["feature_names"]
    other = small.groupby("label").tail(3)
    np.testing.assert_array_equal(
        one["pipeline"].predict_proba(other), two["pipeline"].predict_proba(other)
    )
    # one pass: each signal's features and the rule's evidence for the calibration (one
    # fault_evidence serves both); 48 signals in chunks of 5 x 2
    features_stage = [r for r in reports if r[0] != FIT_STAGE]
    assert features_stage == [
        ("features and rule evidence", done, 48) for done in (10, 20, 30, 40, 48)
    ]
    # then every fit, one by one: each candidate on each fold, the kept one without each end
    # of the speed and load ranges, and on everything
    fits = 4 * 3 + len(one["extrapolation"]) + 1
    expected = [(FIT_STAGE, done, fits) for done in range(1, fits + 1)]
    assert reports[len(features_stage) :] == expected
    # the kept model keeps its candidate's parameters; a model made for threads is fitted on
    # one and given its threads back (for predicting)
    kept = two["pipeline"].steps[-1][1].get_params()
    assert kept == classifier_module.candidate_classifiers()[two["best"]].get_params()
    threads = ExtraTreesClassifier(n_estimators=30, n_jobs=-1)
    forest = classifier_module.fit_single_threaded(threads, np.eye(4), np.arange(4))
    assert forest.get_params()["n_jobs"] == -1 and len(forest.estimators_) == 30
    assert not hasattr(threads, "estimators_")  # the one given is left as it came


def test_model_fits_in_workers_raise_their_warnings_here_once():
    """A warning a fit raises in a worker process reaches the caller, once per message, and
    the results come back in the calls' order."""
    from cmtool.fits import run_fits

    def warn_and_square(value: int) -> int:  # a local function: sent to the workers whole
        import warnings

        warnings.warn(f"fit {value}", UserWarning, stacklevel=1)
        return value * value

    calls = [(warn_and_square, (v,)) for v in (3, 1, 2, 1)]
    with pytest.warns(UserWarning) as caught:
        assert run_fits(calls, workers=2) == [9, 1, 4, 1]
    assert sorted(str(w.message) for w in caught) == ["fit 1", "fit 2", "fit 3"]


def test_train_weighs_each_signals_evidence_once(small, light_forests, monkeypatch):
    """The features' ``fault_evidence`` of a signal is the rule's own for the calibration
    (the dataset's rates are the ones the rule computes from the bearing and the speed), so
    ``train`` computes it once per signal, not twice; where a dataset's rates differ, the rule
    computes its own and the calibration is still the rule's."""
    import cmtool.classifier as classifier_module
    import features.transformer as transformer_module

    calls = []
    shipped = features.fault_evidence

    def counting(x, fs, ctx):
        calls.append(fs)
        return shipped(x, fs, ctx)

    monkeypatch.setattr(transformer_module, "fault_evidence", counting)
    monkeypatch.setattr(features, "fault_evidence", counting)
    part = small.drop(columns="defect_kind").groupby("label").head(6).reset_index(drop=True)
    once = classifier_module.train(part, n_splits=3)
    assert len(calls) == len(part)
    calls.clear()
    shifted = part.assign(bpfo_hz=part["bpfo_hz"] * (1 + 1e-12))
    twice = classifier_module.train(shifted, n_splits=3)
    assert len(calls) == 2 * len(part)
    assert twice["pooled_calibration"] == once["pooled_calibration"]


def test_a_recipe_names_the_classifier_train_keeps(small, light_forests):
    """``[training] classifier`` in the dataset's recipe is what ``train`` keeps by default
    (the rig recipes name the one that carried over between simulated rigs); without it, or
    with ``classifier=None``, the best grouped cross-validation score; a name that is not a
    candidate is refused, by ``train`` and by the recipe validator, naming the key. (The
    forests have 30 trees here: the test is about which candidate is kept, not how well.)"""
    import tomllib

    from cmtool.classifier import recipe_classifier, train
    from generators.recipe import validate_recipe

    part = small.groupby("label").head(16).reset_index(drop=True)
    named = '[training]\nclassifier = "random_forest"\n'
    assert recipe_classifier(named) == "random_forest" and recipe_classifier("x = [") is None
    kept = train(part, recipe=named, n_splits=3)
    assert kept["best"] == "random_forest"
    best = train(part, recipe=named, n_splits=3, classifier=None)
    assert best["best"] == max(best["scores"], key=best["scores"].get)
    assert kept["scores"] == best["scores"]  # every candidate is scored either way
    with pytest.raises(ValueError, match="classifier = 'svm'"):
        train(part, n_splits=3, classifier="svm")
    for name in ("cwru-rig", "mfpt-rig", "universal"):
        text = (REPO / "datasets" / f"{name}.toml").read_text()
        assert recipe_classifier(text) == "extra_trees"
        bad = tomllib.loads(text.replace('classifier = "extra_trees"', 'classifier = "svm"'))
        with pytest.raises(ValueError, match="training.classifier"):
            validate_recipe(bad)


def test_candidates_are_weighed_by_class_and_ranked_by_balanced_accuracy():
    """Every candidate weighs classes by their counts (a ball class thinned by the fault-SNR
    filter must not lose to "healthy" by its size), and the grouped CV score is the balanced
    accuracy: a model that calls everything the majority class scores 1 / classes, not the
    majority's share."""
    from sklearn.dummy import DummyClassifier

    from cmtool.classifier import CLASS_WEIGHT, _grouped_cv, candidate_classifiers

    assert CLASS_WEIGHT == "balanced"
    for name, clf in candidate_classifiers().items():
        assert clf.get_params()["class_weight"] == CLASS_WEIGHT, name
    rng = np.random.default_rng(0)
    y = np.array(["healthy"] * 80 + ["ball"] * 10 + ["inner"] * 10)
    X = rng.normal(size=(y.size, 3))
    groups = np.arange(y.size) % 10
    score, predicted = _grouped_cv(X, y, groups, DummyClassifier(strategy="most_frequent"), 5)
    assert (predicted == "healthy").all()
    assert score == pytest.approx(1 / 3)  # plain accuracy would be 0.8


def test_the_calibration_from_the_cross_validations_fits_is_the_one_it_fits_itself():
    """``train`` hands ``pooled_calibration`` the out-of-fold probabilities its grouped
    cross-validation already has (one fit per fold, not two): the same calibration, to the
    bit, as fitting the folds again, with signals left out of training (each scored by
    every fold's model) and a class one fold never saw."""
    from sklearn.ensemble import RandomForestClassifier

    from cmtool.classifier import _out_of_fold, pooled_calibration

    rng = np.random.default_rng(2)
    y = np.array(["healthy"] * 30 + ["outer"] * 24 + ["inner"] * 6)
    groups = np.r_[np.arange(54) % 6, np.full(6, 6)]  # inner: one group, missing from a fold
    X = rng.normal(size=(y.size, 4)) + (y == "outer")[:, None] * 0.8
    frame = pd.DataFrame({"label": y})
    left_out = pd.DataFrame({"label": ["outer"] * 5})
    X_left_out = rng.normal(size=(5, 4))
    rule = [
        {"healthy": float(p), "outer race": 0.5 * (1 - p), "inner race": 0.5 * (1 - p)}
        for p in rng.uniform(0.05, 0.95, y.size + 5)
    ]
    forest = RandomForestClassifier(n_estimators=20, random_state=0)
    pred, proba, proba_left_out = _out_of_fold(
        X, y, groups, forest, 4, probabilities=True, X_extra=X_left_out
    )
    # what the calibration fitted before train handed it the probabilities
    from sklearn.base import clone
    from sklearn.model_selection import GroupKFold

    classes = np.array(["healthy", "inner", "outer"])
    expected, expected_left_out = np.zeros((60, 3)), np.zeros((5, 3))
    for train_idx, test_idx in GroupKFold(n_splits=4).split(X, y, groups):
        est = clone(forest).fit(X[train_idx], y[train_idx])
        columns = np.searchsorted(classes, est.classes_)
        expected[np.ix_(test_idx, columns)] = est.predict_proba(X[test_idx])
        expected_left_out[:, columns] += est.predict_proba(X_left_out) / 4
        assert (pred[test_idx] == est.predict(X[test_idx])).all()
    assert np.array_equal(proba, expected) and np.array_equal(proba_left_out, expected_left_out)
    assert (proba[y == "inner", 1] == 0).all()  # its fold's model never saw "inner"
    args = (frame, X, y, groups, forest, 4, left_out, X_left_out)
    fitted = pooled_calibration(*args, rule=rule)
    handed = pooled_calibration(*args, rule=rule, out_of_fold=(proba, proba_left_out))
    assert fitted is not None and handed == fitted


def test_diagnosis_beyond_the_ratings_warns_in_its_own_words_once():
    """Found by a property run of diagnose + report: the healthy model waviness is judged
    against ran simulate above the 6205's limiting speed, whose OperatingRangeWarning came on
    top of the diagnosis' own speed warning. Now the diagnosis alone says it, of the speed
    and of a --load over C0r."""
    import warnings

    from generators import OperatingRangeWarning

    x = np.random.default_rng(9).standard_normal(48000)
    with warnings.catch_warnings():
        warnings.simplefilter("error", OperatingRangeWarning)
        fast = diagnose_signal(x, 48000.0, 14000.0, "6205")
        heavy = diagnose_signal(x, 48000.0, 1800.0, "6205", load_n=9000.0)
    assert fast.verdict == "healthy" and "waviness_reference" in fast.assumptions  # it ran
    assert [w for w in fast.warnings if "limiting speed" in w] == [
        "14000 rpm is above the catalogue limiting speed of the 6205 (13000 rpm): check --rpm "
        "and --bearing"
    ]
    assert any(
        "--load 9000 N is over the 6205's static load rating C0r (7850 N)" in w
        for w in heavy.warnings
    )


@pytest.mark.parametrize(
    ("call", "error", "message"),
    [
        (dict(fs="12k"), ParameterError, r"fs = '12k' is not a number"),
        (dict(geometry=6205), ParameterError, r"geometry = 6205 is neither a catalog name"),
        (dict(x=np.zeros((12000, 2))), ValueError, r"x has shape \(12000, 2\): give one record"),
        (dict(x=np.array([])), ValueError, r"x is empty"),
        (dict(x=["a", "b"]), ValueError, r"x is not an array of numbers"),
        (dict(model={"a": 1}), ValueError, r"model has no 'pipeline'"),
        (dict(model=object()), ValueError, r"model = object is not a model bundle"),
    ],
)
def test_the_python_api_names_a_bad_argument(call, error, message):
    """Found by calling cmtool.diagnose_signal as a Python user would: a str rate, an int
    bearing, a two-channel array, an empty one or a dict that is no bundle failed inside
    numpy or with AttributeError/KeyError."""
    arguments = dict(
        x=np.random.default_rng(0).standard_normal(12000), fs=12000.0, rpm=1800.0, geometry="6205"
    )
    model = call.pop("model", None)
    arguments.update(call)
    with pytest.raises(error, match=message):
        diagnose_signal(**arguments, model=model)


def test_the_python_api_takes_one_column_as_one_record():
    x = np.random.default_rng(0).standard_normal(12000)
    column = diagnose_signal(x[:, None], 12000.0, 1800.0, "6205")
    assert column.candidates == diagnose_signal(x, 12000.0, 1800.0, "6205").candidates


TWO_BEARINGS = """
name = "two"
seed = 12
bearings = ["6205", "6203"]
[operating]
rpm = [1500, 2100]
load_n = { min = 200, max = 800 }
[sensor]
fs_hz = 5120
duration_s = 0.5
settle_s = 0.02
snr_db = 10
[[conditions]]
label = "healthy"
count = 8
[[conditions]]
label = "outer"
surface = "outer"
order = { min = 8, max = 10 }
amplitude_m = { min = 0.5e-6, max = 1e-6 }
count = 8
"""


def test_train_and_evaluate_report_each_bearing_of_a_dataset_of_several(
    tmp_path, capsys, light_forests
):
    """A dataset of two bearings: train's out-of-fold scores and evaluate's scores are printed
    per bearing too, each with its own count of signals (issue 17: per rig and per class)."""
    import re

    from cmtool.datasets import generate_dataset

    recipe = tmp_path / "two.toml"
    recipe.write_text(TWO_BEARINGS)
    generate_dataset(recipe, tmp_path / "ds", workers=1)
    model = tmp_path / "m.skops"
    assert main(["train", str(tmp_path / "ds"), "--out", str(model)]) == 0
    out = capsys.readouterr().out
    lines = [ln for ln in out.splitlines() if ln.strip().startswith("bearing ")]
    assert [ln.split(":")[0].strip() for ln in lines] == ["bearing 6203", "bearing 6205"]
    assert all(ln.endswith("(out of fold)") and "on 8 signals" in ln for ln in lines)
    argv = ["evaluate", str(model), str(tmp_path / "ds"), "--allow-training-data"]
    assert main([*argv, "--out", str(tmp_path / "ev")]) == 0
    out = capsys.readouterr().out
    counts = re.findall(r"bearing (\d+): accuracy [0-9.]+ on (\d+) signals", out)
    assert counts == [("6203", "8"), ("6205", "8")]
    # a confusion matrix per bearing beside the overall one, each in evaluation.json too
    saved = json.loads((tmp_path / "ev" / "evaluation.json").read_text())
    for rig in ("6203", "6205"):
        assert (tmp_path / "ev" / f"confusion_{rig}.png").stat().st_size > 5000
        assert np.sum(saved["by_rig"][rig]["confusion"]) == 8
    overall = np.array(saved["confusion"])
    assert (
        np.add(*(np.array(saved["by_rig"][r]["confusion"]) for r in ("6203", "6205"))) == overall
    ).all()


PITS = """
name = "pits"
seed = 52
[operating]
rpm = [1797]
load_n = { min = 100, max = 400 }
[sensor]
fs_hz = 12000
duration_s = 0.5
settle_s = 0.05
background_db = 20
fault_snr_db = { min = -20, max = 10 }
[[conditions]]
label = "healthy"
count = 3
[[conditions]]
label = "outer"
surface = "outer"
defect = "localized"
length_m = 0.3e-3
depth_m = 0.1e-3
count = 6
"""


def test_evaluate_leaves_out_invisible_faults_and_warns_of_other_fault_kinds(
    tmp_path, capsys, bundle
):
    """As train does, evaluate leaves out faulty signals below the fault-SNR floor (-10 dB by
    default: nothing in them shows the fault), says how many, and scores the rest; a model
    that learnt its classes from waviness is warned of when the dataset's faults are local
    ones (datasets/small's model on pits: the same label names, other faults)."""
    from cmtool.datasets import generate_dataset, read_dataset

    recipe = tmp_path / "pits.toml"
    recipe.write_text(PITS)
    generate_dataset(recipe, tmp_path / "ds", workers=1)
    snr = read_dataset(tmp_path / "ds")["fault_snr_db"]
    faint = int((snr < -10).sum())
    assert 0 < faint < 6  # the recipe's draw has faults on both sides of the floor
    model = save_model(bundle, tmp_path / "m.skops")
    argv = ["evaluate", str(model), str(tmp_path / "ds"), "--workers", "1"]
    assert main([*argv, "--out", str(tmp_path / "ev")]) == 0
    out = capsys.readouterr().out
    assert f"left out {faint} faulty signals below -10 dB fault SNR" in out
    assert f"on {9 - faint} signals" in out
    assert "the model learnt 'outer' from waviness faults and this dataset's 'outer'" in out
    saved = json.loads((tmp_path / "ev" / "evaluation.json").read_text())
    assert saved["left_out"] == faint and saved["min_fault_snr_db"] == -10
    assert saved["kinds_unlike"] == {"outer": {"model": "waviness", "dataset": "localized"}}
    assert main([*argv, "--min-fault-snr", "-1000"]) == 0  # every signal scored
    assert "on 9 signals" in capsys.readouterr().out


def test_a_record_outside_what_the_model_saw_is_said_to_be(bundle, rng):
    """`cmtool train` records the speeds, rates and bearings a model saw (datasets/small: 1200
    to 2400 rpm, 6400 Hz, the 6205); `diagnose --model` warns of each way a record is new to
    it, and of none for a record inside them."""
    assert bundle["training_ranges"] == {
        "rpm": [1200.0, 2400.0],
        "fs_hz": [6400.0, 6400.0],
        "bearings": ["6205"],
    }
    inside = diagnose_signal(rng.standard_normal(6400), 6400.0, 1800.0, "6205", model=bundle)
    assert not [w for w in inside.warnings if w.startswith("the model was trained")]
    outside = diagnose_signal(rng.standard_normal(12000), 12000.0, 3000.0, "6203", model=bundle)
    said = [w for w in outside.warnings if w.startswith("the model was trained")]
    assert said == [
        "the model was trained at 1200-2400 rpm and this record is at 3000 rpm: its "
        "probabilities are an extrapolation",
        "the model was trained at 6400 Hz and this record is at 12000 Hz: its "
        "probabilities are an extrapolation",
        "the model was trained on the 6205, not the 6203: its probabilities rest on features "
        "normalised by the bearing's rates",
    ]


def test_a_record_of_few_cage_revolutions_says_the_cage_lines_are_not_weighed():
    """A record holding fewer than features.evidence.MIN_CAGE_REVOLUTIONS cage revolutions
    warns that the ball's cage-rate lines are not weighed and states how many it holds; a
    1 s record of a 6205 at 1797 rpm (11.9 revolutions) weighs them and draws no warning
    about its length."""
    fs, rpm = 12000.0, 1797.0
    x = np.random.default_rng(4).standard_normal(int(fs))
    short = diagnose_signal(x[: int(0.5 * fs)], fs, rpm, "6205", waviness=False)
    whole = diagnose_signal(x, fs, rpm, "6205", waviness=False)
    assert any("6.0 cage revolutions, fewer than 10" in w for w in short.warnings)
    assert "(this record: 6.0)" in short.assumptions["evidence"]
    assert not any("cage-rate lines are not weighed" in w for w in whole.warnings)
    # the record's length draws no other warning: its cage sidebands (+/- 29.95 x 0.398 Hz)
    # stand 12 bins from their line, resolved
    assert not any("cage revolutions" in w for w in whole.warnings), whole.warnings
    assert "(this record: 11.9)" in whole.assumptions["evidence"]
    ball = next(c for c in whole.candidates if c["fault"] == "ball")
    assert {"cage 1x", "cage 2x"} <= {line["line"] for line in ball["lines_weighed"]}
    ball = next(c for c in short.candidates if c["fault"] == "ball")
    assert not {"cage 1x", "cage 2x"} & {line["line"] for line in ball["lines_weighed"]}


def test_a_record_of_few_fault_periods_warns_that_the_rule_is_less_sure():
    """Records of fewer than TRUSTED_RATE_PERIODS periods of the slowest fault rate (a 6205 at
    1797 rpm: BPFO 107.4 Hz, 40 periods in 0.37 s) are diagnosed with a warning that says how
    many they hold (as the JSON's assumptions do); longer ones draw none, and under
    MIN_RATE_PERIODS the record is refused."""
    from cmtool.diagnose import MIN_RATE_PERIODS, TRUSTED_RATE_PERIODS
    from generators import bearing, characteristic_frequencies

    fs, rpm = 12000.0, 1797.0
    x = np.random.default_rng(5).standard_normal(int(fs))
    bpfo = characteristic_frequencies(bearing("6205"), rpm / 60.0).bpfo
    warned = diagnose_signal(x[: int(0.3 * fs)], fs, rpm, "6205", waviness=False)
    assert any(
        f"holds 32 periods of the slowest fault rate ({bpfo:.1f} Hz), fewer than "
        f"{TRUSTED_RATE_PERIODS}" in w
        for w in warned.warnings
    ), warned.warnings
    assert warned.assumptions["slowest_rate_periods"] == pytest.approx(0.3 * bpfo, abs=0.05)
    for seconds in (0.4, 1.0):
        d = diagnose_signal(x[: int(seconds * fs)], fs, rpm, "6205", waviness=False)
        assert not any("periods of the slowest fault rate" in w for w in d.warnings)
    with pytest.raises(ValueError, match=f"at least {MIN_RATE_PERIODS} periods"):
        diagnose_signal(x[: int(0.15 * fs)], fs, rpm, "6205", waviness=False)


def test_a_speed_the_1x_line_contradicts_is_warned_of_and_the_line_stated(tmp_path, capsys):
    """An induction motor under load runs below its nameplate speed (the CWRU rig: 1730 rpm
    at 3 hp). Given 1797 rpm for a record whose 1x line is at 28.83 Hz (1730 rpm), diagnose
    says so (fault lines are searched from 2 % below to 0.5 % above the rates of the speed
    given: 3.7 % off misses them); given 1730 rpm it does not, and the JSON states the speed
    the spectrum shows either way (docs/diagnosis.md, "The speed the rates come from")."""
    fs = 12000.0
    t = np.arange(int(fs)) / fs
    rng = np.random.default_rng(8)
    x = rng.standard_normal(t.size) + sum(
        0.3 / h * np.sin(2 * np.pi * h * 1730 / 60 * t) for h in range(1, 4)
    )
    off = diagnose_signal(x, fs, 1797.0, "6205", waviness=False, speed_source="given")
    said = [w for w in off.warnings if "1x line" in w]
    assert len(said) == 1, off.warnings
    line = re.search(r"1x line is at ([\d.]+) Hz \((\d+) rpm\), ([\d.]+) % below the 1797", said[0])
    assert line is not None, said[0]
    assert float(line[1]) == pytest.approx(28.83, abs=0.1) and float(line[3]) == pytest.approx(
        3.7, abs=0.35
    )
    assert off.assumptions["spectrum_rpm"] == pytest.approx(1730.0, abs=3.0)
    right = diagnose_signal(x, fs, 1730.0, "6205", waviness=False)
    assert not any("1x line" in w for w in right.warnings)
    assert right.assumptions["spectrum_rpm"] == pytest.approx(1730.0, abs=3.0)
    # 0.2 % off (1733.5 rpm) is within the line's accuracy and harmless: no warning; 0.6 % off
    # (1740.4 rpm) is more than a speed 0.5 % off, which called some simulated healthy
    # bearings faulty (SPEED_WARNING, 0.35 %): warned of
    near = diagnose_signal(x, fs, 1733.5, "6205", waviness=False)
    assert not any("1x line" in w for w in near.warnings), near.warnings
    nearly = diagnose_signal(x, fs, 1740.4, "6205", waviness=False)
    said = [w for w in nearly.warnings if "1x line" in w]
    assert len(said) == 1 and "% below the 1740.4 rpm given" in said[0], nearly.warnings
    # a record with no 1x line states none
    quiet = diagnose_signal(rng.standard_normal(t.size), fs, 1797.0, "6205", waviness=False)
    assert quiet.assumptions["spectrum_rpm"] is None
    # the command prints the line's speed beside the one assumed, and the warning
    printed = _diagnosed_at_1797_rpm(x, tmp_path, capsys, "given")
    seen = r"1797 rpm \(the spectrum's 1x line: 17(2\d|3[0-4])(\.\d)? rpm\)"
    assert re.search(seen, printed), printed
    assert "% below the 1797 rpm given" in printed and "check --rpm" in printed


def _diagnosed_at_1797_rpm(x: np.ndarray, tmp_path: Path, capsys, speed_source: str) -> str:
    """What ``cmtool diagnose`` prints for ``x`` (12 kHz, a 6205 given 1797 rpm)."""
    np.save(tmp_path / "x.npy", x)
    argv = ["diagnose", str(tmp_path / "x.npy"), "--fs", "12000", "--rpm", "1797"]
    assert main([*argv, "--bearing", "6205", "--speed-source", speed_source]) == 0
    return capsys.readouterr().out


def test_the_speed_can_come_from_the_spectrums_1x_line(tmp_path, capsys):
    """``speed_source="spectrum"`` (``--speed-source spectrum``): an outer-race pit on a shaft
    turning at 1730 rpm, diagnosed with the nameplate's 1797 rpm, is missed at the speed given
    (3.7 % off: its lines lie outside the search) and found from the 1x line; the assumptions
    say which speed was given, which was used and why; without a line the speed given is used
    and the output says so."""

    from generators import bearing, characteristic_frequencies

    fs, n = 12000.0, 24000
    t = np.arange(n) / fs
    rng = np.random.default_rng(11)
    bpfo = characteristic_frequencies(bearing("6205"), 1730 / 60).bpfo
    x = ringing_impact_train(bpfo, fs, n, rng)  # slip: 1 % jitter
    x = x + 0.05 * rng.standard_normal(n) + 0.2 * np.sin(2 * np.pi * 1730 / 60 * t)
    given = diagnose_signal(x, fs, 1797.0, "6205", waviness=False, speed_source="given")
    assert given.verdict != "outer race", given.candidates
    assert given.assumptions["speed_source"] == "given" and given.assumptions["rpm"] == 1797.0
    line = diagnose_signal(x, fs, 1797.0, "6205", waviness=False, speed_source="spectrum")
    assert line.verdict == "outer race", line.candidates
    a = line.assumptions
    assert a["speed_source"] == "the spectrum's 1x line" and a["rpm_given"] == 1797.0
    assert a["rpm"] == pytest.approx(1730.0, abs=3.0) and a["rpm"] == pytest.approx(
        a["spectrum_rpm"], abs=0.1
    )
    assert line.frequencies["bpfo"] == pytest.approx(bpfo, rel=2e-3)
    assert not any("1x line is at" in w for w in line.warnings)  # used, not warned of
    # no line: the speed given, said
    quiet = diagnose_signal(
        rng.standard_normal(n), fs, 1797.0, "6205", waviness=False, speed_source="spectrum"
    )
    assert quiet.assumptions["rpm"] == 1797.0 and quiet.assumptions["speed_source"] == "given"
    assert any("no 1x line stands out" in w for w in quiet.warnings), quiet.warnings
    with pytest.raises(ValueError, match="'tach' is not one of given, spectrum, auto"):
        diagnose_signal(x, fs, 1797.0, "6205", speed_source="tach")
    # the command
    printed = _diagnosed_at_1797_rpm(x, tmp_path, capsys, "spectrum")
    used = r"17(2\d|3[0-4])(\.\d+)? rpm \(the spectrum's 1x line; 1797 rpm given\)"
    assert re.search(used, printed), printed
    assert "outer race" in printed.splitlines()[0]
    # a folder (by default, auto: 3.7 % off, the line's speed): its manifest's speed in
    # verdicts.csv's rpm, the line's in spectrum_rpm, which one was used in speed_source
    pd.DataFrame(
        [{"file": "x.npy", "sampling_rate_hz": fs, "shaft_rpm": 1797, "bearing": "6205"}]
    ).to_csv(tmp_path / "MANIFEST.csv", index=False)
    out = tmp_path / "reports"
    assert main(["diagnose", str(tmp_path), "--report", str(out)]) == 0
    printed = capsys.readouterr().out
    line_used = r"x.npy: outer race .*6205, 17[23]\d(\.\d)? rpm, the 1x line's \(1797 given\)"
    assert re.search(line_used, printed), printed
    table = pd.read_csv(out / "verdicts.csv")
    assert table["verdict"].tolist() == ["outer race"] and table["rpm"].tolist() == [1797]
    assert table["spectrum_rpm"].iloc[0] == pytest.approx(1730.0, abs=3.0)
    assert table["speed_source"].tolist() == ["the spectrum's 1x line"]


def test_auto_takes_the_lines_speed_only_where_the_speed_given_is_over_one_percent_off():
    """``speed_source="auto"``: the speed given while the 1x line lies within
    ``SPEED_CORRECTION`` (1 %) of it, the line's beyond (a speed 1.25-1.75 % off cost a third
    of the inner-race pits on simulated records, 2 % off most), with a warning that says
    which."""

    from cmtool.diagnose import SPEED_CORRECTION
    from generators import bearing, characteristic_frequencies

    assert SPEED_CORRECTION == 0.01
    fs, n = 12000.0, 24000
    t = np.arange(n) / fs
    rng = np.random.default_rng(12)
    bpfi = characteristic_frequencies(bearing("6205"), 1730 / 60).bpfi
    x = ringing_impact_train(  # the load zone's modulation at the shaft rate
        bpfi, fs, n, rng, strength=lambda times: 1.0 + 0.5 * np.cos(2 * np.pi * 1730 / 60 * times)
    )
    x = x + 0.05 * rng.standard_normal(n) + 0.2 * np.sin(2 * np.pi * 1730 / 60 * t)
    # 3.7 % off: the speed given misses the inner race, auto takes the line's and finds it
    given = diagnose_signal(x, fs, 1797.0, "6205", waviness=False, speed_source="given")
    assert given.verdict != "inner race", given.candidates
    auto = diagnose_signal(x, fs, 1797.0, "6205", waviness=False, speed_source="auto")
    assert auto.verdict == "inner race", auto.candidates
    assert auto.assumptions["speed_source"] == "the spectrum's 1x line"
    assert auto.assumptions["rpm"] == pytest.approx(1730.0, abs=3.0)
    said = [w for w in auto.warnings if "1x line" in w]
    assert len(said) == 1 and "more than 1 %: the fault rates come from the line's" in said[0]
    # 1.5 % off (1756 rpm): over SPEED_CORRECTION, the line's speed as well
    over = diagnose_signal(x, fs, 1756.0, "6205", waviness=False, speed_source="auto")
    assert over.assumptions["speed_source"] == "the spectrum's 1x line", over.warnings
    assert over.verdict == "inner race", over.candidates
    # 0.7 % off (1742 rpm): within SPEED_CORRECTION, the speed given is used (and warned of)
    near = diagnose_signal(x, fs, 1742.0, "6205", waviness=False, speed_source="auto")
    assert near.assumptions["rpm"] == 1742.0 and near.assumptions["speed_source"] == "given"
    said = [w for w in near.warnings if "1x line" in w]
    assert len(said) == 1 and "the fault rates come from the speed given" in said[0]


@pytest.mark.parametrize(
    ("line_rpm", "given_rpm", "fs", "why"),
    [
        # enough for 1797 rpm's fault rates (fs >= 1246 Hz), not for the line's 1850
        (1850.0, 1797.0, 1260.0, "fs = 1260 Hz is too low"),
        # beyond the toolkit's 120,000 rpm
        (122730.0, 119000.0, 100000.0, "outside the allowed range (0, 120000] rpm"),
    ],
)
def test_a_lines_speed_the_record_cannot_be_diagnosed_at_leaves_the_speed_given(
    line_rpm, given_rpm, fs, why
):
    """A 1x line whose speed the record cannot be diagnosed at (too fast for its rate, beyond
    the toolkit's speeds) is reported, and the speed given is used, instead of an error about
    a speed nobody gave."""
    t = np.arange(int(10 * fs if fs < 5000 else fs)) / fs
    rate = line_rpm / 60.0
    x = np.sin(2 * np.pi * rate * t) + 0.5 * np.sin(2 * np.pi * 2 * rate * t)
    x = x + 0.05 * np.random.default_rng(2).standard_normal(t.size)
    for source in ("auto", "spectrum"):
        d = diagnose_signal(x, fs, given_rpm, "6205", waviness=False, speed_source=source)
        assert d.assumptions["rpm"] == given_rpm and d.assumptions["speed_source"] == "given"
        assert d.assumptions["spectrum_rpm"] == pytest.approx(line_rpm, rel=1e-3)
        said = [w for w in d.warnings if "1x line" in w]
        assert len(said) == 1, d.warnings
        assert "cannot be diagnosed at the line's speed" in said[0] and why in said[0]


@pytest.mark.xfail(
    strict=True,
    raises=AssertionError,
    reason="issue 18: the periodic part is removed at the rates of the speed given, so a speed "
    "0.35-1 % off leaves a periodic ball-pass train in the random part (docs/diagnosis.md, 'The "
    "speed the rates come from': the fix measured in stops 61 and 62, not shipped)",
)
def test_a_periodic_ball_pass_train_is_no_fault_when_the_speed_given_is_slightly_off():
    """A strictly periodic train at BPFO (a healthy bearing's varying compliance, made sharp)
    is healthy at the right speed. With the speed given 0.5-0.75 % off, the harmonic fit at the
    given rates leaves it in the random part, where it reads as an outer-race fault far over
    the threshold; auto removes the periodic part at the 1x line's speed (the fault rates stay
    the speed given's) and it stays healthy. Auto does not yet: the bar for it was missed."""
    from scipy import signal as sp_signal

    from generators import bearing, characteristic_frequencies

    fs, n, rpm = 12000.0, 12000, 1797.0
    rates = characteristic_frequencies(bearing("6205"), rpm / 60)
    t = np.arange(n) / fs
    orders = np.arange(1, int(5900 // rates.bpfo))
    gains = sp_signal.freqz(*sp_signal.iirpeak(3000.0, 10.0, fs), worN=orders * rates.bpfo, fs=fs)[
        1
    ]
    x = np.real((gains[:, None] * np.exp(2j * np.pi * np.outer(orders * rates.bpfo, t))).sum(0))
    x = x / x.std() + 0.3 * np.sin(2 * np.pi * rates.shaft * t)
    x = x + 0.05 * np.random.default_rng(1).standard_normal(n)
    assert diagnose_signal(x, fs, rpm, "6205", waviness=False).verdict == "healthy"
    for error in (-0.005, 0.0075):
        given = diagnose_signal(
            x, fs, rpm * (1 + error), "6205", waviness=False, speed_source="given"
        )
        assert given.verdict == "outer race"  # the weakness
        auto = diagnose_signal(x, fs, rpm * (1 + error), "6205", waviness=False)
        assert auto.verdict == "healthy", auto.candidates
        assert auto.assumptions["rpm"] == rpm * (1 + error)  # the fault rates: the speed given's
        said = [w for w in auto.warnings if "1x line" in w]
        assert len(said) == 1 and "the periodic part is removed at the line speed" in said[0]


def test_a_healthy_verdict_near_the_threshold_says_it_is_borderline(tmp_path, capsys):
    """A healthy verdict whose calibrated confidence is under 0.5 (the top candidate within
    about 3 dB under the threshold, HEALTHY_CONFIDENCE) says so in its basis, naming the
    candidate and how far under it stands, in the JSON and the text; a clearly healthy one and
    a fault do not (stop 78; before, "healthy (confidence 0.32)" stood unexplained). An outer-
    race train in white noise, raised through the threshold in small steps."""

    from generators import bearing, characteristic_frequencies

    fs, n, rpm = 12000.0, 12000, 1797.0
    bpfo = characteristic_frequencies(bearing("6205"), rpm / 60).bpfo
    rng = np.random.default_rng(78)
    ring = ringing_impact_train(bpfo, fs, n, rng)
    noise = np.random.default_rng(79).standard_normal(n)
    seen = {"borderline": 0, "healthy": 0, "fault": 0}
    for level in np.arange(0.20, 0.30, 0.005):
        x = noise + level * ring / ring.std()
        d = diagnose_signal(x, fs, rpm, "6205", waviness=False)
        margin = d.candidates[0]["evidence_db"] - d.threshold_db
        if d.verdict == "healthy" and d.confidence < 0.5:
            seen["borderline"] += 1
            said = f"borderline: outer race stands {-margin:.1f} dB under the detection threshold"
            assert said in d.basis and f"probability {d.confidence:.2f}" in d.basis, d.basis
            kept = x
        else:
            seen["healthy" if d.verdict == "healthy" else "fault"] += 1
            assert "borderline" not in d.basis, (level, d.basis)
    assert min(seen.values()) >= 1, seen
    np.save(tmp_path / "near.npy", kept)
    argv = ["diagnose", str(tmp_path / "near.npy"), "--fs", "12000", "--rpm", "1797"]
    assert main([*argv, "--bearing", "6205", "--json"]) == 0
    assert "; borderline: outer race" in json.loads(capsys.readouterr().out)["basis"]
    assert main([*argv, "--bearing", "6205"]) == 0
    said = [line for line in capsys.readouterr().out.splitlines() if "basis:" in line]
    assert len(said) == 1 and "; borderline: outer race stands" in said[0], said
