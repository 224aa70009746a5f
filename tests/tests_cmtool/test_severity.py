"""A race spall's length on a fault verdict (cmtool.severity; docs/diagnosis.md, Severity).

The model's spalls: a ball unloads where it enters one and is struck where it leaves it.
"""

import json

import numpy as np
import pytest

from cmtool.cli import main
from cmtool.diagnose import diagnose_signal
from cmtool.severity import contact_length_scale, spall_size
from generators import (
    LocalizedDefect,
    OperatingCondition,
    SimulationSettings,
    bearing,
    characteristic_frequencies,
    entrainment_speed,
    simulate,
)

FS = 48000.0


def _record(surface: str, length: float, depth: float, noise: float, seed: int = 1):
    """1 s of a 6205 at 1797 rpm and 400 N, 1 % slip, with the pit, in white noise of
    ``noise`` x the record's RMS."""
    op = OperatingCondition.from_rpm(1797, 400.0, random_slip=0.01, ball_jitter=0.005)
    settings = SimulationSettings(fs=FS, duration=1.0, channels=("housing_acceleration_y",))
    pit = LocalizedDefect(surface=surface, length=length, depth=depth)
    x = simulate(bearing("6205"), op, pit, settings=settings, random_state=seed)
    x = x["housing_acceleration_y"]
    return x + np.random.default_rng(seed).normal(0.0, noise * x.std(), x.size)


@pytest.mark.parametrize(("surface", "noise"), [("inner", 0.3), ("outer", 0.1), ("ball", 0.1)])
def test_a_spalls_length_is_estimated_within_its_interval(surface, noise):
    """3 mm x 50 um spalls: the verdict's race or ball, a length within 10 % and an interval
    that holds it (an outer-race or a ball spall's entry is weaker in the housing's signal:
    less noise for them)."""
    d = diagnose_signal(_record(surface, 3e-3, 50e-6, noise), FS, 1797, "6205", waviness=False)
    assert d.verdict == {"ball": "ball"}.get(surface, f"{surface} race")
    size = d.to_dict()["severity"]
    assert size["estimated"] is True, size
    assert size["length_mm"] == pytest.approx(3.0, rel=0.1)
    low, high = size["interval_mm"]
    assert low < 3.0 < high and high - low < 1.5
    assert size["impacts"] >= 50 and size["reason"].startswith("spall length about")


def test_a_cwru_size_pit_is_not_sized():
    """A 0.18 mm pit, 0.28 mm deep, is bridged: one event per passage, nothing to time."""
    d = diagnose_signal(_record("inner", 1.8e-4, 2.8e-4, 0.3), FS, 1797, "6205", waviness=False)
    assert d.verdict == "inner race"
    assert d.severity["estimated"] is False
    assert d.severity["reason"].startswith("not estimated: no entry event")


def test_what_is_not_sized_says_why():
    g = bearing("6205")
    f = characteristic_frequencies(g, 1797 / 60)
    x = np.random.default_rng(0).standard_normal(12000)
    other, timing = spall_size(x, 12000.0, "cage", g, f)
    assert other == {"estimated": False, "reason": "not estimated for a 'cage' verdict"}
    assert timing is None
    slow, timing = spall_size(x, 3000.0, "outer race", g, f)
    assert slow["estimated"] is False and "3000 Hz" in slow["reason"] and timing is None
    for verdict in ("outer race", "inner race", "ball"):
        noise, timing = spall_size(x, 12000.0, verdict, g, f)
        assert noise["estimated"] is False and not timing.resolved


