"""Property: every argument set of `simulate` and `diagnose` ends in exit 0 with finite output,
or exit 2 with one line on stderr; never a traceback, never NaN (issue 19).

Hypothesis runs derandomised (the same examples in every run and in CI) with a small budget:
each example is a real simulation or diagnosis.
"""

import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from cmtool.cli import main

PROFILE = settings(
    max_examples=30,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)

#: Numbers a user might type by mistake (and any float, rarely).
bad_numbers = st.one_of(
    st.sampled_from([0.0, -1.0, 1e-9, 1e9, math.nan, math.inf]),
    st.floats(allow_nan=True, allow_infinity=True, width=32),
)


def mostly(good: list, bad=bad_numbers):
    """Valid values three times in four, the rest from ``bad``."""
    return st.one_of(st.sampled_from(good), st.sampled_from(good), st.sampled_from(good), bad)


def _run(argv, capsys, *, system_exit_ok=True):
    """Run the CLI; return (code, stdout, stderr), with argparse's exits as codes."""
    try:
        code = main(argv)
    except SystemExit as stop:  # argparse usage errors
        assert system_exit_ok
        code = stop.code
    out, err = capsys.readouterr()
    return code, out, err


OUTCOMES: dict[str, list[int]] = {"simulate": [], "diagnose": []}


def _check_outcome(code, err, command):
    OUTCOMES[command].append(code)
    assert code in (0, 2), (code, err)
    if code == 2:
        assert err.count("\n") == 1 and "error" in err and "Traceback" not in err, err
    else:
        assert "Traceback" not in err


@PROFILE
@given(
    rpm=mostly([300.0, 1800.0, 6000.0]),
    load=mostly([0.0, 500.0, 5000.0]),
    fs=mostly([2000.0, 6400.0]),
    duration=mostly([0.02, 0.05], st.sampled_from([0.0, -1.0, 1e7])),
    clearance=st.one_of(st.none(), st.sampled_from([0.0, 10e-6, 1.0, -1.0])),
    extra=st.sampled_from(
        [
            [],
            ["--waviness", "outer:order=9:amplitude=1e-6"],
            ["--waviness", "outer:order=9.5:amplitude=1e-6"],
            ["--defect", "inner:length=0.2e-3:depth=0.1e-3", "--random-slip", "0.01"],
            ["--channels", "housing_velocity_y"],
            ["--channels", "bogus"],
            ["--scene", "shaft", "--no-ehl"],
            ["--random-slip", "0.5"],
        ]
    ),
)
def test_simulate_never_crashes_and_never_writes_nan(
    tmp_path, capsys, rpm, load, fs, duration, clearance, extra
):
    out = tmp_path / "sig.csv"
    argv = ["simulate", "--rpm", str(rpm), "--load", str(load), "--fs", str(fs)]
    argv += ["--duration", str(duration), "--settle", "0.01", "--out", str(out), *extra]
    if clearance is not None:
        argv += ["--clearance", str(clearance)]
    code, _, err = _run(argv, capsys)
    _check_outcome(code, err, "simulate")
    if code == 0:
        frame = pd.read_csv(out)
        assert len(frame) > 0 and np.all(np.isfinite(frame.to_numpy()))
    out.unlink(missing_ok=True)


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    """A one-second 12 kHz CSV of noise with a time column."""
    path = tmp_path_factory.mktemp("rec") / "rec.csv"
    x = np.random.default_rng(8).standard_normal(12000)
    pd.DataFrame({"time": np.arange(x.size) / 12000.0, "accel": x}).to_csv(path, index=False)
    return path


@PROFILE
@given(
    rpm=mostly([600.0, 1797.0, 20000.0]),
    fs=mostly([None, 12000.0, 48000.0], st.sampled_from([200.0, -1.0, math.nan])),
    bearing=mostly(["6205", "mfpt", "6308"], st.none()),
    channel=mostly([None, "0", "accel"], st.sampled_from(["1", "nope"])),
    json_out=st.booleans(),
)
# found by the examples above: at fs 200 Hz the ISO 15242 medium and high bands lie above
# fs/2 and were printed (and written to the JSON) as NaN
@example(rpm=6.0, fs=200.0, bearing="6205", channel=None, json_out=False)
@example(rpm=6.0, fs=200.0, bearing="6205", channel=None, json_out=True)
def test_diagnose_never_crashes_and_never_answers_nan(
    recording, capsys, rpm, fs, bearing, channel, json_out
):
    argv = ["diagnose", str(recording), "--rpm", str(rpm)]
    argv += [] if fs is None else ["--fs", str(fs)]
    argv += [] if bearing is None else ["--bearing", bearing]
    argv += [] if channel is None else ["--channel", channel]
    argv += ["--json"] if json_out else []
    code, out, err = _run(argv, capsys)
    _check_outcome(code, err, "diagnose")
    if code == 0:
        assert "nan" not in out.lower()
        if json_out:
            import json

            def refuse(constant):  # NaN and Infinity are not JSON
                raise AssertionError(f"{constant} in the JSON output")

            data = json.loads(out, parse_constant=refuse)
            assert math.isfinite(data["confidence"]) and 0.0 <= data["confidence"] <= 1.0


def test_the_properties_met_both_outcomes():
    """The examples above reached real runs as well as refusals (run after them, same module)."""
    for command, codes in OUTCOMES.items():
        if not codes:
            pytest.skip("run with the property tests above")
        assert 0 in codes and 2 in codes, (command, codes)
