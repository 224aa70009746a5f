"""Warnings for runs whose record cannot show what their label names (generators.content)."""

import tomllib
from pathlib import Path

import numpy as np

from generators import (
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    simulate,
)
from generators.content import fault_rates_outside_record, odd_ball_waviness
from generators.recipe import recipe_content_warnings, validate_recipe

REPO = Path(__file__).resolve().parents[2]


def test_a_fault_rate_at_or_above_half_the_sample_rate_is_named():
    g = bearing("6205")
    f = characteristic_frequencies(g, 30.0)  # 1800 rpm: BPFI 162.5 Hz is the fastest
    assert fault_rates_outside_record(g, 30.0, 2.0 * f.bpfi + 1e-6) is None
    said = fault_rates_outside_record(g, 30.0, 2.0 * f.bpfi)
    assert said.startswith("fs = 324.9") and "BPFI 162.5 Hz" in said
    assert "BPFO" not in said and "BSF" not in said  # 107.5 and 141.4 Hz are below 162.5
    said = fault_rates_outside_record(g, 30.0, 100.0)
    assert "BPFO 107.5 Hz, BPFI 162.5 Hz, 2 x BSF 141.4 Hz" in said and "above 325 Hz" in said


def test_odd_ball_orders_leave_a_massless_scene_healthy_and_are_said_so():
    """The physics the warning rests on: an odd order cancels at the ball's two contacts,
    so without ball masses the record is the healthy one to the last bit; with them the
    ball's centre moves and the record changes."""
    g, op = bearing("6205"), OperatingCondition.from_rpm(1800, 500)
    settings = SimulationSettings(fs=12000.0, duration=0.1, channels=("housing_acceleration_y",))

    def record(level, defects):
        return simulate(g, op, defects, scene=Scene(level=level), settings=settings)[
            "housing_acceleration_y"
        ]

    odd = [Waviness(surface="ball", order=3, amplitude=1e-6)]
    even = [Waviness(surface="ball", order=2, amplitude=1e-6)]
    healthy = record("shaft+housing", None)
    assert np.array_equal(record("shaft+housing", odd), healthy)
    assert not np.allclose(record("shaft+housing", even), healthy, rtol=0, atol=0.1 * healthy.std())
    assert not np.array_equal(record("full", odd), record("full", None))
    assert "order 3" in odd_ball_waviness([2, 3], "shaft+housing")
    assert "order 1, 5" in odd_ball_waviness([5, 1], "shaft")
    assert odd_ball_waviness([3], "full") is None and odd_ball_waviness([2, 4], "shaft") is None


def test_a_recipe_is_warned_of_what_its_signals_cannot_show():
    text = (REPO / "datasets" / "small.toml").read_text()
    assert recipe_content_warnings(validate_recipe(tomllib.loads(text))) == []
    bad = text.replace("fs_hz = 6400", "fs_hz = 400").replace("order = [2, 4, 6]", "order = [2, 3]")
    said = recipe_content_warnings(validate_recipe(tomllib.loads(bad)))
    assert len(said) == 2
    assert said[0].startswith("recipe bearing 6205: fs = 400 Hz: at 2400 rpm")  # the fastest
    assert said[1].startswith("recipe conditions[3] ('ball'): ball waviness of odd order 3")
    # a range of orders holds the odd ones between its ends
    ranged = text.replace("order = [2, 4, 6]", "order = { min = 2, max = 4 }")
    said = recipe_content_warnings(validate_recipe(tomllib.loads(ranged)))
    assert len(said) == 1 and "odd order 3 " in said[0]
    # with ball masses odd orders vibrate: no warning
    full = bad.replace('scene = "shaft+housing"', 'scene = "full"')
    assert len(recipe_content_warnings(validate_recipe(tomllib.loads(full)))) == 1
