"""The realistic measurement chain in recipes (docs/realism.md): fault SNR, chain, S-curve."""

import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from cmtool.diagnose import diagnose_signal
from generators import ParameterError
from generators.cases import expand_cases
from generators.recipe import validate_recipe
from generators.synthesis import generate_cases

RECIPE = """
name = "chain"
seed = 11
bearings = ["6205"]
[operating]
rpm = [1797]
load_n = [400]
clearance_m = [-5e-6]
random_slip = { min = 0.005, max = 0.02 }
ball_jitter_rad = { min = 0.003, max = 0.01 }
[model]
scene = "shaft+housing"
ehl = false
[sensor]
fs_hz = 12000
duration_s = 1.0
settle_s = 0.05
background_db = { min = 0, max = 20 }
fault_snr_db = [-25, -15, -5, 5]
modes = { min = 2, max = 3 }
mode_hz = { min = 1000, max = 5000 }
mode_damping = { min = 0.02, max = 0.08 }
mode_gain_db = { min = -12, max = 0 }
sensor_resonance_hz = { min = 4000, max = 8000 }
anti_alias = 0.42
adc_bits = 16
[background]
shaft_db = { min = 0, max = 20 }
line_db = { min = -10, max = 10 }
other_bearing = "6203"
other_bearing_db = { min = -10, max = 0 }
floor_db = { min = -20, max = -10 }
[[conditions]]
label = "healthy"
count = 8
[[conditions]]
label = "outer"
surface = "outer"
defect = "localized"
length_m = { min = 0.2e-3, max = 0.5e-3 }
depth_m = [0.28e-3]
position_rad = [-1.5708]
count = 40
"""


@pytest.fixture(scope="module")
def rows():
    recipe = validate_recipe(tomllib.loads(RECIPE))
    return generate_cases(recipe, expand_cases(recipe))


def test_the_chain_is_recorded_and_the_fault_snr_is_reached(rows):
    for row in rows:
        assert row["error"] is None
        assert np.all(np.isfinite(row["signal"]))
        chain = json.loads(row["chain"])
        assert 2 <= len(chain["modes"]) <= 3 and chain["adc_bits"] == 16
        assert chain["anti_alias"] == 0.42 and 4000 <= chain["sensor_resonance_hz"] <= 8000
        assert len(chain["other_lines"]) == 3 and len(chain["shaft_amplitudes"]) == 3
        assert 0.005 <= row["random_slip"] <= 0.02
        if row["label"] == "healthy":
            assert math.isnan(row["fault_snr_db"]) and "fault_gain" not in chain
            continue
        low, high = row["fault_band_low_hz"], row["fault_band_high_hz"]
        assert 0 < low < high <= 0.45 * 12000
        # a pit in the load zone of a preloaded bearing is loud enough for every drawn SNR:
        # the signature was scaled, not capped, and the recorded SNR is the drawn one
        assert chain["fault_gain"] < 100.0
        assert min(abs(row["fault_snr_db"] - v) for v in (-25, -15, -5, 5)) < 1e-6


def test_detection_rises_with_the_fault_snr_as_an_s_curve(rows):
    """The rule detector on a sweep of the recipe's fault SNR: 0.3 or less in the lowest bin,
    0.9 or more in the highest, never falling in between, and no healthy case called faulty."""
    by_snr: dict[float, list[bool]] = {}
    for row in rows:
        d = diagnose_signal(row["signal"], row["fs_hz"], row["rpm"], "6205")
        if row["label"] == "healthy":
            assert d.verdict == "healthy", d.candidates
            continue
        by_snr.setdefault(round(row["fault_snr_db"]), []).append(d.verdict == "outer race")
    rates = [np.mean(by_snr[k]) for k in sorted(by_snr)]
    assert rates[0] <= 0.3 and rates[-1] >= 0.9, rates
    assert all(b >= a - 0.1 for a, b in zip(rates, rates[1:], strict=False)), rates


