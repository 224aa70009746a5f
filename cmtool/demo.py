"""``cmtool demo``: the main job on the embedded default.

1. Simulates the default 6205 scene (1800 rpm, 500 N, docs/model.md 6.3 rig) healthy and with
   outer-race waviness N_w = 9 and plots the housing-velocity spectra.
2. Generates the small dataset (``datasets/small.toml``), trains the classifiers with
   grouped cross-validation and plots the confusion matrix of the held-out operating points.
3. Diagnoses a fresh simulated recording (inner-race waviness at an operating point the
   dataset does not contain), a simulated CWRU-size pit and a 3 mm spall (sized) and, when
   ``../shared/data`` is present, a measured CWRU recording, with reports.
4. Prints a short summary with the paths of the plots.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

import features
from generators import (
    LocalizedDefect,
    OperatingCondition,
    Scene,
    SimulationSettings,
    Waviness,
    bearing,
    simulate,
)

from .io import write_signal
from .plots import plot_confusion, plot_spectrum, waviness_markers
from .vibration_zones import zone_text

__all__ = ["run_demo", "SMALL_RECIPE"]

REPO = Path(__file__).resolve().parents[1]
SMALL_RECIPE = REPO / "datasets" / "small.toml"
SHARED_RECORDING = REPO.parent / "shared" / "data" / "cwru" / "12k_Drive_End_IR007_0_105.mat"


def _simulated_fault(
    defect: LocalizedDefect,
    load: float,
    settings: SimulationSettings,
    *,
    noise: float,
    seed: int,
    out: Path,
    title: str,
):
    """A 6205 at 1797 rpm with 1 % slip and ``defect``, diagnosed, its report written.

    The housing's acceleration [m/s^2] in white noise ``noise`` x its RMS; returns the
    diagnosis and the report's path.
    """
    from .diagnose import diagnose_signal, write_report

    geometry = bearing("6205")
    run = simulate(
        geometry,
        OperatingCondition.from_rpm(1797, load, random_slip=0.01, ball_jitter=0.005),
        [defect],
        scene=Scene(level="shaft+housing", ehl=True),
        settings=settings,
        random_state=seed,
    )
    x = run["housing_acceleration_y"]
    x = x + np.random.default_rng(seed).normal(0, noise * x.std(), x.size)
    diagnosis = diagnose_signal(x, run.fs, 1797.0, geometry, unit="m/s^2")
    return diagnosis, write_report(diagnosis, out, x=x, fs=run.fs, title=title)


def _size(diagnosis) -> str:
    """The fault size's headline: "spall length about ... mm (...)" or "not estimated"."""
    return (diagnosis.severity or {"reason": "-"})["reason"].split(":")[0]


