"""The speed/accuracy study: table contract, Pareto front, recommendation, CLI outputs."""

import math

import pandas as pd
import pytest

from cmtool.cli import main
from cmtool.fidelity import FIDELITY_COLUMNS, fidelity_study, recommend
from generators import OperatingCondition, SimulationSettings, Waviness, bearing

SHORT = SimulationSettings(fs=12800.0, duration=0.25, settle_time=0.05)


@pytest.fixture(scope="module")
def table():
    return fidelity_study(
        bearing("6205"),
        OperatingCondition.from_rpm(1800, 500.0),
        [Waviness(surface="outer", order=9, amplitude=1e-6)],
        settings=SHORT,
        levels=("shaft+housing", "full"),
        ehl_options=(False, True),
        rk4_steps=(2e-5, 1e-4),
        dopri5_rtols=(1e-6,),
        f_max=2000.0,
        error_bound=0.02,
    )


def test_table_contract(table):
    assert tuple(table.columns) == FIDELITY_COLUMNS
    assert len(table) == 2 * 2 * 3 + 2 * 2  # the grid, and each level's error-bound step


def test_the_table_says_which_step_each_run_took(table):
    """``step_used_s``: RK4 runs the requested step shortened onto the record grid by at most
    20 % (2e-5 s at 12 kHz stays, records between steps; 1e-4 s is cut to whole records), the
    bound's rows the step they list, DOPRI5 its mean accepted step, NaN where a run diverged."""
    ok = table[table.stable]
    rk4 = ok[(ok.integrator == "rk4") & ~ok.chosen_for_bound]
    ratio = rk4.step_used_s / rk4.step_or_tolerance
    assert ((ratio > 0.8 - 1e-12) & (ratio <= 1.0 + 1e-12)).all()
    assert (ok[ok.chosen_for_bound].step_used_s == ok[ok.chosen_for_bound].step_or_tolerance).all()
    dopri5 = ok[ok.integrator == "dopri5"]
    assert (dopri5.step_used_s > 0).all() and (dopri5.step_used_s < 1e-4).all()
    assert table[~table.stable].step_used_s.isna().all()


def test_each_level_at_the_step_its_error_bound_chooses(table):
    chosen = table[table.chosen_for_bound]
    assert len(chosen) == 4 and chosen.stable.all() and (chosen.integrator == "rk4").all()
    # the full model with EHL is the reference's physics: its error is the integrator's alone
    full = chosen[(chosen.scene == "full") & chosen.ehl].iloc[0]
    assert full.band_amplitude_error <= 0.02
    # the massless scenes' steps are an order of magnitude longer than the ball mode allows
    assert (
        chosen[chosen.scene == "shaft+housing"].step_or_tolerance.min() > 5 * full.step_or_tolerance
    )
    assert table.attrs["band_frequency_hz"] == pytest.approx(107.54, abs=0.01)


def test_unstable_settings_are_reported_not_hidden(table):
    full_big = table[
        (table.scene == "full") & (table.integrator == "rk4") & (table.step_or_tolerance == 1e-4)
    ]
    assert not full_big["stable"].any()  # 100 us is beyond the ball-mode stability limit
    assert full_big["band_amplitude_error"].isna().all()
    assert not full_big["pareto"].any()


def test_accuracy_ordering(table):
    def err(scene, ehl, integ, value):
        row = table[
            (table.scene == scene)
            & (table.ehl == ehl)
            & (table.integrator == integ)
            & (table.step_or_tolerance == value)
        ].iloc[0]
        return row.band_amplitude_error

    # the tight-tolerance full/EHL run agrees with the reference (same physics)
    assert err("full", True, "dopri5", 1e-6) < 1e-4
    # shaft+housing with EHL drops only the ball masses: close to the reference
    assert err("shaft+housing", True, "rk4", 2e-5) < 1e-3
    # dropping the film costs about 1 % at BPFO (docs/model.md 8.2 values are for the dry model)
    assert 1e-3 < err("shaft+housing", False, "rk4", 2e-5) < 0.03


def test_pareto_and_recommendation(table):
    stable = table[table.stable]
    for _, row in stable[stable.pareto].iterrows():
        better = stable[
            (stable.wall_s_per_simulated_s < row.wall_s_per_simulated_s)
            & (stable.band_amplitude_error < row.band_amplitude_error)
        ]
        assert better.empty
    best = recommend(table, 0.01)
    assert best is not None and best.band_amplitude_error <= 0.01
    cheaper = stable[
        (stable.band_amplitude_error <= 0.01)
        & (stable.wall_s_per_simulated_s < best.wall_s_per_simulated_s)
    ]
    assert cheaper.empty
    assert recommend(table, 1e-12) is None


def test_cli_writes_csv_and_plot(tmp_path, capsys):
    out, plot = tmp_path / "table.csv", tmp_path / "fidelity.png"
    rc = main(
        [
            "fidelity",
            "--levels",
            "shaft",
            "--no-ehl",
            "--steps",
            "5e-5",
            "--rtols",
            "1e-5",
            "--duration",
            "0.1",
            "--settle",
            "0.02",
            "--fs",
            "10240",
            "--f-max",
            "2000",
            "--error-bound",
            "0.2",
            "--out",
            str(out),
            "--plot",
            str(plot),
        ]
    )
    assert rc == 0
    written = pd.read_csv(out)
    assert list(written.columns) == list(FIDELITY_COLUMNS)
    assert plot.stat().st_size > 10_000
    text = capsys.readouterr().out
    assert "spectrum error up to 2000 Hz" in text  # --f-max reached the study
    assert "under a 0.2 band-amplitude error bound" in text or "error bound 0.2" in text
    assert all(math.isfinite(v) for v in written.wall_s_per_simulated_s)
