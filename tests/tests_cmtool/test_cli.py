"""The command line, through ``main([...])`` (ObsPy style), and signal I/O."""

import json

import numpy as np
import pytest

from cmtool.cli import CliError, main, parse_defect, parse_waviness
from cmtool.io import read_signal
from generators import CHANNELS


def test_parse_waviness():
    w = parse_waviness("inner:order=10:amplitude=2e-7:phase=0.5")
    assert (w.surface, w.order, w.amplitude, w.phase) == ("inner", 10, 2e-7, 0.5)
    assert parse_waviness("ball:order=2:amplitude=1e-7").phase is None  # own phase per ball
    assert parse_waviness("outer:order=9:amplitude=1e-6:phase=random").phase is None
    with pytest.raises(CliError, match="amplitude= is missing"):
        parse_waviness("outer:order=9")
    with pytest.raises(CliError, match="unknown key 'depth'"):
        parse_waviness("outer:order=9:amplitude=1e-6:depth=3")


def test_parse_defect():
    d = parse_defect("outer:length=0.18e-3:depth=2e-5")
    assert (d.surface, d.length, d.depth, d.position) == ("outer", 0.18e-3, 2e-5, -np.pi / 2)
    assert parse_defect("inner:length=1e-4:depth=1e-5").position is None  # random
    b = parse_defect("ball:length=1e-4:depth=1e-5:ball=2:latitude=random:drift=30")
    assert (b.ball, b.latitude, b.axis_drift) == (2, None, 30.0)
    with pytest.raises(CliError, match="depth= is missing"):
        parse_defect("outer:length=1e-4")
    with pytest.raises(CliError, match="unknown key 'order'"):
        parse_defect("outer:length=1e-4:depth=1e-5:order=3")
    with pytest.raises(CliError, match="'x' is not a number"):
        parse_defect("outer:length=x:depth=1e-5")


def test_simulate_local_defect(tmp_path, capsys):
    out = tmp_path / "pit.parquet"
    args = ["simulate", "--defect", "inner:length=0.18e-3:depth=2e-5", "--duration", "0.1"]
    env = tmp_path / "envelope.png"
    assert (
        main(
            [
                *args,
                "--settle",
                "0.02",
                "--fs",
                "12000",
                "--out",
                str(out),
                "--envelope-plot",
                str(env),
            ]
        )
        == 0
    )
    assert env.stat().st_size > 10_000
    signal, meta = read_signal(out)
    assert meta["parameters"]["defects"][0]["kind"] == "LocalizedDefect"
    assert np.all(np.isfinite(signal["housing_acceleration_y"]))
    rc = main(["simulate", "--defect", "inner:length=0.18e-3:depth=-1", "--duration", "0.1"])
    assert rc == 2 and "depth = -1" in capsys.readouterr().err


def test_simulate_writes_parquet_with_metadata_and_plot(tmp_path, capsys):
    out, plot = tmp_path / "signal.parquet", tmp_path / "spectrum.png"
    rc = main(
        [
            "simulate",
            "--bearing",
            "6205",
            "--rpm",
            "1800",
            "--load",
            "500",
            "--waviness",
            "outer:order=9:amplitude=1e-6",
            "--duration",
            "0.1",
            "--settle",
            "0.02",
            "--fs",
            "25600",
            "--out",
            str(out),
            "--plot",
            str(plot),
            "--seed",
            "3",
        ]
    )
    assert rc == 0
    frame, meta = read_signal(out)
    assert list(frame.columns) == ["time", *CHANNELS]
    assert len(frame) == 2560
    assert meta["fs_hz"] == 25600.0
    assert meta["frequencies_hz"]["bpfo"] == pytest.approx(107.5434, rel=1e-4)
    assert meta["parameters"]["defects"][0]["order"] == 9
    assert plot.stat().st_size > 10_000
    assert "BPFO 107.543" in capsys.readouterr().out


def test_simulate_csv_has_json_sidecar(tmp_path):
    out = tmp_path / "signal.csv"
    rc = main(
        [
            "simulate",
            "--scene",
            "shaft",
            "--no-ehl",
            "--duration",
            "0.02",
            "--settle",
            "0",
            "--fs",
            "10240",
            "--integrator",
            "dopri5",
            "--rtol",
            "1e-6",
            "--out",
            str(out),
        ]
    )
    assert rc == 0
    frame, meta = read_signal(out)
    assert np.all(np.isfinite(frame["housing_velocity_y"]))
    assert meta["parameters"]["scene"]["level"] == "shaft"
    assert meta["parameters"]["settings"]["integrator"] == "dopri5"
    json.dumps(meta)


def test_every_setting_reaches_the_model(tmp_path):
    out = tmp_path / "s.parquet"
    rc = main(
        [
            "simulate",
            "--scene",
            "full",
            "--no-ehl",
            "--clearance",
            "20e-6",
            "--shaft-mass",
            "1.5",
            "--housing-mass",
            "3",
            "--pedestal-stiffness",
            "6e7",
            "--pedestal-damping",
            "900",
            "--shaft-damping",
            "500",
            "--contact-damping-time",
            "1e-7",
            "--film-damping-factor",
            "0.5",
            "--lubricant",
            "VG32",
            "--loading-stiffness",
            "1e6",
            "--unbalance",
            "1e-5",
            "--no-gravity",
            "--cage-slip",
            "0.01",
            "--load-angle",
            "-1.0",
            "--step",
            "2e-6",
            "--oversample",
            "2",
            "--cage-angle",
            "0.1",
            "--duration",
            "0.01",
            "--settle",
            "0",
            "--fs",
            "20000",
            "--out",
            str(out),
        ]
    )
    assert rc == 0
    _, meta = read_signal(out)
    p = meta["parameters"]
    assert p["bearing"]["radial_internal_clearance"] == 20e-6
    assert p["rig"]["shaft_mass"] == 1.5 and p["rig"]["gravity"] is False
    assert p["rig"]["lubricant"]["name"].startswith("ISO VG 32")
    assert p["operating"]["cage_slip"] == 0.01
    assert p["settings"]["oversample"] == 2
    assert p["integrator_stats"]["step_s"] <= 2e-6


def test_bad_input_exit_code_and_message(capsys):
    assert main(["simulate", "--load", "-5", "--duration", "0.01"]) == 2
    assert "radial_load = -5" in capsys.readouterr().err
    assert main(["simulate", "--waviness", "outer:order=9", "--duration", "0.01"]) == 2


def test_diverged_run_exit_code(capsys):
    rc = main(
        [
            "simulate",
            "--scene",
            "full",
            "--no-ehl",
            "--step",
            "1e-4",
            "--duration",
            "0.05",
            "--settle",
            "0",
            "--fs",
            "5120",
        ]
    )
    assert rc == 3
    assert "diverged" in capsys.readouterr().err


def test_frequencies_json(capsys):
    assert main(["frequencies", "--bearing", "6205", "--rpm", "1797", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["frequencies_hz"]["bpfo"] == pytest.approx(107.36, abs=0.01)