def run_demo(out: Path, *, recipe: Path = SMALL_RECIPE, workers: int = 1) -> int:
    """Run the demo into ``out``; returns 0.

    Parameters
    ----------
    out : pathlib.Path
        The folder for its plots, dataset, model and reports (created).
    recipe : pathlib.Path
        The dataset recipe it generates and trains on (default the small recipe).
    workers : int
        Worker threads for the generation.

    Returns
    -------
    int
        The exit code, 0.
    """
    from .classifier import save_model, train
    from .datasets import generate_dataset, read_dataset
    from .diagnose import diagnose_signal, write_report
    from .io import read_recording

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    geometry = bearing("6205")
    operating = OperatingCondition.from_rpm(1800, 500.0)
    settings = SimulationSettings(fs=25600.0, duration=1.0, settle_time=0.2)
    scene = Scene(level="shaft+housing", ehl=True)
    print(
        f"cmtool demo: {geometry.name}, {operating.rpm:g} rpm, {operating.radial_load:g} N, "
        f"scene {scene.label}, {settings.duration:g} s at {settings.fs:g} Hz"
    )
    summary = []
    for name, defects in {
        "healthy": [],
        "outer_waviness_nw9": [Waviness(surface="outer", order=9, amplitude=1e-6)],
    }.items():
        result = simulate(
            geometry, operating, defects, scene=scene, settings=settings, random_state=0
        )
        write_signal(result, out / f"{name}.parquet")
        freqs, amp = features.amplitude_spectrum(result["housing_velocity_y"], result.fs)
        level = features.band_amplitude(freqs, amp, result.frequencies.bpfo, half_width=1.5)
        png = plot_spectrum(
            freqs,
            amp * 1e3,
            out / f"{name}_spectrum.png",
            title=f"{name}: housing velocity (y) spectrum, peak [mm/s]",
            ylabel="velocity [mm/s]",
            markers=waviness_markers(result, defects),
        )
        print(
            f"  simulated {name:<20s} BPFO {result.frequencies.bpfo:.2f} Hz: {level * 1e3:.4f} mm/s"
        )
        summary.append(("spectrum", png))

    dataset = out / "dataset"
    if not (dataset / "_dataset.json").is_file():
        generate_dataset(recipe, dataset, workers=workers, resume=dataset.exists())
    frame = read_dataset(dataset)
    print(
        f"  dataset {dataset}: {len(frame)} signals, labels "
        f"{', '.join(sorted(frame['label'].unique()))}"
    )
    bundle = train(frame, recipe=Path(recipe).read_text())
    model_path = save_model(bundle, out / "model.skops")
    best = bundle["best"]
    print(
        f"  trained {best}: grouped-CV balanced accuracy on held-out operating points "
        f"{bundle['scores'][best]:.3f}"
    )
    labels = sorted(set(bundle["cv_labels"]))
    from sklearn.metrics import confusion_matrix

    cm = confusion_matrix(bundle["cv_labels"], bundle["cv_predictions"], labels=labels)
    summary.append(
        (
            "confusion matrix",
            plot_confusion(
                cm, labels, out / "confusion.png", title=f"{best}, held-out operating points"
            ),
        )
    )

    fresh = simulate(
        geometry,
        OperatingCondition.from_rpm(2100, 550.0),
        [Waviness(surface="inner", order=9, amplitude=1e-6)],
        scene=scene,
        settings=SimulationSettings(fs=6400.0, duration=1.0, settle_time=0.1),  # as the recipe
        random_state=1,
    )
    x = fresh["housing_acceleration_y"]
    x = x + np.random.default_rng(1).normal(0, 10 ** (-10 / 20) * x.std(), x.size)
    diagnosis = diagnose_signal(x, fresh.fs, 2100.0, geometry, model=bundle, unit="m/s^2")
    report = write_report(
        diagnosis,
        out / "diagnosis_simulated",
        x=x,
        fs=fresh.fs,
        title="simulated inner-race waviness N_w = 9, 2100 rpm, 550 N",
    )
    print(
        f"  simulated inner-race waviness: rule-based verdict "
        f"{diagnosis.rule_verdict['label']}, model verdict {diagnosis.model_verdict['label']}, "
        f"together {diagnosis.verdict} ({diagnosis.basis})"
    )
    summary.append(("report", report))

    # a local defect: a 0.18 mm (0.007 inch) inner-race pit, the CWRU seeded-fault size, with
    # the random slip of a real bearing (1 % cage speed, 0.005 rad of pocket play:
    # docs/realism.md), without which its impacts would be as periodic as a machine's lines
    diagnosis, report = _simulated_fault(
        LocalizedDefect(surface="inner", length=0.1778e-3, depth=0.28e-3),
        300.0,
        SimulationSettings(fs=12000.0, duration=1.0, settle_time=0.1),
        noise=10 ** (-10 / 20),
        seed=2,
        out=out / "diagnosis_local_defect",
        title="simulated inner-race pit 0.18 mm, 1797 rpm, 300 N",
    )
    print(
        f"  simulated inner-race pit 0.18 mm: rule-based verdict {diagnosis.verdict} "
        f"(confidence {diagnosis.confidence:.2f}); fault size {_size(diagnosis)}"
    )
    summary.append(("report", report))

    # a spall: 3 mm x 50 um on the inner race, 48 kHz, noise at 0.3 of the RMS; its entry and
    # exit events are timed for its length (docs/diagnosis.md, Severity)
    diagnosis, report = _simulated_fault(
        LocalizedDefect(surface="inner", length=3e-3, depth=50e-6),
        400.0,
        SimulationSettings(fs=48000.0, duration=1.0, channels=("housing_acceleration_y",)),
        noise=0.3,
        seed=1,
        out=out / "diagnosis_spall",
        title="simulated inner-race spall 3 mm x 50 um, 1797 rpm, 400 N",
    )
    print(
        f"  simulated inner-race spall 3 mm: rule-based verdict {diagnosis.verdict}; fault size "
        f"{_size(diagnosis)}"
    )
    summary.append(("report", report))
    if SHARED_RECORDING.is_file():
        x, meta = read_recording(SHARED_RECORDING)
        # the rig's 2 hp (1.5 kW) motor is a small machine: ISO 10816-1 class I (../shared/rigs.md)
        diagnosis = diagnose_signal(
            x, 12000.0, meta["rpm"], geometry, unit=meta.get("unit"), machine_class="class-I"
        )
        report = write_report(
            diagnosis, out / "diagnosis_cwru_ir007", x=x, fs=12000.0, title=SHARED_RECORDING.name
        )
        print(
            f"  measured {SHARED_RECORDING.name} (CWRU inner race 0.007 in): "
            f"verdict {diagnosis.verdict} (confidence {diagnosis.confidence:.2f}); fault size "
            f"{_size(diagnosis)}"
        )
        zone = diagnosis.overall_velocity.get("zone")
        if zone is not None:
            print(f"    its vibration zone: {zone_text(zone)}")
        summary.append(("report", report))
    else:
        print("  ../shared/data is absent: no measured recording diagnosed")
    print(f"done in {time.perf_counter() - t_start:.1f} s; look at:")
    for what, path in summary:
        print(f"  {what:<17s} {path}")
    print(f"  model             {model_path}")
    return 0