def test_chain_keys_are_validated():
    base = tomllib.loads(RECIPE)
    for key, value, match in (
        ("modes", 0, r"sensor.modes = 0"),
        ("anti_alias", 0.6, r"sensor.anti_alias"),
        ("electronic_floor_db", 10, r"sensor.electronic_floor_db = 10\b.*\[-120, 0\]"),
        ("resonance_hz", 3000, r"resonance_hz is the older"),
    ):
        bad = tomllib.loads(RECIPE)
        bad["sensor"][key] = value
        with pytest.raises(ParameterError, match=match):
            validate_recipe(bad)
    bad = dict(base, background={**base["background"], "other_bearing": "9999"})
    with pytest.raises(ParameterError, match="background.other_bearing"):
        validate_recipe(bad)
    bad = tomllib.loads(RECIPE)
    del bad["sensor"]["background_db"]
    del bad["sensor"]["fault_snr_db"]
    with pytest.raises(ParameterError, match="background_db"):
        validate_recipe(bad)


def test_the_recipes_of_machines_draw_their_bearings_form_lines():
    """Stop 67 (docs/realism.md 9, against bars written before the draws): the rig recipes and
    the universal one draw the bearing's own form lines at the argued ranges; the small
    reference dataset and the detector benchmark (published figures) do not."""
    datasets = Path(__file__).resolve().parents[2] / "datasets"
    for name in ("cwru-rig", "mfpt-rig", "universal", "small", "detector-bench"):
        recipe = validate_recipe(tomllib.loads((datasets / f"{name}.toml").read_text()))
        background = recipe.get("background", {})
        drawn = {k: background.get(k) for k in ("form_inner_db", "form_ball_db")}
        if name in ("small", "detector-bench"):
            assert drawn == {"form_inner_db": None, "form_ball_db": None}, name
        else:
            assert drawn == {
                "form_inner_db": {"range": (-20.0, 10.0)},
                "form_ball_db": {"range": (-30.0, 0.0)},
            }, name


def test_the_bearings_own_form_lines_stand_at_its_rates_and_drawn_levels():
    """``[background] form_inner_db`` and ``form_ball_db``: a healthy bearing's own form-error
    lines (docs/realism.md 9) at BPFI - fs, BPFI, BPFI + fs and 2 BSF - FTF, 2 BSF, 2 BSF + FTF,
    at the drawn level over the healthy bearing's RMS at the sensor; the rest of a case's chain
    unchanged in kind, and a recipe without the keys drawing none."""
    from features import amplitude_spectrum
    from generators import bearing, characteristic_frequencies
    from generators.synthesis import FORM_LINE_PATTERN_DB

    text = RECIPE.replace("count = 40", "count = 1").replace("count = 8", "count = 2")
    with_lines = text.replace(
        "floor_db = { min = -20, max = -10 }",
        "floor_db = { min = -20, max = -10 }\nform_inner_db = { min = -1, max = 1 }\n"
        "form_ball_db = { min = -11, max = -9 }",
    )
    recipe = validate_recipe(tomllib.loads(with_lines))
    plain = validate_recipe(tomllib.loads(text))
    f = characteristic_frequencies(bearing("6205"), 1797 / 60)
    for row, without in zip(
        generate_cases(recipe, expand_cases(recipe)),
        generate_cases(plain, expand_cases(plain)),
        strict=True,
    ):
        chain = json.loads(row["chain"])
        inner_db, ball_db = chain["form_inner_db"], chain["form_ball_db"]
        assert -1.0 <= inner_db <= 1.0 and -11.0 <= ball_db <= -9.0
        assert "form_inner_db" not in json.loads(without["chain"])
        lines = chain["form_lines"]
        assert (
            len(lines) == 6 and chain["other_lines"] == json.loads(without["chain"])["other_lines"]
        )
        wanted = [f.bpfi - f.shaft, f.bpfi, f.bpfi + f.shaft, f.two_bsf - f.ftf, f.two_bsf]
        assert np.allclose([hz for hz, _ in lines[:5]], wanted)
        # the levels: BPFI at the drawn level, its sidebands -7 and +4 dB, the ball's at its own
        inner = [a for _, a in lines[:3]]
        ball = [a for _, a in lines[3:]]
        assert np.allclose(20 * np.log10(np.array(inner) / inner[1]), [-7.0, 0.0, 4.0])
        assert np.allclose(20 * np.log10(np.array(ball) / inner[1]), [ball_db - inner_db] * 3)
        assert [p[1] for p in FORM_LINE_PATTERN_DB["form_inner_db"]] == [-7.0, 0.0, 4.0]
        # and in the signal: a line at BPFI where the recipe without the keys has none
        freqs, amp = amplitude_spectrum(np.asarray(row["signal"], float), row["fs_hz"])
        _, amp0 = amplitude_spectrum(np.asarray(without["signal"], float), row["fs_hz"])
        near = np.abs(freqs - f.bpfi) < 2.0
        assert amp[near].max() > 10 * amp0[near].max()
        # every other draw of the case is the same: the difference is the lines alone (up to
        # the converter's rounding, whose full scale the lines move)
        diff = np.asarray(row["signal"], float) - np.asarray(without["signal"], float)
        _, lines_only = amplitude_spectrum(diff, row["fs_hz"])
        far = (freqs > 1000.0) & (freqs < 4000.0)
        assert lines_only[far].max() < 0.01 * amp0[far].max()


