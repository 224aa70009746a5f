"""Detector benchmark: scores, ROC, detection at fixed false-alarm rates, SNR curves (issue 20)."""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from cmtool.bench import (
    BUILTIN_DETECTORS,
    by_factor,
    confusion_frame,
    confusion_tables,
    load_callable,
    run_bench,
    score_summary,
    summarise,
    threshold_at_pfa,
    wilson_interval,
)
from cmtool.cli import main

SMALL = Path(__file__).resolve().parents[2] / "datasets" / "small"


def always_healthy(x, fs, rpm, bearing):
    return "healthy"


def rms_detector(x, fs, rpm, bearing):
    """A plug-in with scores: the RMS for every fault (the documented mapping form)."""
    value = float(np.sqrt(np.mean(np.square(x))))
    return {"label": "outer race", "scores": {"outer": value, "inner race": value, "ball": value}}


@pytest.fixture(scope="module")
def half_small(tmp_path_factory):
    """Every other part of datasets/small: 96 signals, every label at every operating point
    (the scoring's contract is the test's, not the detectors' figures on 192 signals)."""
    import shutil

    folder = tmp_path_factory.mktemp("half") / "small"
    (folder / "data").mkdir(parents=True)
    for name in sorted((SMALL / "data").glob("*.parquet"))[::2]:
        shutil.copy(name, folder / "data" / name.name)
    return folder


def test_every_detector_scores_every_fault_and_plugins_follow_the_contract(half_small):
    results = run_bench(half_small, detectors={"null": always_healthy, "rms": rms_detector})
    assert list(dict.fromkeys(results["detector"])) == [*BUILTIN_DETECTORS, "null", "rms"]
    scores = results[["score_outer_race", "score_inner_race", "score_ball"]].to_numpy()
    assert np.isfinite(scores).all()
    null = results[results["detector"] == "null"]
    assert (null[["score_outer_race", "score_inner_race", "score_ball"]] == 0).all().all()
    rms = results[results["detector"] == "rms"]
    assert (rms["score_outer_race"] == rms["score_ball"]).all() and (
        rms["verdict"] == "outer race"
    ).all()
    summary = summarise(results)
    assert summary["overall"].loc["null", "detection_rate"] == 0.0
    assert summary["overall"].loc["null", "accuracy"] == pytest.approx(12 / 48)
    # factors in numeric order with readable units
    bins = list(summary["rpm"].loc["envelope"].index)
    assert bins == sorted(bins, key=lambda b: float(b.split()[0])) and bins[0].endswith("rpm")


def test_wilson_interval_and_thresholds():
    # Wilson (1927): 9 of 10, z = 1.96 -> [0.5958, 0.9821]; 0 of 20 -> [0, 0.1611]
    assert wilson_interval(9, 10) == pytest.approx((0.5958, 0.9821), abs=1e-4)
    assert wilson_interval(0, 20) == pytest.approx((0.0, 0.1611), abs=1e-4)
    assert all(math.isnan(v) for v in wilson_interval(0, 0))
    healthy = np.arange(1000.0)  # scores 0 .. 999
    assert threshold_at_pfa(healthy, 1e-2) == 989.0  # 10 of 1000 above it
    assert threshold_at_pfa(healthy, 1e-3) == 998.0  # 1 of 1000 above it
    assert math.isnan(threshold_at_pfa(healthy[:999], 1e-3))  # 999 cannot measure 1e-3


def _synthetic_results(rng, n_healthy=1000, n_fault=200, shift=2.0):
    """One detector: healthy scores N(0, 1), each fault's own score N(shift, 1)."""
    rows = []
    for i in range(n_healthy):
        rows.append({"id": f"h{i}", "label": "healthy", "fault_snr_db": np.nan})
    for fault in ("outer race", "inner race", "ball"):
        for i in range(n_fault):
            rows.append(
                {"id": f"{fault}{i}", "label": fault, "fault_snr_db": -20 + 30 * i / n_fault}
            )
    frame = pd.DataFrame(rows)
    frame["detector"] = "gauss"
    frame["verdict"] = "healthy"
    for fault in ("outer race", "inner race", "ball"):
        column = "score_" + fault.replace(" ", "_")
        own = frame["label"] == fault
        frame[column] = rng.standard_normal(len(frame)) + shift * own
    return frame


