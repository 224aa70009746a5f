"""Form errors (generators.form): the waviness every manufactured race and ball carries."""

import dataclasses
import tomllib

import numpy as np
import pytest

from generators import (
    OperatingCondition,
    SimulationSettings,
    bearing,
    characteristic_frequencies,
    form_waviness,
    simulate,
)
from generators import _kernels as K
from generators.cases import expand_cases
from generators.recipe import validate_recipe
from generators.synthesis import _setup


def test_form_waviness_lists_the_orders_that_make_lines():
    rows = form_waviness(9, 1e-7, 2e-7, 1e-7)
    inner = [(w.order, w.amplitude) for w in rows if w.surface == "inner"]
    outer = [w.order for w in rows if w.surface == "outer"]
    balls = [(w.order, w.amplitude) for w in rows if w.surface == "ball"]
    assert [k for k, _ in inner] == outer == [8, 9, 10, 17, 18, 19]
    # the amplitude at order Z is the one given, falling as Z / k
    assert dict(inner)[9] == pytest.approx(1e-7) and dict(inner)[18] == pytest.approx(0.5e-7)
    assert balls == [(2, pytest.approx(1e-7)), (4, pytest.approx(0.5e-7))]
    assert all(w.phase is None and w.ball is None for w in rows)  # every ball its own phase
    assert form_waviness(9, 0.0, 0.0, 0.0) == ()
    assert {w.surface for w in form_waviness(8, 0.0, 1e-7, 0.0)} == {"outer"}


def _line_db(x, fs, f0):
    spectrum = np.abs(np.fft.rfft(x * np.hanning(x.size)))
    freqs = np.fft.rfftfreq(x.size, 1.0 / fs)
    i = int(np.argmin(np.abs(freqs - f0)))
    return 20.0 * np.log10(spectrum[i - 2 : i + 3].max())


def test_form_errors_put_lines_where_docs_model_2_1_says():
    """A perfect 6205 under a radial load vibrates at the ball pass rates only (varying
    compliance); with form errors of 0.05 um a line stands at BPFI (inner order Z, load
    zone), BPFI - f_s (order Z - 1) and 2 f_b (ball order 2), at least 20 dB over the same
    bins of the perfect bearing (measured: 77-97 dB; those bins hold next to nothing)."""
    g = bearing("6205", radial_internal_clearance=5e-6)
    op = OperatingCondition.from_rpm(1797, 300.0)
    settings = SimulationSettings(fs=12000.0, duration=0.5, settle_time=0.05)
    perfect = simulate(g, op, settings=settings)["housing_acceleration_y"]
    wavy = simulate(g, op, form_waviness(9, 5e-8, 0.0, 5e-8), settings=settings, random_state=3)
    wavy = wavy["housing_acceleration_y"]
    f = characteristic_frequencies(g, op.shaft_frequency)
    for line in (f.bpfi, f.bpfi - op.shaft_frequency, 2.0 * f.bsf):
        assert _line_db(wavy, 12000.0, line) - _line_db(perfect, 12000.0, line) > 20.0


RECIPE = """
name = "form"
seed = 11
[operating]
rpm = 1797
load_n = { min = 100, max = 500 }
random_slip = 0.01
ball_jitter_rad = 0.005
%s
[sensor]
fs_hz = 12000
duration_s = 0.1
settle_s = 0.02
background_db = 10
fault_snr_db = 0
[[conditions]]
label = "healthy"
count = 2
[[conditions]]
label = "outer"
surface = "outer"
defect = "localized"
length_m = 0.3e-3
depth_m = 0.1e-3
count = 3
"""
FORM = "race_form_waviness_m = { min = 0.01e-6, max = 0.2e-6 }\nball_form_waviness_m = 0.1e-6"


def test_a_case_and_its_healthy_twin_carry_the_same_form_errors():
    recipe = validate_recipe(tomllib.loads(RECIPE % FORM))
    shared: dict = {}
    for case in expand_cases(recipe):
        assert 0.01e-6 <= case.inner_form_waviness_m <= 0.2e-6
        assert case.inner_form_waviness_m != case.outer_form_waviness_m  # drawn per race
        assert case.ball_form_waviness_m == 0.1e-6
        job = _setup(recipe, case, "housing_acceleration_y", shared)
        form = job.run.wav[job.run.wav[:, K.W_SURFACE] <= K.SURF_BALL]
        assert form.shape[0] == 2 * 6 + 2 * 9  # six orders per race, two per ball
        if case.label == "outer":
            np.testing.assert_array_equal(job.healthy.wav, form)  # same orders and phases
            assert job.run.wav.shape[0] > form.shape[0]  # and the pit (with its slip) after


def test_a_recipe_without_form_errors_draws_the_cases_it_drew_before():
    with_form = expand_cases(validate_recipe(tomllib.loads(RECIPE % FORM)))
    without = expand_cases(validate_recipe(tomllib.loads(RECIPE % "")))
    names = ("inner_form_waviness_m", "outer_form_waviness_m", "ball_form_waviness_m")
    for a, b in zip(with_form, without, strict=True):
        assert all(getattr(b, n) == 0.0 for n in names)
        assert dataclasses.replace(a, **dict.fromkeys(names, 0.0)) == b