def _wideband_pair() -> str:
    """RECIPE at 48 kHz over a 2 kHz mounted resonance, one healthy and one faulty case of 0.5
    s: above the resonance the machine has rolled off, where the chain's own noise shows."""
    return (
        RECIPE.replace("fs_hz = 12000", "fs_hz = 48000")
        .replace("sensor_resonance_hz = { min = 4000, max = 8000 }", "sensor_resonance_hz = 2000")
        .replace("count = 40", "count = 1")
        .replace("count = 8", "count = 1")
        .replace("duration_s = 1.0", "duration_s = 0.5")
    )


def test_the_electronics_floor_is_white_after_the_sensors_resonance():
    """``[sensor] electronic_floor_db`` (docs/realism.md 2): the sensor's and the recorder's own
    noise comes after the mounted resonance, so at 48 kHz above a 2 kHz resonance, where the
    machine's floor has rolled off, the record is white at the drawn level over the sensor
    output's RMS (up to the anti-alias filter); where the machine stands well over them, the
    record is the one without the key, whose every other draw is the same."""
    from scipy import signal as sp_signal

    text = _wideband_pair()
    drawn = text.replace("anti_alias = 0.42", "electronic_floor_db = [-50]\nanti_alias = 0.42")
    plain = validate_recipe(tomllib.loads(text))
    recipe = validate_recipe(tomllib.loads(drawn))
    (without,) = generate_cases(plain, expand_cases(plain)[:1])  # the healthy case
    (row,) = generate_cases(recipe, expand_cases(recipe)[:1])
    assert row["label"] == "healthy"
    chain, chain_without = json.loads(row["chain"]), json.loads(without["chain"])
    assert chain.pop("electronic_floor_db") == -50.0 and "electronic_floor_db" not in chain_without
    floor_rms = chain.pop("electronic_floor_rms")
    for key in ("adc_full_scale", "clipped_fraction"):  # the floor moves the record's peak
        chain.pop(key), chain_without.pop(key)
    assert chain == chain_without
    fs = 48000.0
    freqs, psd = sp_signal.welch(np.asarray(row["signal"], float), fs, nperseg=2048)
    _, psd_without = sp_signal.welch(np.asarray(without["signal"], float), fs, nperseg=2048)
    high = (freqs > 9000.0) & (freqs < 15000.0)
    white = 2.0 * floor_rms**2 / fs  # one-sided density of white noise of that RMS
    # without the electronics the record has rolled off there, 10 dB and more under them
    assert np.mean(psd_without[high]) < 0.1 * white
    level_db = 10.0 * np.log10(np.mean(psd[high]) / white)
    assert -0.5 < level_db < 1.0, level_db  # the machine's residue adds at most 0.4 dB
    lower, upper = (freqs > 9000.0) & (freqs < 12000.0), (freqs > 12000.0) & (freqs < 15000.0)
    tilt_db = 10.0 * np.log10(np.mean(psd[upper]) / np.mean(psd[lower]))
    assert abs(tilt_db) < 0.5, tilt_db  # white: flat (each half's mean within 0.15 dB)
    # where the machine stands 20 dB and more over them, the record is the one without them
    loud = psd_without > 100.0 * white
    assert np.count_nonzero(loud[freqs < 2000.0]) > 20
    assert abs(np.sum(psd[loud]) / np.sum(psd_without[loud]) - 1.0) < 0.02