def test_auc_and_detection_at_fixed_false_alarm_match_the_gaussian_theory(rng):
    from scipy.stats import norm

    shift = 2.0
    frame = _synthetic_results(rng, n_healthy=4000, n_fault=2000, shift=shift)
    summary, curves = score_summary(frame)
    assert set(summary.columns) >= {"detector", "fault", "auc", "pd_at_pfa_0.01", "pd_at_pfa_0.001"}
    # binormal ROC: AUC = Phi(d / sqrt 2), Pd at Pfa = Phi(d - z_(1 - Pfa))
    auc = norm.cdf(shift / math.sqrt(2))  # 0.921
    pd2 = norm.cdf(shift - norm.ppf(1 - 1e-2))  # 0.372
    pd3 = norm.cdf(shift - norm.ppf(1 - 1e-3))  # 0.116
    # sampling errors: AUC ~ 0.004, Pd ~ 0.011 (binomial, 2000) plus the threshold's own
    # error (4000 healthy; the 1e-3 quantile rests on 4 exceedances: ~0.05 in Pd)
    assert summary["auc"].to_numpy() == pytest.approx(auc, abs=0.02)
    assert summary["pd_at_pfa_0.01"].to_numpy() == pytest.approx(pd2, abs=0.05)
    assert summary["pd_at_pfa_0.001"].to_numpy() == pytest.approx(pd3, abs=0.08)
    assert set(curves) == {("gauss", f) for f in ("outer race", "inner race", "ball")}


def test_detection_against_snr_bins_in_order_with_intervals(rng):
    frame = _synthetic_results(rng)
    # make the own score grow with the SNR: an S-curve by construction
    faulty = frame["label"] != "healthy"
    for fault in ("outer race", "inner race", "ball"):
        column = "score_" + fault.replace(" ", "_")
        own = frame["label"] == fault
        frame.loc[own, column] = (
            rng.standard_normal(own.sum()) + (frame.loc[own, "fault_snr_db"] + 20) / 5
        )
    table = by_factor(frame, "fault_snr_db")
    assert list(table["value"]) == sorted(table["value"])  # bins in order
    assert table["bin"].iloc[0] == "-20 to -17 dB"
    assert table["signals"].sum() == faulty.sum()
    assert (table["ci_low"] <= table["pd_at_pfa_0.01"]).all()
    assert (table["pd_at_pfa_0.01"] <= table["ci_high"]).all()
    assert table["pd_at_pfa_0.01"].iloc[0] < 0.2 and table["pd_at_pfa_0.01"].iloc[-1] > 0.95


def test_detection_and_verdicts_by_the_films_entrainment_where_a_recipe_draws_it(rng):
    """A dataset that draws ``film_entrainment_factor`` (the recipe key, per case) is scored
    by it too: four bins of equal counts, in order, readable, the detection rate rising where
    the scores were made to rise with it, and a verdict table; a dataset without it has none."""
    from cmtool.bench_scores import summarise

    frame = _synthetic_results(rng)
    frame["film_entrainment_factor"] = rng.uniform(0.0, 1.0, len(frame))
    own = frame["label"] == "outer race"
    frame.loc[own, "score_outer_race"] += 4.0 * frame.loc[own, "film_entrainment_factor"]
    table = by_factor(frame, "film_entrainment_factor", fault="outer race")
    assert list(table["value"]) == sorted(table["value"]) and len(table) == 4
    edges = [tuple(float(v) for v in text.split("-")) for text in table["bin"]]  # "0.26-0.49"
    assert all(low < high for low, high in edges) and edges == sorted(edges)
    assert edges[0][0] < 0.01 and edges[-1][1] > 0.99  # the drawn span, unitless
    assert table["pd_at_pfa_0.01"].iloc[0] < table["pd_at_pfa_0.01"].iloc[-1]
    assert "film_entrainment_factor" in summarise(frame)
    assert "film_entrainment_factor" not in summarise(frame.drop(columns="film_entrainment_factor"))


def test_detection_against_snr_of_an_absent_fault_is_an_empty_table(rng):
    """A dataset of healthy and ball faults only: the per-fault table of inner-race faults has
    the columns and no rows (``cmtool bench`` stopped with a KeyError on it)."""
    frame = _synthetic_results(rng)
    frame = frame[frame["label"].isin(["healthy", "ball"])]
    table = by_factor(frame, "fault_snr_db", fault="inner race")
    assert table.empty
    assert {"detector", "bin", "value", "pd_at_pfa_0.01", "ci_low", "signals"} <= set(table)
    assert len(by_factor(frame, "fault_snr_db", fault="ball")) > 0


