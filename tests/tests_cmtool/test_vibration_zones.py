"""The overall velocity's evaluation zone (ISO 10816-3 and -1 classes, or a site's limits)."""

import json

import numpy as np
import pandas as pd
import pytest

from cmtool.cli import main
from cmtool.diagnose import diagnose_signal
from cmtool.vibration_zones import MACHINE_CLASSES, parse_zone_limits, vibration_zone

FS = 12000.0


def _record(velocity_rms_mm_s: float, seconds: float = 2.0) -> np.ndarray:
    """A 50 Hz vibration of the given velocity RMS, as acceleration [m/s^2], in faint noise.

    a(t) = A sin(2 pi f t) has the velocity amplitude A / (2 pi f): RMS A / (2 pi f sqrt 2).
    """
    t = np.arange(int(seconds * FS)) / FS
    amplitude = velocity_rms_mm_s * 1e-3 * 2 * np.pi * 50.0 * np.sqrt(2.0)
    noise = np.random.default_rng(10816).standard_normal(t.size)
    return amplitude * np.sin(2 * np.pi * 50.0 * t) + 1e-3 * amplitude * noise


def _route(folder, velocities_mm_s: dict, **columns) -> dict:
    """Recordings of the given velocities in ``folder`` and its MANIFEST.csv with ``columns``
    added; returns the manifest's columns (to write again changed)."""
    for name, v in velocities_mm_s.items():
        np.save(folder / name, _record(v))
    n = len(velocities_mm_s)
    rows = {
        "file": list(velocities_mm_s),
        "sampling_rate_hz": [FS] * n,
        "shaft_rpm": [1797] * n,
        "bearing": ["6205"] * n,
        "unit": ["m/s^2"] * n,
        **columns,
    }
    pd.DataFrame(rows).to_csv(folder / "MANIFEST.csv", index=False)
    return rows


def test_each_class_has_increasing_boundaries_and_a_boundary_is_the_lower_zone():
    for name, (described, limits) in MACHINE_CLASSES.items():
        assert 0 < limits[0] < limits[1] < limits[2], name
        assert described.startswith("ISO 10816-"), name
        zones = [vibration_zone(v, name)["zone"] for v in (0.0, *limits)]
        assert zones == ["A", "A", "B", "C"], name  # on a boundary: the zone below it
        above = [vibration_zone(1.001 * v, name)["zone"] for v in limits]
        assert above == ["B", "C", "D"], name
    # the classes an analyst looks up most: medium machines on rigid support, small machines
    assert MACHINE_CLASSES["group2-rigid"][1] == (1.4, 2.8, 4.5)
    assert MACHINE_CLASSES["class-I"][1] == (0.71, 1.8, 4.5)


@pytest.mark.parametrize("text", ["1.4,2.8,4.5", "1.4/2.8/4.5", " 1.4; 2.8 ;4.5 ", "1.4 2.8 4.5"])
def test_site_limits_are_read_however_separated(text):
    assert parse_zone_limits(text) == (1.4, 2.8, 4.5)
    zone = vibration_zone(3.0, parse_zone_limits(text))
    assert zone["zone"] == "C" and zone["machine_class"] == "site limits"


@pytest.mark.parametrize("bad", ["1.4,2.8", "2.8,1.4,4.5", "0,1,2", "a,b,c", "1,2,nan", [1, 2]])
def test_bad_limits_and_classes_are_named(bad):
    with pytest.raises(ValueError, match="zone limits = .* outside the allowed range"):
        parse_zone_limits(bad)
    with pytest.raises(ValueError, match="machine class = 'group3-rigid' is not one of"):
        vibration_zone(1.0, "group3-rigid")
    with pytest.raises(ValueError, match=r"rms_mm_s = -1.0 is outside the allowed range"):
        vibration_zone(-1.0, "class-I")
    x = _record(2.0)
    with pytest.raises(ValueError, match="machine class = 'group3-rigid'"):  # before the work
        diagnose_signal(x, FS, 1797, "6205", unit="m/s^2", machine_class="group3-rigid")


