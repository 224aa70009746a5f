"""Speed against accuracy: one scene at every model level and integrator setting.

For each setting the study measures the wall time per simulated second (best of two runs
after compilation, one core), the relative error of the WPF (or BPFO) band amplitude and the
relative L2 error of the amplitude spectrum up to ``f_max`` against a reference run (full
model with EHL, RK4 at ``reference_step``), and whether the run stayed stable. It marks the
Pareto front (no other setting is both faster and more accurate in the band amplitude) and
recommends the cheapest stable setting under an error bound.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pandas as pd

import features
from generators import (
    BearingGeometry,
    LocalizedDefect,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    simulate,
    waviness_passage_frequencies,
)

__all__ = [
    "fidelity_study",
    "recommend",
    "FIDELITY_COLUMNS",
    "plot_fidelity",
    "DEFAULT_RK4_STEPS",
    "DEFAULT_DOPRI5_RTOLS",
]

FIDELITY_COLUMNS = (
    "scene",
    "ehl",
    "integrator",
    "step_or_tolerance",
    "wall_s_per_simulated_s",
    "band_amplitude_error",
    "spectrum_error",
    "stable",
    "pareto",
    "chosen_for_bound",
    "step_used_s",
)
DEFAULT_RK4_STEPS = (2.5e-6, 5e-6, 7.5e-6, 1e-5, 2e-5, 5e-5, 1e-4, 2e-4)
DEFAULT_DOPRI5_RTOLS = (1e-4, 1e-6, 1e-8)
CHANNEL = "housing_velocity_y"


def _band_frequency(result, defects: Sequence[Waviness | LocalizedDefect]) -> float:
    """The line a fidelity run measures [Hz].

    The first strong waviness line of the first waviness, the fault frequency of the first
    local defect (BPFO, BPFI, 2xBSF), or BPFO for a healthy bearing.
    """
    f = result.frequencies
    for w in defects:
        if isinstance(w, LocalizedDefect):
            return {"outer": f.bpfo, "inner": f.bpfi, "ball": f.two_bsf}[w.surface]
        if w.order >= 1:
            from generators import bearing

            lines = waviness_passage_frequencies(
                bearing(result.parameters["bearing"]["name"]),
                f.shaft,
                w.surface,
                w.order,
                max_harmonic=2,
            )
            strong = [ln for ln in lines if ln.strength == "strong"]
            if strong:
                return strong[0].frequency
    return f.bpfo


def _measure(geometry, operating, defects, scene, rig, settings, seed):
    warm = dataclasses.replace(settings, duration=min(settings.duration, 0.01), settle_time=0.0)
    simulate(geometry, operating, defects, scene=scene, rig=rig, settings=warm, random_state=seed)
    best, result = math.inf, None
    for _ in range(2):
        t0 = time.perf_counter()
        result = simulate(
            geometry, operating, defects, scene=scene, rig=rig, settings=settings, random_state=seed
        )
        best = min(best, time.perf_counter() - t0)
    return best / (settings.duration + settings.settle_time), result


def _step_used(stats: dict, settings: SimulationSettings) -> float:
    """The step a run took [s].

    RK4's (the requested one shortened onto the record grid by up to 20 %,
    ``generators.steps.rk4_schedule``), DOPRI5's mean accepted step.
    """
    if "step_s" in stats:
        return float(stats["step_s"])
    accepted = stats.get("accepted_steps", 0)
    simulated = settings.duration + settings.settle_time
    return simulated / accepted if accepted else math.nan


def fidelity_study(
    geometry: BearingGeometry,
    operating: OperatingCondition,
    defects: Sequence[Waviness] = (),
    *,
    rig: Rig | None = None,
    settings: SimulationSettings | None = None,
    levels: Sequence[str] = ("shaft", "shaft+housing", "full"),
    ehl_options: Sequence[bool] = (False, True),
    rk4_steps: Sequence[float] = DEFAULT_RK4_STEPS,
    dopri5_rtols: Sequence[float] = DEFAULT_DOPRI5_RTOLS,
    reference_step: float = 1e-6,
    f_max: float = 5000.0,
    seed: int = 0,
    error_bound: float | None = None,
    progress: Callable[[int, int, str], None] | None = None,
) -> pd.DataFrame:
    """Run one scene at every model level and integrator setting and compare with a reference.

    Parameters
    ----------
    geometry, operating, defects
        The scene (bearing, speed [Hz] and load [N], waviness).
    rig : Rig, optional
        Rig parameters.
    settings : SimulationSettings, optional
        Sample rate [Hz], duration [s], settling [s] (step and integrator are varied).
    levels, ehl_options : sequences
        Model levels and film switches to try.
    rk4_steps : sequence of float
        RK4 steps [s]; steps beyond the stability limit of a level are run and reported as
        unstable.
    dopri5_rtols : sequence of float
        DOPRI5 relative tolerances.
    reference_step : float
        RK4 step of the reference run (full model with EHL) [s].
    f_max : float
        Upper frequency of the spectrum error [Hz].
    seed : int
        Seed of the random waviness phases (the same for every run).
    error_bound : float, optional
        Also run each level and film at the RK4 step ``SimulationSettings(error_bound=...)``
        chooses for it (:mod:`generators.accuracy`: the integration error alone, in lines and
        octave bands); those rows have ``chosen_for_bound`` True, the chosen step, and the
        wall time of a run once the pilots are cached (their cost is not counted).
    progress : callable, optional
        ``progress(done, total, label)`` after each run.

    Returns
    -------
    DataFrame
        One row per setting, columns ``FIDELITY_COLUMNS``; errors are relative (0.01 = 1 %),
        NaN for unstable runs; ``step_or_tolerance`` is the setting asked for (the chosen step
        for ``chosen_for_bound`` rows) and ``step_used_s`` the step the run took (RK4's on the
        record grid, DOPRI5's mean accepted step) [s].
    """
    rig = rig or Rig()
    settings = settings or SimulationSettings(fs=25600.0, duration=1.0, settle_time=0.2)
    settings = dataclasses.replace(settings, channels=(CHANNEL,))
    if not 0.0 < f_max <= settings.fs / 2.0:  # NaN fails too
        raise ParameterError(
            f"f_max = {f_max:g} Hz is outside the allowed range (0, {settings.fs / 2.0:g}] Hz "
            "(up to half the sample rate)"
        )
    defects = tuple(defects)
    ref = simulate(
        geometry,
        operating,
        defects,
        scene=Scene(level="full", ehl=True),
        rig=rig,
        settings=dataclasses.replace(settings, integrator="rk4", step=reference_step),
        random_state=seed,
    )
    f_line = _band_frequency(ref, defects)
    freqs, ref_spec = features.amplitude_spectrum(ref[CHANNEL], ref.fs)
    band = (freqs > 0) & (freqs <= f_max)
    ref_amp = features.band_amplitude(freqs, ref_spec, f_line, half_width=1.5)
    ref_norm = float(np.linalg.norm(ref_spec[band]))
    runs = [(lvl, ehl, "rk4", s) for lvl in levels for ehl in ehl_options for s in rk4_steps]
    runs += [(lvl, ehl, "dopri5", r) for lvl in levels for ehl in ehl_options for r in dopri5_rtols]
    if error_bound is not None:
        runs += [(lvl, ehl, "bound", error_bound) for lvl in levels for ehl in ehl_options]
    rows = []
    for i, (level, ehl, integrator, value) in enumerate(runs):
        scene = Scene(level=level, ehl=ehl)
        if integrator == "rk4":
            st = dataclasses.replace(settings, integrator="rk4", step=value)
        elif integrator == "bound":
            st = dataclasses.replace(settings, integrator="rk4", step=None, error_bound=value)
        else:
            st = dataclasses.replace(settings, integrator="dopri5", rtol=value)
        chosen = integrator == "bound"
        try:
            wall, result = _measure(geometry, operating, defects, scene, rig, st, seed)
            _, spec = features.amplitude_spectrum(result[CHANNEL], result.fs)
            amp = features.band_amplitude(freqs, spec, f_line, half_width=1.5)
            used = _step_used(result.parameters["integrator_stats"], st)
            rows.append(
                (
                    level,
                    ehl,
                    "rk4" if chosen else integrator,
                    used if chosen else value,
                    wall,
                    abs(amp / ref_amp - 1.0),
                    float(np.linalg.norm(spec[band] - ref_spec[band]) / ref_norm),
                    True,
                    chosen,
                    used,
                )
            )
        except SimulationDivergedError:
            rows.append(
                (
                    level,
                    ehl,
                    "rk4" if chosen else integrator,
                    value,
                    *[math.nan] * 3,
                    False,
                    chosen,
                    math.nan,
                )
            )
        if progress is not None:
            progress(i + 1, len(runs), f"{scene.label} {integrator} {value:g}")
    columns = [c for c in FIDELITY_COLUMNS if c != "pareto"]
    table = pd.DataFrame(rows, columns=columns)
    table.insert(FIDELITY_COLUMNS.index("pareto"), "pareto", _pareto(table))
    table.attrs.update(
        {
            "band_frequency_hz": f_line,
            "reference_amplitude_m_s": ref_amp,
            "f_max_hz": f_max,
            "reference": f"full/ehl rk4 {reference_step:g} s",
        }
    )
    return table


def _pareto(table: pd.DataFrame) -> np.ndarray:
    ok = table["stable"].to_numpy(bool)
    wall = table["wall_s_per_simulated_s"].to_numpy(float)
    err = table["band_amplitude_error"].to_numpy(float)
    front = np.zeros(len(table), dtype=bool)
    for i in np.flatnonzero(ok):
        dominated = ok & (wall <= wall[i]) & (err <= err[i]) & ((wall < wall[i]) | (err < err[i]))
        front[i] = not dominated.any()
    return front


def recommend(table: pd.DataFrame, error_bound: float) -> pd.Series | None:
    """Cheapest stable setting whose band amplitude error is at most ``error_bound``.

    Parameters
    ----------
    table : pandas.DataFrame
        The fidelity study's table (``cmtool fidelity``).
    error_bound : float
        The largest relative band amplitude error allowed (0.01: 1 %).

    Returns
    -------
    pandas.Series or None
        The table's row, None when no stable setting meets the bound.
    """
    ok = table[table["stable"] & (table["band_amplitude_error"] <= error_bound)]
    if ok.empty:
        return None
    return ok.sort_values("wall_s_per_simulated_s").iloc[0]


def plot_fidelity(
    table: pd.DataFrame, path: str | Path, *, error_bound: float | None = None
) -> Path:
    """Runtime against band amplitude error, one marker per setting, Pareto front joined.

    Parameters
    ----------
    table : pandas.DataFrame
        The fidelity study's table (``cmtool fidelity``).
    path : str or Path
        The PNG written.
    error_bound : float, optional
        The bound drawn as a line (relative error).

    Returns
    -------
    Path
    """
    from .plots import plt, save_figure

    path = Path(path)
    fig, ax = plt.subplots(figsize=(8, 5), dpi=110)
    stable = table[table["stable"]]
    colors = plt.get_cmap("tab20").colors
    for k, ((scene, ehl, integ), group) in enumerate(
        stable.groupby(["scene", "ehl", "integrator"])
    ):
        ax.scatter(
            group["wall_s_per_simulated_s"],
            group["band_amplitude_error"].clip(1e-7),
            marker="o" if integ == "rk4" else "s",
            s=28,
            color=colors[k % len(colors)],
            label=f"{scene}/{'ehl' if ehl else 'dry'} {integ}",
        )
    front = stable[stable["pareto"]].sort_values("wall_s_per_simulated_s")
    ax.plot(
        front["wall_s_per_simulated_s"],
        front["band_amplitude_error"].clip(1e-7),
        "k--",
        lw=1,
        label="Pareto front",
    )
    if error_bound is not None:
        ax.axhline(error_bound, color="red", lw=0.8, ls=":", label=f"bound {error_bound:g}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per simulated second [s] (one core)")
    ax.set_ylabel("relative error of the band amplitude [-]")
    ax.set_title("speed against accuracy (reference: full model with EHL, RK4 1 us)")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    return save_figure(fig, path)