def test_load_callable_errors():
    assert load_callable("test_bench:always_healthy") is always_healthy
    with pytest.raises(ValueError, match="module:function"):
        load_callable("nocolon")
    with pytest.raises(ValueError, match="not a callable"):
        load_callable("math:pi")


def test_cli_bench_writes_the_named_outputs(tmp_path, capsys, half_small):
    out = tmp_path / "bench"
    argv = ["bench", str(half_small), "--detector", "test_bench:rms_detector", "--out", str(out)]
    assert main([*argv, "--workers", "2"]) == 0
    printed = capsys.readouterr().out
    assert "pd_at_pfa_0.01" in printed and "detection_rate" in printed
    summary = pd.read_csv(out / "summary.csv")
    assert list(summary.columns[:6]) == [
        "detector",
        "fault",
        "auc",
        "pd_at_pfa_0.01",
        "pd_at_pfa_0.001",
        "signals",
    ]
    assert set(summary["detector"]) == {*BUILTIN_DETECTORS, "test_bench:rms_detector"}
    # 24 healthy signals: a 1e-2 threshold cannot be measured on them
    assert summary["pd_at_pfa_0.01"].isna().all()
    by_snr = pd.read_csv(out / "by_snr.csv")
    assert list(by_snr.columns) == [
        "detector",
        "snr_db",
        "pd_at_pfa_0.01",
        "ci_low",
        "ci_high",
        "signals",
    ]
    for name in ("roc.png", "pd_vs_snr.png"):
        assert (out / name).stat().st_size > 10000
    report = (out / "report.md").read_text()
    assert "Healthy signals: 24" in report and "![ROC](roc.png)" in report
    # per class: each detector's labels against the true classes, counts, table and plot
    confusion = pd.read_csv(out / "confusion.csv")
    assert list(confusion.columns) == ["detector", "rig", "label", "verdict", "count"]
    assert set(confusion["rig"]) == {"all"}  # one bearing: no rig breakdown
    assert (confusion.groupby("detector")["count"].sum() == 96).all()
    rule = confusion_frame(confusion, "envelope")
    assert list(rule.index) == ["healthy", "outer race", "inner race", "ball"]
    assert rule.loc["healthy"].tolist() == [24, 0, 0, 0]  # every healthy signal healthy
    assert "-- envelope\n" in printed and "rows: true class, columns: verdict" in printed
    assert (out / "confusion_envelope.png").stat().st_size > 10000
    assert "## By class" in report and "![envelope](confusion_envelope.png)" in report
    assert main(["bench", str(SMALL), "--detector", "nosuch:module"]) == 2


def test_confusion_tables_count_every_class_overall_and_per_rig():
    results = pd.DataFrame(
        {
            "detector": ["rule"] * 5 + ["kurtosis"] * 5,
            "label": ["healthy", "ball", "outer race", "healthy", "ball"] * 2,
            "verdict": ["healthy", "outer race", "outer race", "ball", "ball"]
            + ["healthy", "fault", "fault", "fault", "healthy"],
            "rig": ["CWRU", "CWRU", "CWRU", "MFPT", "MFPT"] * 2,
        }
    )
    tables = confusion_tables(results)
    assert list(dict.fromkeys(tables["rig"])) == ["all", "CWRU", "MFPT"]
    rule = confusion_frame(tables, "rule")
    assert list(rule.index) == ["healthy", "outer race", "ball"]
    assert rule.to_numpy().tolist() == [[1, 0, 1], [0, 1, 0], [0, 1, 1]]
    assert confusion_frame(tables, "rule", "MFPT").to_numpy().tolist() == [
        [0, 0, 1],
        [0, 0, 0],
        [0, 0, 1],
    ]
    kurtosis = confusion_frame(tables, "kurtosis")
    assert list(kurtosis.columns) == ["healthy", "outer race", "ball", "fault"]
    assert kurtosis["fault"].tolist() == [1, 1, 1]
    sums = tables.groupby(["detector", "rig"], sort=False)["count"].sum()
    assert sums.tolist() == [5, 3, 2, 5, 3, 2]