def test_the_rolling_speed_and_the_contacts_length_scale():
    """The contact crosses either race at omega (D^2 - d^2) / (4 D) (no slip, no contact
    angle); the inner race's contact, more curved, has the shorter length scale."""
    g = bearing("6205")
    f = characteristic_frequencies(g, 30.0)
    expected = (
        2 * np.pi * 30.0 * (g.pitch_diameter**2 - g.ball_diameter**2) / (4 * g.pitch_diameter)
    )
    # the speed severity uses (generators.entrainment_speed) is the contact's speed over the
    # outer race (cage x outer radius) and over the inner race ((shaft - cage) x inner radius)
    outer = 2 * np.pi * f.ftf * 0.5 * (g.pitch_diameter + g.ball_diameter)
    inner = 2 * np.pi * (f.shaft - f.ftf) * 0.5 * (g.pitch_diameter - g.ball_diameter)
    for speed in (entrainment_speed(g, 30.0), outer, inner):
        assert speed == pytest.approx(expected, rel=1e-12)
    assert 0.2e-3 < contact_length_scale(g, "inner") < contact_length_scale(g, "outer") < 1e-3


def test_cli_diagnose_gives_the_spalls_length(tmp_path, capsys):
    """Text, JSON and report of a sized spall."""
    npy = tmp_path / "spall.npy"
    np.save(npy, _record("inner", 3e-3, 50e-6, 0.3))
    args = ["diagnose", str(npy), "--fs", "48000", "--rpm", "1797", "--bearing", "6205"]
    assert main([*args, "--report", str(tmp_path / "rep")]) == 0
    assert "fault size: spall length about" in capsys.readouterr().out
    report = (tmp_path / "rep" / "report.md").read_text()
    assert "spall length about" in report.split("## Fault size", 1)[1].split("##", 1)[0]
    assert (tmp_path / "rep" / "entry_exit.png").stat().st_size > 10_000
    assert main([*args, "--json"]) == 0
    size = json.loads(capsys.readouterr().out)["severity"]
    assert size["estimated"] is True and size["interval_mm"][0] < 3.0 < size["interval_mm"][1]


def test_a_routes_verdicts_table_gives_each_spalls_length(tmp_path):
    """`cmtool diagnose FOLDER --report OUT`: verdicts.csv's spall columns, empty where no
    size was estimated (a healthy record)."""
    import pandas as pd

    route = tmp_path / "route"
    route.mkdir()
    np.save(route / "spall.npy", _record("inner", 3e-3, 50e-6, 0.3))
    np.save(route / "noise.npy", np.random.default_rng(3).standard_normal(48000))
    (route / "MANIFEST.csv").write_text(
        "file,sampling_rate_hz,shaft_rpm,bearing\n"
        "spall.npy,48000,1797,6205\nnoise.npy,48000,1797,6205\n"
    )
    assert main(["diagnose", str(route), "--report", str(tmp_path / "out")]) == 0
    table = pd.read_csv(tmp_path / "out" / "verdicts.csv").set_index("file")
    spall, noise = table.loc["spall.npy"], table.loc["noise.npy"]
    assert spall.verdict == "inner race"
    assert spall.spall_low_mm < 3.0 < spall.spall_high_mm
    assert spall.spall_length_mm == pytest.approx(3.0, rel=0.1)
    assert noise.verdict == "healthy" and np.isnan(noise.spall_length_mm)


def test_the_radial_load_given_narrows_the_interval():
    """With the 400 N the record was simulated at, the interval is scaled at the ball load
    (5 F_r / Z): narrower than without a load, and it still holds the length."""
    x = _record("inner", 3e-3, 50e-6, 0.3)
    alone = diagnose_signal(x, FS, 1797, "6205", waviness=False).severity
    loaded = diagnose_signal(x, FS, 1797, "6205", waviness=False, load_n=400.0).severity
    assert alone["estimated"] and loaded["estimated"] and alone["load_n"] is None
    assert loaded["load_n"] == 400.0 and "radial load 400 N" in loaded["reason"]
    assert loaded["entry_exit_ms"] == alone["entry_exit_ms"]  # the same timing
    low, high = loaded["interval_mm"]
    assert low < 3.0 < high
    assert high - low < 0.8 * (alone["interval_mm"][1] - alone["interval_mm"][0])


