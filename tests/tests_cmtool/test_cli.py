"""The command line, through ``main([...])`` (ObsPy style), and signal I/O."""

import argparse
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
    printed = capsys.readouterr().out
    assert "BPFO 107.543" in printed
    # what the record was: the step on the record grid, 4 x fs, decimated
    assert meta["parameters"]["oversample"] == 4
    assert "RK4 step 19.53 us, recorded at 102.4 kHz (4 x fs)" in printed


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


def test_frequencies_with_a_slipping_cage(capsys):
    """--cage-slip s: FTF, BPFO and the ball's spin lower by s, BPFI higher by s BPFO / BPFI
    (the inner race meets lagging balls faster), the waviness lines with them; out of [0,
    0.5) the flag, its value and the range are named."""
    assert main(["frequencies", "--rpm", "1797", "--json"]) == 0
    kinematic = json.loads(capsys.readouterr().out)["frequencies_hz"]
    argv = ["frequencies", "--rpm", "1797", "--cage-slip", "0.02", "--wpf", "outer:9"]
    assert main([*argv, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    f = data["frequencies_hz"]
    assert data["cage_slip"] == 0.02
    for key in ("ftf", "bpfo", "bsf", "two_bsf"):
        assert f[key] == pytest.approx(0.98 * kinematic[key], rel=1e-12)
    assert f["bpfi"] == pytest.approx(kinematic["bpfi"] + 0.02 * kinematic["bpfo"], rel=1e-12)
    assert f["shaft"] == kinematic["shaft"]
    line = data["waviness_passage_frequencies_hz"][0]["lines"][0]["frequency"]
    assert line == pytest.approx(f["bpfo"])
    assert main(argv) == 0
    assert "cage slip 0.02: the cage at 0.98 of its kinematic speed" in capsys.readouterr().out
    assert main(["frequencies", "--rpm", "1797", "--cage-slip", "0.6"]) == 2
    err = capsys.readouterr().err
    assert "--cage-slip" in err and "0.6" in err and "0.5" in err


def test_frequencies_gives_the_waviness_passage_frequencies_by_order(capsys):
    """--wpf: the lines of docs/model.md 2.1 at 1800 rpm (f_s 30 Hz) on a 6205 (Z = 9): outer
    orders at q BPFO, inner order k at q BPFI + (k - qZ) f_s, even ball orders 2p at 2p f_b
    and 2p f_b +/- f_c, odd ball orders none."""
    argv = ["frequencies", "--rpm", "1800", "--wpf", "outer:8-10", "--wpf", "inner:9,10"]
    assert main([*argv, "--wpf", "ball:3,4", "--harmonics", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    f = data["frequencies_hz"]
    lines = {
        (w["surface"], w["order"]): sorted(x["frequency"] for x in w["lines"])
        for w in data["waviness_passage_frequencies_hz"]
    }
    assert list(lines) == [
        (s, k)
        for s, ks in (("outer", (8, 9, 10)), ("inner", (9, 10)), ("ball", (3, 4)))
        for k in ks
    ]
    for k in (8, 9, 10):
        assert lines["outer", k] == pytest.approx([f["bpfo"], 2 * f["bpfo"]])
    assert lines["inner", 9] == pytest.approx([2 * f["bpfi"] - 9 * 30.0, f["bpfi"]])
    assert any(x == pytest.approx(f["bpfi"] + 30.0) for x in lines["inner", 10])  # k = Z + 1
    assert lines["ball", 3] == []
    assert lines["ball", 4] == pytest.approx(
        [4 * f["bsf"] - f["ftf"], 4 * f["bsf"], 4 * f["bsf"] + f["ftf"]]
    )
    assert main(argv + ["--wpf", "ball:3"]) == 0
    text = capsys.readouterr().out
    assert "outer N_w = 9   107.543 (q 1, load, strong)" in text
    assert "ball N_w = 3   no line (an odd order does not compress the ball)" in text
    for bad, message in (
        ("cage:3", "surface outer, inner or ball"),
        ("outer:0-2", "[1, 500]"),
        ("outer:9-x", "'9-x' is not an order"),
    ):
        assert main(["frequencies", "--rpm", "1800", "--wpf", bad]) == 2
        assert message in capsys.readouterr().err


# every model flag of `simulate` (and of `fidelity`, which shares them), the value given and
# where it must land: (flag, value, object, field, expected)
MODEL_FLAGS = [
    ("--bearing", "6203", "geometry", "name", "6203"),
    ("--clearance", "2.5e-05", "geometry", "radial_internal_clearance", 2.5e-05),
    ("--rpm", "2400", "operating", "shaft_frequency", 40.0),
    ("--load", "750", "operating", "radial_load", 750.0),
    ("--load-angle", "-1.25", "operating", "load_angle", -1.25),
    ("--cage-slip", "0.015", "operating", "cage_slip", 0.015),
    ("--random-slip", "0.012", "operating", "random_slip", 0.012),
    ("--ball-jitter", "0.004", "operating", "ball_jitter", 0.004),
    ("--scene", "full", "scene", "level", "full"),
    ("--no-ehl", None, "scene", "ehl", False),
    ("--auto-error-bound", "0.02", "scene", "auto_error_bound", 0.02),
    ("--shaft-mass", "1.7", "rig", "shaft_mass", 1.7),
    ("--housing-mass", "3.3", "rig", "housing_mass", 3.3),
    ("--pedestal-stiffness", "6.5e7", "rig", "pedestal_stiffness", 6.5e7),
    ("--pedestal-damping", "950", "rig", "pedestal_damping", 950.0),
    ("--shaft-damping", "450", "rig", "shaft_damping", 450.0),
    ("--contact-damping-time", "3e-7", "rig", "contact_damping_time", 3e-7),
    ("--film-damping-factor", "0.4", "rig", "film_damping_factor", 0.4),
    ("--film-entrainment-factor", "0.6", "rig", "film_entrainment_factor", 0.6),
    ("--loading-stiffness", "1.5e6", "rig", "loading_stiffness", 1.5e6),
    ("--unbalance", "2e-5", "rig", "unbalance", 2e-5),
    ("--no-gravity", None, "rig", "gravity", False),
    ("--fs", "20480", "settings", "fs", 20480.0),
    ("--duration", "0.25", "settings", "duration", 0.25),
    ("--settle", "0.03", "settings", "settle_time", 0.03),
    ("--integrator", "dopri5", "settings", "integrator", "dopri5"),
    ("--step", "7e-6", "settings", "step", 7e-6),
    ("--error-bound", "0.02", "settings", "error_bound", 0.02),
    ("--rtol", "1e-7", "settings", "rtol", 1e-7),
    ("--atol", "3e-13", "settings", "atol_displacement", 3e-13),
    ("--oversample", "3", "settings", "oversample", 3),
    ("--cage-angle", "0.2", "settings", "cage_angle", 0.2),
    ("--contact-loads", None, "settings", "record_contact_loads", True),
    (
        "--channels",
        "housing_velocity_y,shaft_displacement_x",
        "settings",
        "channels",
        ("housing_velocity_y", "shaft_displacement_x"),
    ),
]


@pytest.mark.parametrize("flag, value, target, field, expected", MODEL_FLAGS)
def test_every_model_flag_lands_in_its_parameter_object(flag, value, target, field, expected):
    """One flag at a time: the parameter object gets the value, and nothing else changes."""
    from cmtool.cli import build_parser
    from cmtool.commands.simulate import _model_inputs

    parser = build_parser()
    default = dict(
        zip(
            ("geometry", "operating", "defects", "scene", "rig", "settings"),
            _model_inputs(parser.parse_args(["simulate"])),
            strict=True,
        )
    )
    argv = ["simulate", flag] + ([] if value is None else [value])
    given = dict(zip(default, _model_inputs(parser.parse_args(argv)), strict=True))
    got = getattr(given[target], field)
    assert got == (pytest.approx(expected) if isinstance(expected, float) else expected)
    assert getattr(default[target], field) != got  # the test value is not the default
    for name in ("operating", "scene", "rig", "settings"):
        if name != target and not (flag == "--bearing" and name == "operating"):
            assert given[name] == default[name], name


def test_every_simulate_flag_is_in_the_table():
    from cmtool.cli import build_parser

    parser = build_parser()
    simulate = parser._subparsers._group_actions[0].choices["simulate"]
    flags = {s for a in simulate._actions for s in a.option_strings if s.startswith("--")}
    outputs = {
        "--help",
        "--out",
        "--plot",
        "--envelope-plot",
        "--seed",
        "--ehl",
        "--lubricant",
        "--waviness",
        "--defect",
        "--form-waviness",  # test_cli_inputs.py::test_form_waviness_flag_simulates_...
    }
    tested = {row[0] for row in MODEL_FLAGS}
    assert flags - outputs - tested == set()


def test_version_flag(capsys):
    from cmtool import __version__

    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0
    assert capsys.readouterr().out.strip() == f"cmtool {__version__}"


def test_command_line_defaults_are_the_parameter_objects_defaults():
    """`simulate` with no flag builds exactly the default parameter objects (the defaults are
    written once, in generators.params, and read by the command line)."""
    from cmtool.cli import build_parser
    from cmtool.commands.simulate import _model_inputs
    from generators import OperatingCondition, Rig, Scene, SimulationSettings, bearing

    geometry, operating, defects, scene, rig, settings = _model_inputs(
        build_parser().parse_args(["simulate"])
    )
    assert geometry == bearing("6205") and defects == []
    assert operating == OperatingCondition.from_rpm(1800.0)
    assert (scene, rig, settings) == (Scene(), Rig(), SimulationSettings())


def test_every_help_states_a_default_once_and_never_none(capsys):
    """--help of every command: an option's default appears once (its own words or argparse's
    "(default: X)"), never "(default: None)" or "(default: False)"."""
    from cmtool.cli import build_parser

    parser = build_parser()
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sub in commands.choices.items():
        text = " ".join(sub.format_help().split())
        assert "(default: None)" not in text and "(default: False)" not in text, name
        for option in text.split(" --")[1:]:
            assert option.lower().count("default") <= 1, (name, option)
    train = " ".join(commands.choices["train"].format_help().split())
    assert "(default: evidence+scale-free" in train and "(default: -10.0)" not in train


def test_help_says_what_the_tool_is_and_every_option_what_it_does():
    """``cmtool --help`` opens with what the tool does and ends with where to start, not a
    module docstring's reST (it said "The ``cmtool`` command line."); no help anywhere shows
    reST markup, and every option of every command has words of its own."""
    from cmtool.cli import build_parser

    parser = build_parser()
    top = " ".join(parser.format_help().split())
    assert "Condition monitoring of rolling-element bearings" in top
    assert "Start with 'cmtool demo'" in top
    commands = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    for name, sub in [("cmtool", parser), *commands.choices.items()]:
        assert "``" not in sub.format_help(), name
        assert "(default: True)" not in sub.format_help(), name  # --no-ehl read "dry contacts
        # (default: True)"
        for action in sub._actions:
            if action.option_strings and not isinstance(action, argparse._HelpAction):
                assert action.help, (name, action.option_strings)