@pytest.mark.realdata
def test_bench_on_measured_recordings(shared_data):
    results = run_bench(shared_data)
    summary = summarise(results)
    rule = summary["overall"].loc["envelope"]
    assert rule["signals"] == 6
    assert rule["detection_rate"] == 1.0
    assert rule["false_alarm_rate"] == 0.0
    assert rule["correct_fault_first_rate"] == 1.0
    scores, _ = score_summary(results)
    # one healthy record: every AUC is measured against it; no false-alarm rate can be
    assert scores["healthy_signals"].eq(1).all() and scores["pd_at_pfa_0.01"].isna().all()
    # by class and per rig (the manifest's dataset column): the rule's labels all right
    confusion = confusion_tables(results)
    rigs = set(pd.read_csv(Path(shared_data) / "MANIFEST.csv")["dataset"])
    assert set(confusion["rig"]) == {"all", *rigs}
    for rig in ("all", *rigs):
        frame = confusion_frame(confusion, "envelope", rig)
        right = sum(int(frame.loc[c, c]) for c in frame.index if c in frame.columns)
        assert right == int(frame.to_numpy().sum()) > 0


def test_the_benchmark_recipe_can_set_a_1e3_threshold_and_sweeps_the_snr():
    import tomllib

    from generators.recipe import validate_recipe

    path = Path(__file__).resolve().parents[2] / "datasets" / "detector-bench.toml"
    recipe = validate_recipe(tomllib.loads(path.read_text()))
    counts = {c["label"]: c["count"] for c in recipe["conditions"]}
    assert counts["healthy"] >= 1000  # a 1e-3 false-alarm threshold on healthy signals alone
    assert {"inner", "outer", "ball"} <= set(counts)
    assert recipe["sensor"]["fault_snr_db"] == {"range": (-20.0, 10.0)}
    assert len(recipe["bearings"]) >= 3


def test_snr_below_the_sweep_is_pooled_in_one_bin_first(rng):
    frame = _synthetic_results(rng, n_healthy=200, n_fault=30)
    frame.loc[frame["id"].isin(["ball0", "ball1"]), "fault_snr_db"] = [-150.0, -45.0]
    table = by_factor(frame, "fault_snr_db")
    assert table["bin"].iloc[0] == "below -20 dB" and table["signals"].iloc[0] == 2


def test_a_dataset_of_healthy_signals_only_gives_false_alarm_figures_and_no_crash(tmp_path):
    """No faulty signal: no ROC, no Pd; the labels' false-alarm rates are the figures."""
    import shutil

    data = tmp_path / "healthy" / "data"
    data.mkdir(parents=True)
    for name in sorted((SMALL / "data").glob("*.parquet"))[:2]:  # the first parts: healthy
        shutil.copy(name, data / name.name)
    out = tmp_path / "out"
    assert main(["bench", str(data.parent), "--out", str(out)]) == 0
    summary = pd.read_csv(out / "summary.csv")
    assert summary["auc"].isna().all() and (summary["signals"] == 0).all()
    labels = pd.read_csv(out / "labels.csv", index_col=0)
    assert labels.loc["envelope", "false_alarm_rate"] == 0.0
    assert (out / "report.md").is_file() and (out / "roc.png").is_file()


def test_a_dataset_of_healthy_and_one_fault_gives_its_figures_and_plots(tmp_path):
    """A recipe of healthy and outer-race signals only (a user's own, for one fault): the
    per-fault SNR table has no rows for the faults it lacks and the plot no panel for them.
    Before: a TypeError in matplotlib (the absent faults' empty tables made the SNR columns
    objects). With 16 healthy signals no 1e-2 threshold exists, and the plot says so."""
    import shutil

    data = tmp_path / "outer_only" / "data"
    data.mkdir(parents=True)
    for index in (0, 1, 12, 13):  # parts of datasets/small: two healthy, two outer race
        name = SMALL / "data" / f"part-{index:05d}.parquet"
        shutil.copy(name, data / name.name)
    out = tmp_path / "out"
    assert main(["bench", str(data.parent), "--out", str(out)]) == 0
    by_fault = pd.read_csv(out / "by_snr_fault.csv")
    assert set(by_fault["fault"]) == {"all", "outer race"}
    assert (by_fault.groupby("fault")["signals"].sum() == 16 * len(BUILTIN_DETECTORS)).all()
    assert (out / "pd_vs_snr.png").stat().st_size > 10000
    summary = pd.read_csv(out / "summary.csv").set_index(["detector", "fault"])
    assert (summary.xs("outer race", level="fault")["signals"] == 16).all()