def test_a_record_has_the_absolute_level_of_its_healthy_machine():
    """``[sensor] machine_velocity_mm_s`` (docs/realism.md 2, stop 83): the healthy machine
    reads the drawn overall velocity in ISO 10816's band, as ``cmtool diagnose`` measures it
    (``features.velocity_band_rms``: another implementation than the chain's), and a fault
    raises the record over it; every record is the one without the key times a factor, since
    the level comes from a generator of its own and the chain after it reads ratios."""
    import features

    text = RECIPE.replace("count = 40", "count = 3").replace("count = 8", "count = 3")
    drawn = text.replace("adc_bits = 16", "adc_bits = 16\nmachine_velocity_mm_s = [0.45, 1.8]")
    plain = validate_recipe(tomllib.loads(text))
    recipe = validate_recipe(tomllib.loads(drawn))
    without = generate_cases(plain, expand_cases(plain))
    rows_with = generate_cases(recipe, expand_cases(recipe))
    seen = set()
    for row, before in zip(rows_with, without, strict=True):
        x, x0 = np.asarray(row["signal"], float), np.asarray(before["signal"], float)
        chain, chain0 = json.loads(row["chain"]), json.loads(before["chain"])
        target = chain.pop("machine_velocity_mm_s")
        scale = chain.pop("level_scale")
        seen.add(target)
        overall = 1e3 * features.velocity_band_rms(x, 12000.0, {"o": (10.0, 1000.0)})["o"]
        if row["label"] == "healthy":
            # the sensor's resonance, the anti-alias filter and the converter barely touch
            # 10-1000 Hz: within 1 %
            assert overall == pytest.approx(target, rel=0.01)
        else:
            assert overall > 0.99 * target
        # the record without the key times the factor, up to the converter's rounding
        assert np.std(x - scale * x0) < 1e-6 * np.std(x)
        assert row["noise_rms"] == pytest.approx(scale * before["noise_rms"], rel=1e-9)
        full_scale, full_scale0 = chain.pop("adc_full_scale"), chain0.pop("adc_full_scale")
        assert full_scale == pytest.approx(scale * full_scale0, rel=1e-9)
        assert chain == chain0  # every other draw the same (amplitudes before the scale)
    assert seen == {0.45, 1.8}
    for value, match in (
        (0.0, r"sensor.machine_velocity_mm_s = 0.0: .*\[0.001, 100\] mm/s"),
        ([1.0, 200.0], r"sensor.machine_velocity_mm_s = \[1.0, 200.0\]"),
    ):
        bad = tomllib.loads(drawn)
        bad["sensor"]["machine_velocity_mm_s"] = value
        with pytest.raises(ParameterError, match=match):
            validate_recipe(bad)
    bad = tomllib.loads(drawn)
    bad["sensor"]["body"] = "shaft"
    with pytest.raises(ParameterError, match=r"machine_velocity_mm_s.*a housing's"):
        validate_recipe(bad)
    bad = tomllib.loads(text)  # a recipe without the realistic chain has no such level
    del bad["background"]
    for key in ("modes", "mode_hz", "mode_damping", "mode_gain_db", "sensor_resonance_hz"):
        del bad["sensor"][key]
    del bad["sensor"]["anti_alias"], bad["sensor"]["adc_bits"]
    bad["sensor"]["machine_velocity_mm_s"] = 1.0
    with pytest.raises(ParameterError, match=r"machine_velocity_mm_s.*needs sensor.modes"):
        validate_recipe(bad)
    from generators.measurement import overall_velocity_band, overall_velocity_rms

    with pytest.raises(ParameterError, match=r"quantity = 'jerk'"):
        overall_velocity_rms(np.ones(64), 12000.0, "jerk", (10.0, 1000.0))
    with pytest.raises(ParameterError, match=r"band = \(10, 1000\) Hz .* fs / 2 = 500 Hz"):
        overall_velocity_rms(np.ones(64), 1000.0, "acceleration", (10.0, 1000.0))
    assert overall_velocity_band(600.0, 12000.0) == (2.0, 1000.0)
    assert overall_velocity_band(1797.0, 1000.0) == (10.0, 500.0)