def test_the_zone_of_a_known_velocity_in_the_library_the_text_json_and_report(tmp_path, capsys):
    """2.0 mm/s RMS at 50 Hz: zone B for a medium machine on rigid support (1.4-2.8), zone C
    for a small one (1.8-4.5); without the unit no zone, and a warning says why."""
    x = _record(2.0)
    d = diagnose_signal(x, FS, 1797, "6205", unit="m/s^2", machine_class="group2-rigid")
    assert d.overall_velocity["rms_mm_s"] == pytest.approx(2.0, rel=0.02)
    assert d.overall_velocity["zone"]["zone"] == "B"
    assert d.to_dict()["overall_velocity_iso10816"]["zone"]["limits_mm_s"] == [1.4, 2.8, 4.5]
    assert diagnose_signal(x, FS, 1797, "6205", unit="m/s^2").overall_velocity.get("zone") is None
    unknown = diagnose_signal(x, FS, 1797, "6205", machine_class="class-I")
    assert "zone" not in unknown.overall_velocity
    assert any("no vibration zone" in w and "--unit" in w for w in unknown.warnings)

    np.save(tmp_path / "rec.npy", x)
    argv = ["diagnose", str(tmp_path / "rec.npy"), "--fs", "12000", "--rpm", "1797"]
    argv += ["--bearing", "6205", "--unit", "m/s^2"]
    assert main([*argv, "--machine-class", "class-I", "--report", str(tmp_path / "rep")]) == 0
    said = [line for line in capsys.readouterr().out.splitlines() if "vibration zone" in line]
    assert len(said) == 1 and said[0].strip().startswith("vibration zone C (ISO 10816-1 class I")
    assert "Vibration zone C (ISO 10816-1 class I" in (tmp_path / "rep" / "report.md").read_text()
    assert main([*argv, "--zone-limits", "2.5,5,10", "--json"]) == 0
    zone = json.loads(capsys.readouterr().out)["overall_velocity_iso10816"]["zone"]
    assert (zone["zone"], zone["machine_class"], zone["limits_mm_s"]) == (
        "A",
        "site limits",
        [2.5, 5.0, 10.0],
    )
    with pytest.raises(SystemExit):  # a class and limits are one or the other
        main([*argv, "--machine-class", "class-I", "--zone-limits", "1,2,3"])
    with pytest.raises(SystemExit):
        main([*argv, "--zone-limits", "3,2,1"])
    assert "each above 0 and above the one before" in capsys.readouterr().err


def test_a_manifest_gives_each_machine_its_class_and_verdicts_csv_its_zone(tmp_path, capsys):
    """A route of three machines: one by class, one by a site's limits, one with none (then
    --machine-class stands in); verdicts.csv has each one's zone. A value that is neither is
    refused with its line and column."""
    velocities = {"a.npy": 2.0, "b.npy": 2.0, "c.npy": 5.0}
    rows = _route(tmp_path, velocities, machine_class=["group2-rigid", "1/3/5", ""])
    out = tmp_path / "out"
    argv = ["diagnose", str(tmp_path), "--report", str(out), "--machine-class", "class-I"]
    assert main(argv) == 0
    capsys.readouterr()
    table = pd.read_csv(out / "verdicts.csv")
    assert dict(zip(table["file"], table["zone"], strict=True)) == {
        "a.npy": "B",  # group 2, rigid: 1.4-2.8
        "b.npy": "B",  # the site's 1-3
        "c.npy": "D",  # --machine-class class-I: over 4.5
    }
    index = (out / "index.md").read_text().splitlines()
    assert "| zone | report |" in index[2]  # the index's column, where a class was given
    assert [line.split(" | ")[-2] for line in index[4:7]] == ["B", "B", "D"]
    rows["machine_class"] = ["group2-rigid", "group9", ""]
    pd.DataFrame(rows).to_csv(tmp_path / "MANIFEST.csv", index=False)
    assert main(["diagnose", str(tmp_path)]) != 0
    err = capsys.readouterr().err
    assert "machine_class = 'group9' is not one of" in err and "line 3" in err, err


def test_a_machines_trend_draws_the_zone_boundaries_it_was_judged_by(tmp_path, monkeypatch, capsys):
    """Three dated recordings of one pump, 1, 2 and 5 mm/s, its class in the manifest: zones
    A, B and D in verdicts.csv, and trend.png's velocity panel draws the class's three
    boundaries (ISO 10816-3 group 2, rigid: 1.4, 2.8, 4.5 mm/s); a pump whose recordings were
    judged by different boundaries gets none drawn."""
    import cmtool.plots as plots

    drawn = {}

    def keep(fig, path):  # the zone lines of the velocity panel, then the figure closed
        if path.name == "trend.png":
            velocity = fig.axes[1]
            drawn["trend"] = sorted(
                line.get_ydata()[0]
                for line in velocity.lines
                if line.get_label().startswith("zone")
            )
        plots.plt.close(fig)
        return path

    monkeypatch.setattr(plots, "save_figure", keep)
    rows = _route(
        tmp_path,
        {"a.npy": 1.0, "b.npy": 2.0, "c.npy": 5.0},
        machine=["pump"] * 3,
        time=["2026-01-01", "2026-02-01", "2026-03-01"],
        machine_class=["group2-rigid"] * 3,
    )
    out = tmp_path / "out"
    assert main(["diagnose", str(tmp_path), "--report", str(out)]) == 0
    capsys.readouterr()
    table = pd.read_csv(out / "verdicts.csv")
    assert table["zone"].tolist() == ["A", "B", "D"]
    assert set(table["zone_limits_mm_s"]) == {"1.4/2.8/4.5"}
    assert drawn.pop("trend") == [1.4, 2.8, 4.5]
    rows["machine_class"] = ["group2-rigid", "class-I", "group2-rigid"]
    pd.DataFrame(rows).to_csv(tmp_path / "MANIFEST.csv", index=False)
    assert main(["diagnose", str(tmp_path), "--report", str(out)]) == 0
    assert drawn.pop("trend") == []