def test_bench_names_the_column_a_dataset_lacks(tmp_path):
    """Before: a KeyError ('rpm') from deep in the benchmark."""
    import pyarrow.parquet as pq

    data = tmp_path / "cut" / "data"
    data.mkdir(parents=True)
    table = pq.read_table(SMALL / "data" / "part-00000.parquet")
    pq.write_table(table.drop_columns(["rpm"]), data / "part-00000.parquet")
    with pytest.raises(ValueError, match=r"has no column 'rpm' \(cmtool generate gives"):
        run_bench(data.parent, allow_incomplete=True)


def test_a_dataset_that_turns_the_load_gives_detection_by_its_angle_from_the_sensor(tmp_path):
    """A recipe that draws the load's direction (operating.load_angle_deg) gets its detection
    counted by the angle between the load and the sensor's axis (0-90 deg)."""
    import math

    import pyarrow as pa
    import pyarrow.parquet as pq

    from cmtool.bench import _records

    data = tmp_path / "turned" / "data"
    data.mkdir(parents=True)
    source = sorted((SMALL / "data").glob("*.parquet"))[-1]
    table = pq.read_table(source)
    angles = [0.0 if i % 2 else -math.pi / 2 for i in range(table.num_rows)]
    column = table.schema.get_field_index("load_angle_rad")
    table = table.set_column(column, "load_angle_rad", pa.array(angles))
    pq.write_table(table, data / source.name)
    seen = [meta["load_from_sensor_deg"] for *_, meta in _records(data.parent, "6205", True)]
    assert seen == pytest.approx([90.0 if i % 2 else 0.0 for i in range(table.num_rows)])


def _crashes(x, fs, rpm, bearing):
    raise RuntimeError("boom")


@pytest.mark.parametrize(
    ("returned", "message"),
    [
        (42, "returned the label 42; a label is one of healthy, outer race, inner race, ball"),
        ("cage", "returned the label 'cage'"),
        ({"label": "ball", "scores": {"outer": 1.0, "inner": 0.0}}, "scores miss ball"),
        (
            {"label": "ball", "scores": {"outer": math.nan, "inner": 0.0, "ball": 1.0}},
            "the score of 'outer' is nan, not a finite number",
        ),
        ({"label": "ball", "scores": {"outer": "high", "inner": 0, "ball": 1}}, "'high'"),
        ({"verdict": "ball"}, "a mapping must hold 'label' and 'scores'"),
    ],
)
def test_a_plugin_that_breaks_the_contract_is_named_with_its_signal(returned, message):
    """Found by probing `cmtool bench --detector`: 42 or 'cage' were scored as a label of
    their own, a NaN score failed in scikit-learn without naming the detector."""

    def plugin(x, fs, rpm, bearing):
        return returned

    with pytest.raises(ValueError, match=r"detector odd on signal 'small-\d+'") as err:
        run_bench(SMALL, detectors={"odd": plugin})
    assert message in str(err.value)


def test_a_plugin_that_raises_is_named_with_its_signal(capsys):
    with pytest.raises(ValueError, match=r"detector crash failed on signal 'small-\d+': "):
        run_bench(SMALL, detectors={"crash": _crashes})
    argv = ["bench", str(SMALL), "--detector", f"{__name__}:_crashes"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "RuntimeError: boom" in err and "Traceback" not in err


def _warns(x, fs, rpm, bearing):
    import warnings

    warnings.warn("the plug-in's own caveat", UserWarning, stacklevel=2)
    return "healthy"


def test_a_warning_in_the_worker_processes_reaches_the_caller_once(tmp_path, capsys):
    """A plug-in's warning raised in ``workers=2`` processes is the caller's, once: each worker
    printed it itself (twice with two workers, out of reach of the caller's filters), and
    ``cmtool bench`` showed it so."""
    import shutil
    import warnings

    part = tmp_path / "part" / "data"
    part.mkdir(parents=True)
    for name in sorted((SMALL / "data").glob("*.parquet"))[::8]:  # 24 signals
        shutil.copy(name, part / name.name)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        run_bench(part.parent, detectors=[f"{__name__}:_warns"], workers=2)
    mine = [w for w in caught if "the plug-in's own caveat" in str(w.message)]
    assert len(mine) == 1 and mine[0].category is UserWarning
    argv = ["bench", str(part.parent), "--detector", f"{__name__}:_warns", "--workers", "2"]
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert err.count("the plug-in's own caveat") == 1, err
