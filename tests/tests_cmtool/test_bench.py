"""Detector benchmark over labelled datasets (synthetic folder and measured manifest)."""

from pathlib import Path

import pandas as pd
import pytest

from cmtool.bench import load_callable, run_bench, summarise
from cmtool.cli import main

SMALL = Path(__file__).resolve().parents[2] / "datasets" / "small"


def always_healthy(x, fs, rpm, bearing):
    return "healthy"


def test_user_detector_rates():
    results = run_bench(SMALL, detectors={"null": always_healthy})
    summary = summarise(results)
    null = summary["overall"].loc["null"]
    assert null["detection_rate"] == 0.0 and null["false_alarm_rate"] == 0.0
    assert null["accuracy"] == pytest.approx(12 / 48)
    assert {"rpm", "radial_load_n", "waviness_amplitude_m"} <= set(summary)
    env = summary["overall"].loc["envelope"]
    assert 0.0 <= env["correct_fault_first_rate"] <= env["detection_rate"] <= 1.0


def test_load_callable_errors():
    assert load_callable("test_bench:always_healthy") is always_healthy
    with pytest.raises(ValueError, match="module:function"):
        load_callable("nocolon")
    with pytest.raises(ValueError, match="not a callable"):
        load_callable("math:pi")


def test_cli_bench_writes_tables_and_plots(tmp_path, capsys):
    rc = main(
        ["bench", str(SMALL), "--detector", "test_bench:always_healthy", "--out", str(tmp_path)]
    )
    assert rc == 0
    assert "detection_rate" in capsys.readouterr().out
    overall = pd.read_csv(tmp_path / "bench_overall.csv", index_col=0)
    assert set(overall.index) == {"envelope", "test_bench:always_healthy"}
    assert (tmp_path / "bench_rpm.png").stat().st_size > 5000


@pytest.mark.realdata
def test_bench_on_measured_recordings(shared_data):
    summary = summarise(run_bench(shared_data))
    env = summary["overall"].loc["envelope"]
    assert env["signals"] == 6
    assert env["detection_rate"] == 1.0
    assert env["false_alarm_rate"] == 0.0
    assert env["correct_fault_first_rate"] == 1.0