def test_the_sensors_own_noise_is_absolute_and_white_after_its_resonance():
    """``[sensor] sensor_noise_density`` (docs/realism.md 2): an accelerometer's own noise is a
    property of the sensor, not of the vibration it measures. The same healthy case at two
    absolute levels holds the same noise (recovered from the pair: its RMS the density times
    sqrt(fs / 2)); above a 2 kHz resonance, where the machine has rolled off, the record's
    density is the one drawn; a recipe without an absolute level or not of an acceleration
    is refused naming the key."""
    from scipy import signal as sp_signal

    fs, density = 48000.0, 2e-5
    text = _wideband_pair().replace(
        "adc_bits = 16", f"machine_velocity_mm_s = [0.28]\nsensor_noise_density = [{density}]"
    )
    records, chains = [], []
    for velocity in (0.28, 1.8):
        bare = text.replace("anti_alias = 0.42\n", "").replace("[0.28]", f"[{velocity}]")
        recipe = validate_recipe(tomllib.loads(bare))
        (row,) = generate_cases(recipe, expand_cases(recipe)[:1])  # the healthy case
        records.append(np.asarray(row["signal"], float))
        chains.append(json.loads(row["chain"]))
    (y1, y2), (s1, s2) = records, [c["level_scale"] for c in chains]
    noise = (s2 * y1 - s1 * y2) / (s2 - s1)  # y = s x + n at both levels
    expected = density * math.sqrt(fs / 2.0)
    assert chains[0]["sensor_noise_rms"] == chains[1]["sensor_noise_rms"] == pytest.approx(expected)
    assert np.std(noise) == pytest.approx(expected, rel=0.03)  # 24,000 samples: 0.5 % sd
    # with the anti-alias filter: the record's density above the resonance is the one drawn
    recipe = validate_recipe(tomllib.loads(text))
    (row,) = generate_cases(recipe, expand_cases(recipe)[:1])  # the healthy case
    freqs, psd = sp_signal.welch(np.asarray(row["signal"], float), fs, nperseg=2048)
    high = (freqs > 9000.0) & (freqs < 15000.0)
    level_db = 10.0 * np.log10(np.mean(psd[high]) / density**2)
    assert -0.5 < level_db < 1.0, level_db
    for change, match in (
        (("machine_velocity_mm_s = [0.28]\n", ""), r"sensor_noise_density.*machine_velocity_mm_s"),
        (("[sensor]", '[sensor]\nquantity = "velocity"'), r"sensor_noise_density.*'velocity'"),
        (("[2e-05]", "[1.0]"), r"sensor.sensor_noise_density = \[1.0\].*m/s\^2/sqrt\(Hz\)"),
    ):
        with pytest.raises(ParameterError, match=match):
            validate_recipe(tomllib.loads(text.replace(*change)))