def test_a_size_on_a_bearing_kappa_was_not_measured_on_says_so():
    """The offset was measured on the 6205 and the MFPT bearing: a 6308's spall (4 mm x 50 um,
    800 N, noise at 0.1 of the RMS) is sized, its interval holds the length, and it says
    where the interval was validated; a 6205's does not need to."""
    op = OperatingCondition.from_rpm(1797, 800.0, random_slip=0.01, ball_jitter=0.005)
    settings = SimulationSettings(fs=FS, duration=1.0, channels=("housing_acceleration_y",))
    pit = LocalizedDefect(surface="inner", length=4e-3, depth=50e-6)
    x = simulate(bearing("6308"), op, pit, settings=settings, random_state=1)
    x = x["housing_acceleration_y"]
    x = x + np.random.default_rng(1).normal(0.0, 0.1 * x.std(), x.size)
    size = diagnose_signal(x, FS, 1797, "6308", waviness=False).severity
    assert size["estimated"] and size["interval_mm"][0] < 4.0 < size["interval_mm"][1]
    assert "measured on the 6205 and the MFPT bearing" in size["reason"]
    ours = diagnose_signal(_record("inner", 3e-3, 50e-6, 0.3), FS, 1797, "6205", waviness=False)
    assert ours.severity["estimated"] and "measured on" not in ours.severity["reason"]


def test_the_size_can_be_left_out():
    """`severity=False` (what `cmtool bench` asks: it scores verdicts, not sizes) leaves the
    size out of a fault verdict, and nothing else changes."""
    x = _record("inner", 3e-3, 50e-6, 0.3)
    sized = diagnose_signal(x, FS, 1797, "6205", waviness=False)
    unsized = diagnose_signal(x, FS, 1797, "6205", waviness=False, severity=False)
    assert sized.severity["estimated"] and unsized.severity is None
    assert "severity" not in unsized.to_dict()
    without = {k: v for k, v in sized.to_dict().items() if k != "severity"}
    assert unsized.to_dict() == without


def test_a_machines_trend_shows_its_spall_growing(tmp_path):
    """Dated recordings of one machine (healthy, then a 3 mm and a 3.5 mm inner-race spall):
    the sizes in verdicts.csv grow, and trend.png gets a third panel for them (a taller
    figure than a trend with no size)."""
    import matplotlib.image
    import pandas as pd

    route = tmp_path / "route"
    route.mkdir()
    records = {
        "m1.npy": np.random.default_rng(5).standard_normal(48000),
        "m2.npy": _record("inner", 3e-3, 50e-6, 0.3),
        "m3.npy": _record("inner", 3.5e-3, 50e-6, 0.3),
    }
    lines = ["file,sampling_rate_hz,shaft_rpm,bearing,machine,time"]
    for month, (name, x) in enumerate(records.items(), start=1):
        np.save(route / name, x)
        lines.append(f"{name},48000,1797,6205,pump,2026-{month:02d}-01T08:00")
    (route / "MANIFEST.csv").write_text("\n".join(lines) + "\n")
    assert main(["diagnose", str(route), "--report", str(tmp_path / "out")]) == 0
    table = pd.read_csv(tmp_path / "out" / "verdicts.csv").set_index("file")
    assert np.isnan(table.loc["m1.npy", "spall_length_mm"])
    assert 2.7 < table.loc["m2.npy", "spall_length_mm"] < table.loc["m3.npy", "spall_length_mm"]
    sized = matplotlib.image.imread(tmp_path / "out" / "trend.png").shape[0]
    np.save(route / "m0.npy", np.random.default_rng(6).standard_normal(48000))
    (route / "MANIFEST.csv").write_text(
        "\n".join(lines[:2]) + "\nm0.npy,48000,1797,6205,pump,2026-02-01T08:00\n"
    )  # two healthy records
    assert main(["diagnose", str(route), "--report", str(tmp_path / "healthy")]) == 0
    unsized = matplotlib.image.imread(tmp_path / "healthy" / "trend.png").shape[0]
    assert sized > 1.25 * unsized
