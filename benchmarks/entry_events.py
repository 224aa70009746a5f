"""The load-zone entry events of a bearing with form errors (docs/diagnosis.md, "Form errors
read as a local fault"): how impulsive the 3-4.7 kHz band of the housing acceleration is.

Prints, for a 6205 at 1797 rpm and 400 N, 12 kHz, 1 s: the spectral kurtosis of the band's
squared envelope (0 for Gaussian noise; E[e^2] / E[e]^2 - 2 of the squared band-passed signal)
and the band's share of the RMS, for the perfect bearing and with 0.1 um of inner-race form
errors, per scene, film and clearance; the same form-error case at three steps; and with the
contact damping off (``Rig(contact_damping_time=0)``). Last, what the rule sees: the same
kurtosis of the random part (``features.separate_discrete``) in the band the rule chooses
(``features.select_band``), for 0.1 um of inner-race or ball form errors and for 0.3 mm pits
with 1 % slip, clearance -5/5 um, 100/400 N.

Run: .venv/bin/python benchmarks/entry_events.py
"""

import numpy as np
from scipy import signal as sp_signal

from generators import (
    OperatingCondition,
    Rig,
    Scene,
    SimulationSettings,
    bearing,
    form_waviness,
    simulate,
)

BAND_HZ = (3000.0, 4688.0)
FS = 12000.0


def band_kurtosis(x: np.ndarray) -> tuple[float, float]:
    """Spectral kurtosis of the band (squared envelope) and the band's share of the RMS."""
    sos = sp_signal.butter(6, BAND_HZ, "bandpass", fs=FS, output="sos")
    y = sp_signal.sosfiltfilt(sos, x)
    e = y * y
    return float(np.mean(e * e) / np.mean(e) ** 2 - 2.0), float(np.std(y) / np.std(x))


def run(clearance: float, amplitude: float, **kw) -> tuple[float, float]:
    g = bearing("6205", radial_internal_clearance=clearance)
    op = OperatingCondition.from_rpm(1797, 400.0)
    settings = SimulationSettings(fs=FS, duration=1.0, settle_time=0.1, step=kw.pop("step", None))
    form = form_waviness(9, amplitude, 0.0, 0.0) or None
    x = simulate(g, op, form, settings=settings, random_state=2, **kw)["housing_acceleration_y"]
    return band_kurtosis(x)


def main() -> None:
    print("clearance [um] | scene | form [um] | band kurtosis | band / RMS")
    for clearance in (-5e-6, 5e-6):
        for ehl in (True, False):
            for level in ("shaft+housing", "full"):
                for amplitude in (0.0, 1e-7):
                    sk, share = run(clearance, amplitude, scene=Scene(level=level, ehl=ehl))
                    label = f"{level}/{'ehl' if ehl else 'dry'}"
                    print(
                        f"{clearance * 1e6:+.0f} | {label} | {amplitude * 1e6:.1f} | {sk:.1f} | "
                        f"{share:.4f}"
                    )
    for step in (None, 1e-5, 5e-6):
        sk, share = run(-5e-6, 1e-7, step=step)
        print(f"-5 um, form 0.1 um, step {step or 'default'}: kurtosis {sk:.3f}, share {share:.5f}")
    for tau in (Rig().contact_damping_time, 0.0):
        sk, share = run(5e-6, 1e-7, rig=Rig(contact_damping_time=tau))
        print(f"+5 um, form 0.1 um, contact damping time {tau:g} s: kurtosis {sk:.2f}")
    chosen_band_kurtosis()


def chosen_band_kurtosis() -> None:
    from features.envelope import envelope
    from features.separation import select_band, separate_discrete
    from generators import LocalizedDefect, characteristic_frequencies

    cases = {
        "inner form": form_waviness(9, 1e-7, 0.0, 0.0),
        "ball form": form_waviness(9, 0.0, 0.0, 1e-7),
        "outer pit": LocalizedDefect(surface="outer", length=0.3e-3, depth=0.1e-3),
        "inner pit": LocalizedDefect(surface="inner", length=0.3e-3, depth=0.1e-3),
    }
    settings = SimulationSettings(fs=FS, duration=1.0, settle_time=0.1)
    for clearance in (-5e-6, 5e-6):
        g = bearing("6205", radial_internal_clearance=clearance)
        f = characteristic_frequencies(g, 1797 / 60)
        rates = {"bpfo": f.bpfo, "bpfi": f.bpfi, "two_bsf": f.two_bsf}
        for load in (100.0, 400.0):
            op = OperatingCondition.from_rpm(1797, load, random_slip=0.01, ball_jitter=0.005)
            row = []
            for name, defects in cases.items():
                x = simulate(g, op, defects, settings=settings, random_state=2)
                rest = separate_discrete(
                    x["housing_acceleration_y"], FS, fundamentals=(1797 / 60, f.bpfo)
                )
                e = envelope(rest, FS, band=select_band(rest, FS, rates).band, method="squared")
                row.append(f"{name} {np.mean(e * e) / np.mean(e) ** 2 - 2.0:.1f}")
            print(f"chosen band, {clearance * 1e6:+.0f} um, {load:.0f} N: " + ", ".join(row))


if __name__ == "__main__":
    main()
