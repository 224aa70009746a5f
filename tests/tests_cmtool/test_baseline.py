"""A local fault judged against a healthy recording of the same machine (cmtool.baseline)."""

import json

import numpy as np
import pytest

from cmtool.baseline import BASELINE_RISE_DB
from cmtool.cli import main
from cmtool.diagnose import diagnose_signal

FS = 12000.0
RPM = 1797.0
CHANNEL = "housing_acceleration_y"


def _bearing_with_form_errors(load, rpm=RPM, pit=None):
    """A 6205 (5 um clearance) whose inner race carries 0.1 um form errors (the same bearing
    for every call: random_state fixes their phases), 1 s at 12 kHz, 5 % white noise."""
    from generators import (
        OperatingCondition,
        SimulationSettings,
        bearing,
        form_waviness,
        simulate,
    )

    g = bearing("6205", radial_internal_clearance=5e-6)
    slip = {"random_slip": 0.01, "ball_jitter": 0.005} if pit else {}
    op = OperatingCondition.from_rpm(rpm, load, **slip)
    defects = list(form_waviness(9, 1e-7, 0.0, 0.0)) + ([pit] if pit else [])
    settings = SimulationSettings(fs=FS, duration=1.0, channels=(CHANNEL,))
    x = simulate(g, op, defects, settings=settings, random_state=2)[CHANNEL]
    noise = np.random.default_rng(int(load) + (7 if pit else 0))
    return g, x + noise.normal(0.0, 0.05 * x.std(), x.size)


@pytest.fixture(scope="module")
def machine():
    """The record, the same bearing another day (1.2 x the load, 1.005 x the speed), and the
    record with an outer-race pit (0.3 mm, 1 % slip)."""
    from generators import LocalizedDefect

    g, record = _bearing_with_form_errors(400.0)
    _, baseline = _bearing_with_form_errors(480.0, rpm=1.005 * RPM)
    pit = LocalizedDefect(surface="outer", length=0.3e-3, depth=0.1e-3)
    _, faulty = _bearing_with_form_errors(400.0, pit=pit)
    return g, record, baseline, faulty


def test_form_errors_in_the_baseline_are_no_fault_and_a_pit_over_them_is(machine):
    """Alone, the rule reads the bearing's own form errors as an outer-race fault
    (docs/diagnosis.md, "Form errors read as a local fault"); against a healthy recording of
    the same bearing the lines stand no higher than there: healthy, and the basis says why. A
    pit on the same bearing rises far over the baseline and stays an outer-race fault."""
    g, record, baseline, faulty = machine
    alone = diagnose_signal(record, FS, RPM, g, waviness=False)
    assert alone.verdict == "outer race"
    d = diagnose_signal(record, FS, RPM, g, waviness=False, baseline=baseline)
    assert d.verdict == "healthy", d.basis
    outer = next(c for c in d.candidates if c["fault"] == "outer race")
    assert outer["as_in_baseline"] and not outer["detected"]
    assert outer["over_baseline_db"] < BASELINE_RISE_DB
    assert outer["confidence"] < 0.5  # read from its rise, not from its margin alone
    assert "stand as clearly in the healthy baseline" in d.basis and "outer race" in d.basis
    assert "fault_reference" in d.assumptions
    both = json.loads(json.dumps(d.to_dict()))  # the JSON carries the comparison
    assert {"baseline_margin_db", "over_baseline_db"} <= set(both["candidates"][0])

    found = diagnose_signal(faulty, FS, RPM, g, waviness=False, baseline=baseline)
    assert found.verdict == "outer race", found.basis
    outer = next(c for c in found.candidates if c["fault"] == "outer race")
    assert outer["detected"] and outer["over_baseline_db"] >= BASELINE_RISE_DB
    assert "baseline" not in found.basis


def test_without_a_baseline_nothing_changes(machine):
    """No baseline, no comparison: the candidates carry none of its keys and the verdict is the
    rule's alone."""
    g, record, _, _ = machine
    d = diagnose_signal(record, FS, RPM, g, waviness=False)
    assert all("over_baseline_db" not in c and "as_in_baseline" not in c for c in d.candidates)
    assert "fault_reference" not in d.assumptions


def test_cli_says_which_lines_the_baseline_accounts_for(machine, tmp_path, capsys):
    """``cmtool diagnose REC --baseline BASE``: each fault's rise over the baseline in the text
    and in the report's evidence table."""
    _, record, baseline, _ = machine
    np.savetxt(tmp_path / "rec.csv", record)
    np.savetxt(tmp_path / "base.csv", baseline)
    argv = ["diagnose", str(tmp_path / "rec.csv"), "--fs", "12000", "--rpm", "1797"]
    argv += ["--bearing", "6205", "--baseline", str(tmp_path / "base.csv")]
    assert main([*argv, "--report", str(tmp_path / "report")]) == 0
    out = capsys.readouterr().out
    assert "rec.csv: healthy" in out
    assert "dB over the baseline's margin" in out and "as in the baseline" in out
    report = (tmp_path / "report" / "report.md").read_text()
    assert "no: as in the baseline" in report
