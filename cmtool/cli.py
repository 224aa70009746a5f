"""The ``cmtool`` command line.

Subcommands: ``simulate`` (one signal from the dynamic model), ``frequencies`` (characteristic
frequencies of a catalog bearing), ``demo`` (the main job on the embedded default).
Units at the edge: ``--rpm`` in rev/min, everything else SI (m, N, s, Hz, Pa s).
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from generators import (
    BEARINGS,
    CHANNELS,
    LUBRICANTS,
    LocalizedDefect,
    OperatingCondition,
    ParameterError,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
)
from generators.params import check_shaft_speed_rpm

from . import __version__

logger = logging.getLogger("cmtool")

__all__ = ["main", "parse_waviness", "parse_defect", "build_parser"]


class CliError(Exception):
    """A command-line input error (printed without a traceback, exit code 2)."""


def _optional_float(value: str) -> float | None:
    return None if value == "random" else float(value)


def _parse_spec(
    spec: str, option: str, usage: str, keys: dict[str, tuple[str, object]], required: tuple
) -> tuple[str, dict[str, object]]:
    """Split ``surface:key=value:...``; ``keys`` maps a key to (field name, converter)."""
    parts = spec.split(":")
    surface = parts[0].strip()
    fields: dict[str, object] = {}
    for item in parts[1:]:
        if "=" not in item:
            raise CliError(f"{option} {spec!r}: {item!r} is not key=value (expected {usage})")
        key, value = (s.strip() for s in item.split("=", 1))
        if key not in keys:
            raise CliError(f"{option} {spec!r}: unknown key {key!r} (allowed: {', '.join(keys)})")
        name, convert = keys[key]
        try:
            fields[name] = convert(value)  # type: ignore[operator]
        except ValueError as err:
            kind = "an integer" if convert is int else "a number"
            raise CliError(f"{option} {spec!r}: {key}={value!r} is not {kind}") from err
    for key in required:
        if keys[key][0] not in fields:
            raise CliError(f"{option} {spec!r}: {key}= is missing")
    return surface, fields


def parse_waviness(spec: str) -> Waviness:
    """Parse ``surface:order=N:amplitude=A[:phase=P|random][:ball=J]`` into a Waviness.

    Examples
    --------
    >>> parse_waviness("outer:order=9:amplitude=1e-6").order
    9
    """
    surface, fields = _parse_spec(
        spec,
        "--waviness",
        "surface:order=N:amplitude=A[:phase=P][:ball=J]",
        {
            "order": ("order", int),
            "amplitude": ("amplitude", float),
            "phase": ("phase", _optional_float),
            "ball": ("ball", int),
        },
        ("order", "amplitude"),
    )
    if surface == "ball" and "phase" not in fields:
        fields["phase"] = None  # each ball its own phase
    return Waviness(surface=surface, **fields)  # type: ignore[arg-type]


def parse_defect(spec: str) -> LocalizedDefect:
    """Parse ``surface:length=L:depth=H[:position=P|random][:ball=J]`` into a LocalizedDefect.

    Lengths in m, position in rad (outer race default -pi/2: 6 o'clock, the load-zone centre;
    inner race and ball default random); ball pits also take ``latitude=A|random`` [rad] and
    ``drift=W`` (spin-axis drift [rad/s]).

    Examples
    --------
    >>> parse_defect("outer:length=0.18e-3:depth=20e-6").depth
    2e-05
    """
    surface, fields = _parse_spec(
        spec,
        "--defect",
        "surface:length=L:depth=H[:position=P|random][:ball=J][:latitude=A|random][:drift=W]",
        {
            "length": ("length", float),
            "depth": ("depth", float),
            "position": ("position", _optional_float),
            "ball": ("ball", int),
            "latitude": ("latitude", _optional_float),
            "drift": ("axis_drift", float),
        },
        ("length", "depth"),
    )
    if surface in ("inner", "ball") and "position" not in fields:
        fields["position"] = None
    return LocalizedDefect(surface=surface, **fields)  # type: ignore[arg-type]


def _default(cls: type, name: str):
    """The default of a parameter object's field (the one place it is written)."""
    import dataclasses

    return next(f.default for f in dataclasses.fields(cls) if f.name == name)


def _add_model_arguments(p: argparse.ArgumentParser) -> None:
    from generators.params import INTEGRATORS, SCENE_LEVELS

    g = p.add_argument_group("bearing and operating point")
    g.add_argument(
        "--bearing", default="6205", choices=sorted(BEARINGS), help="catalog bearing (default 6205)"
    )
    g.add_argument(
        "--clearance",
        type=float,
        default=None,
        help="radial internal (diametral) clearance P_d [m]; default the catalog's",
    )
    g.add_argument("--rpm", type=float, default=1800.0, help="shaft speed [rev/min]")
    g.add_argument(
        "--load",
        type=float,
        default=_default(OperatingCondition, "radial_load"),
        help="radial load [N]",
    )
    g.add_argument(
        "--load-angle",
        type=float,
        default=_default(OperatingCondition, "load_angle"),
        help="load direction from +x [rad] (default -pi/2, down)",
    )
    g.add_argument(
        "--cage-slip",
        type=float,
        default=_default(OperatingCondition, "cage_slip"),
        help="cage slip fraction [-]",
    )
    g.add_argument(
        "--random-slip",
        type=float,
        default=_default(OperatingCondition, "random_slip"),
        help="random fluctuation of the cage speed, standard deviation over its mean [-] "
        "(real bearings 0.01-0.02; makes local-defect impacts cyclostationary)",
    )
    g.add_argument(
        "--ball-jitter",
        type=float,
        default=_default(OperatingCondition, "ball_jitter"),
        help="each ball's random offset in its cage pocket, standard deviation [rad]",
    )
    g.add_argument(
        "--waviness",
        action="append",
        default=[],
        metavar="SPEC",
        help="surface:order=N:amplitude=A[:phase=P|random][:ball=J], repeatable; "
        "surface outer|inner|ball, amplitude [m]",
    )
    g.add_argument(
        "--defect",
        action="append",
        default=[],
        metavar="SPEC",
        help="local defect (pit, spall) surface:length=L:depth=H[:position=P|random][:ball=J]"
        "[:latitude=A|random][:drift=W], repeatable; length and depth [m], position [rad] "
        "(outer default -pi/2, the load zone); ball pits: latitude from the rolling circle "
        "[rad], spin-axis drift [rad/s]",
    )
    s = p.add_argument_group("model")
    s.add_argument("--scene", default=_default(Scene, "level"), choices=SCENE_LEVELS)
    s.add_argument(
        "--ehl",
        dest="ehl",
        action="store_true",
        default=True,
        help="include the EHL film (default)",
    )
    s.add_argument("--no-ehl", dest="ehl", action="store_false", help="dry contacts")
    s.add_argument("--auto-error-bound", type=float, default=_default(Scene, "auto_error_bound"))
    r = p.add_argument_group("rig (docs/model.md 6.3 defaults)")
    d = Rig()
    r.add_argument("--shaft-mass", type=float, default=d.shaft_mass, help="[kg]")
    r.add_argument("--housing-mass", type=float, default=d.housing_mass, help="[kg]")
    r.add_argument("--pedestal-stiffness", type=float, default=d.pedestal_stiffness, help="[N/m]")
    r.add_argument("--pedestal-damping", type=float, default=d.pedestal_damping, help="[N s/m]")
    r.add_argument("--shaft-damping", type=float, default=d.shaft_damping, help="[N s/m]")
    r.add_argument(
        "--contact-damping-time",
        type=float,
        default=d.contact_damping_time,
        help="dry contact damping c = tau dQ/d delta [s]",
    )
    r.add_argument("--film-damping-factor", type=float, default=d.film_damping_factor)
    r.add_argument(
        "--lubricant",
        default=next(k for k, v in LUBRICANTS.items() if v == d.lubricant),
        choices=sorted(LUBRICANTS),
    )
    r.add_argument(
        "--loading-stiffness",
        type=float,
        default=0.0,
        help="loading spring [N/m]; 0 = constant force",
    )
    r.add_argument("--unbalance", type=float, default=0.0, help="m_u e [kg m]")
    r.add_argument("--no-gravity", dest="gravity", action="store_false", default=True)
    n = p.add_argument_group("integration and sampling")
    sim = SimulationSettings()
    n.add_argument("--fs", type=float, default=sim.fs, help="output sample rate [Hz]")
    n.add_argument("--duration", type=float, default=sim.duration, help="recorded duration [s]")
    n.add_argument(
        "--settle", type=float, default=sim.settle_time, help="settling time discarded [s]"
    )
    n.add_argument("--integrator", default=sim.integrator, choices=INTEGRATORS)
    n.add_argument("--step", type=float, default=None, help="RK4 step [s]; default per scene")
    n.add_argument("--rtol", type=float, default=sim.rtol, help="dopri5 relative tolerance")
    n.add_argument(
        "--atol", type=float, default=sim.atol_displacement, help="dopri5 displacement atol [m]"
    )
    n.add_argument(
        "--oversample",
        type=int,
        default=None,
        help="integration record rate / output rate (anti-alias margin)",
    )
    n.add_argument(
        "--cage-angle", type=float, default=sim.cage_angle, help="initial cage angle [rad]"
    )
    n.add_argument("--contact-loads", action="store_true", help="also record ball loads")
    n.add_argument(
        "--channels",
        default=None,
        help="comma-separated output channels (default all), e.g. housing_velocity_y",
    )
    n.add_argument("--seed", type=int, default=None, help="seed for random waviness phases")


def _model_inputs(args: argparse.Namespace):
    overrides = {}
    if args.clearance is not None:
        overrides["radial_internal_clearance"] = args.clearance
    geometry = bearing(args.bearing, **overrides)
    operating = OperatingCondition.from_rpm(
        check_shaft_speed_rpm("--rpm", args.rpm, standing=True),
        args.load,
        load_angle=args.load_angle,
        cage_slip=args.cage_slip,
        random_slip=args.random_slip,
        ball_jitter=args.ball_jitter,
    )
    defects = [parse_waviness(s) for s in args.waviness]
    defects += [parse_defect(s) for s in args.defect]
    scene = Scene(level=args.scene, ehl=args.ehl, auto_error_bound=args.auto_error_bound)
    rig = Rig(
        shaft_mass=args.shaft_mass,
        housing_mass=args.housing_mass,
        pedestal_stiffness=args.pedestal_stiffness,
        pedestal_damping=args.pedestal_damping,
        shaft_damping=args.shaft_damping,
        contact_damping_time=args.contact_damping_time,
        film_damping_factor=args.film_damping_factor,
        lubricant=LUBRICANTS[args.lubricant],
        loading_stiffness=args.loading_stiffness,
        unbalance=args.unbalance,
        gravity=args.gravity,
    )
    settings = SimulationSettings(
        fs=args.fs,
        duration=args.duration,
        settle_time=args.settle,
        integrator=args.integrator,
        step=args.step,
        rtol=args.rtol,
        atol_displacement=args.atol,
        oversample=args.oversample,
        cage_angle=args.cage_angle,
        record_contact_loads=args.contact_loads,
        channels=_simulated_channels(args),
    )
    return geometry, operating, defects, scene, rig, settings


def _requested_channels(args: argparse.Namespace) -> tuple[str, ...] | None:
    """``--channels`` as a tuple of channel names (None: all), checked."""
    if getattr(args, "channels", None) is None:
        return None
    names = tuple(c.strip() for c in args.channels.split(",") if c.strip())
    unknown = [c for c in names if c not in CHANNELS]
    if not names or unknown:
        raise CliError(
            f"--channels {args.channels!r}: {', '.join(unknown) or 'no channel'} is not one of "
            f"{', '.join(CHANNELS)}"
        )
    return names


def _simulated_channels(args: argparse.Namespace) -> tuple[str, ...] | None:
    """The channels to simulate: those asked for, plus those the plots need."""
    names = _requested_channels(args)
    if names is None:
        return None
    need = ["housing_velocity_y"] if getattr(args, "plot", None) else []
    need += ["housing_acceleration_y"] if getattr(args, "envelope_plot", None) else []
    return tuple(dict.fromkeys([*names, *need]))


#: Formats matplotlib writes (checked before a run, not after it).
PLOT_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".webp")


def _check_outputs(args: argparse.Namespace) -> None:
    """Refuse output names the command could not write, before anything runs."""
    if getattr(args, "out", None) and Path(args.out).suffix.lower() not in (".parquet", ".csv"):
        raise CliError(f"--out {args.out!r}: the file must end in .parquet or .csv")
    for flag in ("plot", "envelope_plot"):
        value = getattr(args, flag, None)
        if value and Path(value).suffix.lower() not in PLOT_SUFFIXES:
            raise CliError(
                f"--{flag.replace('_', '-')} {value!r}: the file must end in one of "
                f"{', '.join(PLOT_SUFFIXES)}"
            )


#: Runs with more output samples than this stream to disk in blocks (bounded memory): about
#: 41 s at 51.2 kHz; an in-memory run of this length holds about 0.4 GB.
STREAM_ABOVE_SAMPLES = 1 << 21


def _check_run_size(args: argparse.Namespace, settings, n_samples: int) -> bool:
    """Whether the run streams; refuses what a long run cannot do, and a disk too small."""
    import shutil

    from .io import estimated_file_bytes

    streams = n_samples > STREAM_ABOVE_SAMPLES
    if streams and settings.integrator != "rk4":
        raise CliError(
            f"--duration {args.duration:g} at --fs {args.fs:g}: {n_samples:,} samples; "
            f"--integrator {settings.integrator} runs in memory, at most "
            f"{STREAM_ABOVE_SAMPLES:,} samples (use --integrator rk4, which streams to disk)"
        )
    if streams and (args.plot or args.envelope_plot):
        flag = "--plot" if args.plot else "--envelope-plot"
        raise CliError(
            f"{flag}: a run of {n_samples:,} samples streams to disk (more than "
            f"{STREAM_ABOVE_SAMPLES:,}) and is never whole in memory; plot a shorter run, or "
            "the written file with cmtool diagnose --report"
        )
    if args.out:
        out = Path(args.out)
        channels = _requested_channels(args) or CHANNELS
        size = estimated_file_bytes(out, n_samples, len(channels))
        folder = out.parent if str(out.parent) else Path(".")
        while not folder.exists() and folder != folder.parent:
            folder = folder.parent
        free = shutil.disk_usage(folder).free
        if size > 0.95 * free:
            raise CliError(
                f"--out {args.out!r}: the run writes about {size / 1e9:.2f} GB "
                f"({n_samples:,} samples x {len(channels) + 1} columns) and {folder} has "
                f"{free / 1e9:.2f} GB free; choose fewer --channels, a shorter --duration or "
                "another disk"
            )
        if size > 100e6:
            print(f"writing about {size / 1e9:.2f} GB to {out}", file=sys.stderr)
    return streams


def cmd_simulate(args: argparse.Namespace) -> int:
    """Run one simulation, write the signal and optionally the spectrum plot."""
    import features
    from generators import simulate
    from generators.prepared import EHL_MIN_SHAFT_FREQUENCY

    from .io import write_signal
    from .plots import plot_spectrum, waviness_markers

    _check_outputs(args)
    geometry, operating, defects, scene, rig, settings = _model_inputs(args)
    n_samples = int(round(settings.duration * settings.fs))
    streams = _check_run_size(args, settings, n_samples)
    film = scene.ehl and operating.shaft_frequency >= EHL_MIN_SHAFT_FREQUENCY
    if streams:
        return _simulate_streamed(args, geometry, operating, defects, scene, rig, settings, film)
    result = simulate(
        geometry,
        operating,
        defects,
        scene=scene,
        rig=rig,
        settings=settings,
        random_state=args.seed,
    )
    _print_run(result, settings, geometry, operating, film)
    if args.out:
        path = write_signal(result, args.out, channels=_requested_channels(args))
        print(f"wrote {path}")
    f = result.frequencies
    if args.plot:
        freqs, amp = features.amplitude_spectrum(result["housing_velocity_y"], result.fs)
        markers = waviness_markers(result, defects)
        title = (
            f"{geometry.name}, {operating.rpm:g} rpm, {operating.radial_load:g} N: "
            "housing velocity (y), peak amplitude"
        )
        path = plot_spectrum(
            freqs, amp * 1e3, args.plot, title=title, ylabel="velocity [mm/s]", markers=markers
        )
        print(f"wrote {path}")
    if args.envelope_plot:
        x = result["housing_acceleration_y"]
        freqs, amp, band = features.envelope_spectrum(
            x,
            result.fs,
            return_band=True,
            fault_frequencies={
                "bpfo": f.bpfo,
                "bpfi": f.bpfi,
                "two_bsf": f.two_bsf,
                "shaft": f.shaft,
            },
        )
        markers = waviness_markers(result, defects)
        title = (
            f"{geometry.name}, {operating.rpm:g} rpm: envelope of housing acceleration (y), "
            f"band {band[0]:.0f}-{band[1]:.0f} Hz"
        )
        path = plot_spectrum(
            freqs,
            amp,
            args.envelope_plot,
            title=title,
            ylabel="envelope [m/s^2]",
            markers=markers,
            fmax=min(result.fs / 2, 5 * f.bpfi),
        )
        print(f"wrote {path}")
    return 0


def _print_run(run, settings, geometry, operating, film: bool) -> None:
    """The header of ``simulate``: what ran, and the bearing's frequencies."""
    level = run.parameters["scene"]["resolved_level"]
    contacts = "ehl" if film else "dry"
    if not film and run.parameters["scene"]["ehl"]:
        contacts = "dry (no film below 1 rpm)"
    print(
        f"simulated {settings.duration:g} s of {geometry.name} at {operating.rpm:g} rpm, "
        f"{operating.radial_load:g} N, scene {level}/{contacts}"
    )
    f = run.frequencies
    print(
        f"FTF {f.ftf:.3f} Hz  BPFO {f.bpfo:.3f} Hz  BPFI {f.bpfi:.3f} Hz  "
        f"BSF {f.bsf:.3f} Hz  2xBSF {f.two_bsf:.3f} Hz"
    )


def _simulate_streamed(args, geometry, operating, defects, scene, rig, settings, film) -> int:
    """A long run: integrated and written block by block, with a progress bar."""
    from generators.stream import simulate_stream

    from .io import write_signal_stream

    stream = simulate_stream(
        geometry,
        operating,
        defects,
        scene=scene,
        rig=rig,
        settings=settings,
        random_state=args.seed,
    )
    with _progress_bar(stream.n_samples, "simulate", "sample", unit_scale=True) as bar:
        if args.out:
            path = write_signal_stream(
                stream, args.out, channels=_requested_channels(args), progress=bar.update
            )
        else:
            path = None
            for block in stream:
                bar.update(len(block.time))
    _print_run(stream, settings, geometry, operating, film)
    if path is not None:
        print(f"wrote {path} (streamed in blocks of {stream.block_samples:,} samples)")
    return 0


def cmd_frequencies(args: argparse.Namespace) -> int:
    """Print the characteristic frequencies of a catalog bearing."""
    geometry = bearing(args.bearing)
    rpm = check_shaft_speed_rpm("--rpm", args.rpm)
    f = characteristic_frequencies(geometry, rpm / 60.0)
    data = f.as_dict()
    if args.json:
        print(
            json.dumps(
                {
                    "bearing": geometry.name,
                    "rpm": args.rpm,
                    "frequencies_hz": data,
                    "orders": f.orders(),
                },
                indent=2,
            )
        )
    else:
        for key, value in data.items():
            print(f"{key:>24s} {value:10.4f} Hz  {value / f.shaft:8.5f} x shaft")
    return 0


def _progress_bar(
    total: int, desc: str, unit: str = "run", *, initial: int = 0, unit_scale: bool = False
):
    """The progress bar of every command: tqdm (count, rate, ETA) on stderr, quiet off a tty."""
    from tqdm import tqdm

    return tqdm(
        total=total,
        desc=desc,
        unit=unit,
        unit_scale=unit_scale,
        initial=initial,
        disable=None,
        file=sys.stderr,
    )


def cmd_fidelity(args: argparse.Namespace) -> int:
    """Run the speed/accuracy study and print, write and plot the table."""
    from .fidelity import fidelity_study, plot_fidelity, recommend

    geometry, operating, defects, _, rig, settings = _model_inputs(args)
    steps = tuple(float(v) for v in args.steps.split(",")) if args.steps else None
    rtols = tuple(float(v) for v in args.rtols.split(",")) if args.rtols else None
    levels = tuple(args.levels.split(","))
    kwargs = {}
    if steps is not None:
        kwargs["rk4_steps"] = steps
    if rtols is not None:
        kwargs["dopri5_rtols"] = rtols
    bar = None

    def progress(done: int, total: int, label: str) -> None:
        nonlocal bar
        if bar is None:
            bar = _progress_bar(total, "fidelity")
        bar.set_postfix_str(label)
        bar.update(1)

    table = fidelity_study(
        geometry,
        operating,
        defects,
        rig=rig,
        settings=settings,
        levels=levels,
        f_max=args.f_max,
        progress=progress,
        **kwargs,
    )
    if bar is not None:
        bar.close()
    with __import__("pandas").option_context("display.width", 160, "display.max_rows", 200):
        print(table.to_string(index=False, float_format=lambda v: f"{v:.4g}"))
    print(
        f"band line {table.attrs['band_frequency_hz']:.2f} Hz, reference "
        f"{table.attrs['reference']}, spectrum error up to {args.f_max:g} Hz"
    )
    best = recommend(table, args.error_bound)
    if best is None:
        print(f"no stable setting meets the error bound {args.error_bound:g}")
    else:
        print(
            f"recommended under a {args.error_bound:g} band-amplitude error bound: "
            f"{best.scene}/{'ehl' if best.ehl else 'dry'} {best.integrator} "
            f"{best.step_or_tolerance:g} ({best.wall_s_per_simulated_s:.4f} s per simulated s,"
            f" error {best.band_amplitude_error:.2e})"
        )
    if args.out:
        from .io import atomic_write

        atomic_write(Path(args.out), lambda tmp: table.to_csv(tmp, index=False))
        print(f"wrote {args.out}")
    if args.plot:
        print(f"wrote {plot_fidelity(table, args.plot, error_bound=args.error_bound)}")
    return 0


def cmd_generate(args: argparse.Namespace) -> int:
    """Generate a dataset from a recipe."""
    from .datasets import generate_dataset

    bar = None

    def progress(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = _progress_bar(total, "generate", "signal", initial=done)
        else:
            bar.update(done - bar.n)

    try:
        summary = generate_dataset(
            args.recipe,
            args.out,
            workers=args.workers,
            resume=args.resume,
            scheduler=args.scheduler,
            progress=progress,
        )
    except KeyboardInterrupt:
        # the chunks being written were finished; every visible part is whole
        if bar is not None:
            bar.close()
        print(
            f"cmtool generate: interrupted; the parts written in {args.out} are complete. "
            "Run the same command with --resume to finish.",
            file=sys.stderr,
        )
        return 130
    if bar is not None:
        bar.close()
    print(
        f"dataset {summary['name']} in {args.out}: {summary['written']} written, "
        f"{summary['failed']} failed, {summary['skipped_existing']} already present "
        f"(of {summary['signals']})"
    )
    return 0


def cmd_dataset_info(args: argparse.Namespace) -> int:
    """Print counts per label and parameter ranges."""
    from .datasets import dataset_info

    print(dataset_info(args.path))
    return 0


def cmd_train(args: argparse.Namespace) -> int:
    """Train classifiers with grouped cross-validation and save the best."""
    from .classifier import save_model, train
    from .datasets import read_dataset

    frame = read_dataset(args.dataset, allow_incomplete=args.allow_incomplete)
    recipe = Path(args.dataset, "recipe.toml")
    bundle = train(
        frame,
        recipe=recipe.read_text() if recipe.is_file() else "",
        random_state=args.seed,
        feature_set=args.feature_set,
        min_fault_snr_db=None if args.min_fault_snr is None else float(args.min_fault_snr),
    )
    print(
        f"trained on {len(frame) - bundle['left_out']} signals ({bundle['left_out']} faulty "
        f"ones below the fault SNR floor left out), {frame['operating_point_id'].nunique()} "
        f"operating points, features {bundle['feature_set']}; grouped "
        f"{bundle['n_splits']}-fold accuracy (no operating point in both train and test):"
    )
    for name, score in sorted(bundle["scores"].items(), key=lambda kv: -kv[1]):
        print(f"  {name:<22s} {score:.3f}{'  <- kept' if name == bundle['best'] else ''}")
    for key, value in bundle["extrapolation"].items():
        print(f"  extrapolation {key:<28s} {value:.3f}")
    print(f"wrote {save_model(bundle, args.out)}")
    return 0


def cmd_evaluate(args: argparse.Namespace) -> int:
    """Accuracy, per-class precision/recall and confusion matrix of a model on a dataset."""
    from .classifier import evaluate, load_model
    from .datasets import read_dataset
    from .plots import plot_confusion

    bundle = load_model(args.model)
    frame = read_dataset(args.dataset, allow_incomplete=args.allow_incomplete)
    in_sample = _check_training_overlap(bundle, frame, args)
    result = evaluate(bundle, frame)
    result["in_sample_fraction"] = in_sample
    tag = " (IN-SAMPLE: signals the model was trained on; not a measure of accuracy)"
    print(
        f"accuracy {result['accuracy']:.3f} on {len(result['predictions'])} signals"
        + (tag if in_sample else "")
    )
    print(f"{'label':<12s} {'precision':>9s} {'recall':>7s} {'f1':>6s}")
    for label, m in result["per_class"].items():
        print(f"{label:<12s} {m['precision']:9.3f} {m['recall']:7.3f} {m['f1-score']:6.3f}")
    labels = result["labels"]
    print("confusion matrix (rows true, columns predicted): " + ", ".join(labels))
    for label, row in zip(labels, result["confusion"], strict=True):
        print(f"  {label:<12s} " + " ".join(f"{v:4d}" for v in row))
    if args.out:
        out = Path(args.out)
        png = plot_confusion(
            result["confusion"],
            labels,
            out / "confusion.png",
            title=f"{Path(args.model).name} on {Path(args.dataset).name}"
            + (" (in-sample)" if in_sample else ""),
        )
        (out / "evaluation.json").write_text(
            json.dumps({k: v for k, v in result.items() if k != "predictions"}, indent=2)
        )
        print(f"wrote {png}")
    return 0


def _check_training_overlap(bundle: dict, frame, args: argparse.Namespace) -> float:
    """Refuse to score a model on its own training signals unless --allow-training-data.

    Returns the fraction of ``frame``'s signals the model was trained on (0 when none).
    """
    from .classifier import training_overlap

    overlap = training_overlap(bundle, frame)
    if overlap > 0 and not args.allow_training_data:
        raise CliError(
            f"{overlap:.0%} of the signals in {args.dataset} were used to train "
            f"{args.model}: scores on them say nothing about new data. Evaluate on a dataset "
            "generated with another seed, or pass --allow-training-data to run anyway "
            "(every output is then labelled in-sample)"
        )
    return overlap


def cmd_diagnose(args: argparse.Namespace) -> int:
    """Diagnose a recording: verdict, evidence, optional report and JSON."""
    from .diagnose import diagnose_signal, write_report
    from .io import read_recording

    if args.report and Path(args.report).exists() and not Path(args.report).is_dir():
        raise CliError(f"--report {args.report!r} is a file; give a folder for report.md")
    x, meta = read_recording(args.recording, variable=args.variable, channel=args.channel)
    warnings = []
    fs = args.fs if args.fs is not None else meta.get("fs_hz")
    if fs is None:
        raise CliError(f"{args.recording}: the file holds no sample rate; give --fs")
    if args.fs is not None and "fs_hz" in meta and abs(meta["fs_hz"] - args.fs) > 1e-6 * args.fs:
        warnings.append(
            f"--fs {args.fs:g} Hz differs from the file's {meta['fs_hz']:g} Hz; using --fs"
        )
    rpm = check_shaft_speed_rpm("--rpm", args.rpm) if args.rpm is not None else meta.get("rpm")
    if rpm is None:
        raise CliError(f"{args.recording}: the file holds no shaft speed; give --rpm")
    name = args.bearing or meta.get("bearing")
    if name is None:
        raise CliError(
            f"{args.recording}: the file does not say which bearing it is; give --bearing "
            f"(one of {', '.join(sorted(BEARINGS))})"
        )
    if args.bearing and meta.get("bearing") and args.bearing != meta["bearing"]:
        warnings.append(f"--bearing {args.bearing} differs from the file's {meta['bearing']}")
    model = None
    if args.model:
        from .classifier import load_model

        model = load_model(args.model)
    baseline = baseline_fs = None
    if args.baseline:
        baseline, base_meta = read_recording(
            args.baseline, variable=args.variable, channel=args.channel
        )
        baseline_fs = base_meta.get("fs_hz", float(fs))
    diagnosis = diagnose_signal(
        x, float(fs), float(rpm), name, model=model, baseline=baseline, baseline_fs=baseline_fs
    )
    diagnosis.warnings = warnings + diagnosis.warnings
    diagnosis.assumptions["channel"] = str(meta.get("variable") or args.channel or "first")
    diagnosis.assumptions["file"] = Path(args.recording).name
    if args.report:
        report = write_report(
            diagnosis, args.report, title=Path(args.recording).name, x=x, fs=float(fs)
        )
        if not args.json:
            print(f"wrote {report}")
    if args.json:
        print(json.dumps(diagnosis.to_dict(), indent=2))
    else:
        print(
            f"{Path(args.recording).name}: {diagnosis.verdict} (confidence "
            f"{diagnosis.confidence:.2f}); envelope band {diagnosis.band_hz[0]:.0f}-"
            f"{diagnosis.band_hz[1]:.0f} Hz, threshold {diagnosis.threshold_db:.1f} dB"
        )
        a = diagnosis.assumptions
        print(
            f"  assumed: bearing {a['bearing']}, {a['rpm']:g} rpm, fs {a['fs_hz']:g} Hz, "
            f"{a['record_s']:g} s ({a['samples']} samples), channel {a['channel']}"
        )
        for c in diagnosis.candidates:
            print(
                f"  {c['fault']:<11s} {c['frequency_hz']:9.3f} Hz  envelope SNR "
                f"{c['envelope_snr_db'][0]:6.1f} / {c['envelope_snr_db'][1]:6.1f} / "
                f"{c['envelope_snr_db'][2]:6.1f} dB (1x/2x/3x)"
            )
        print(f"  basis: {diagnosis.basis}")
        change = (diagnosis.baseline or {}).get("velocity_bands_change_db", {})
        bands = ", ".join(
            f"{k} {v:.3g}" + (f" ({change[k]:+.1f} dB)" if change.get(k) is not None else "")
            for k, v in (diagnosis.velocity_bands or {}).items()
        )
        print(f"  velocity RMS (ISO 15242 bands, signal unit x s): {bands}")
        if diagnosis.waviness:
            w = diagnosis.waviness
            over = w.get("over_baseline_db")
            print(
                f"  waviness hint: {w['surface']} race order ~{w['order']} at {w['line_hz']} Hz"
                + ("" if over is None else f", {over:+.1f} dB over the baseline")
            )
        if diagnosis.model_verdict:
            print(f"  model: {diagnosis.model_verdict}")
        for w in diagnosis.warnings:
            print(f"  warning: {w}")
    return 0


def cmd_realism(args: argparse.Namespace) -> int:
    """Tell simulated from measured signals: ROC AUC and the features that give it away."""
    import numpy as np

    from .datasets import read_dataset
    from .realism import plot_realism, realism, recording_segments

    simulated = read_dataset(args.dataset, allow_incomplete=args.allow_incomplete)
    duration = float(np.median(simulated["duration_s"])) if "duration_s" in simulated else 1.0
    measured = recording_segments(args.recordings, duration)
    result = realism(simulated, measured, feature_set=args.feature_set, n_jobs=args.workers)
    print(
        f"measured vs simulated: ROC AUC {result['auc']:.3f} (0.5: indistinguishable, 1: "
        f"every recording recognised); {result['segments']} segments of {duration:g} s from "
        f"{result['recordings']} recordings against {result['simulated']} simulated signals, "
        f"{result['folds']}-fold cross-validation grouped by recording, "
        f"{result['feature_set']} features"
    )
    print("what gives the simulation away (random-forest importance):")
    for name, value in result["features"][:10]:
        print(f"  {name:<40s} {value:.3f}")
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "realism.json").write_text(
            json.dumps({k: v for k, v in result.items() if k != "scores"}, indent=2)
        )
        print(f"wrote {plot_realism(result, out / 'realism.png')}")
    return 0


def cmd_bench(args: argparse.Namespace) -> int:
    """Run detectors over a labelled dataset; print and write the scores, curves and report."""
    import pandas as pd

    from . import bench

    out = Path(args.out) if args.out else None
    if out is not None and out.exists() and not out.is_dir():
        raise CliError(f"--out {args.out!r} is a file; give a folder for the tables and plots")
    for spec in args.detector:
        bench.load_callable(spec)  # a wrong plug-in is refused before any work
    model = None
    in_sample = 0.0
    if args.model:
        from .classifier import load_model

        model = load_model(args.model)
        if not (Path(args.dataset) / "MANIFEST.csv").is_file():
            from .datasets import read_dataset

            in_sample = _check_training_overlap(
                model,
                read_dataset(
                    args.dataset, columns=["signal"], allow_incomplete=args.allow_incomplete
                ),
                args,
            )
            if in_sample:
                print(
                    f"IN-SAMPLE: {in_sample:.0%} of these signals trained the model; its rates "
                    "below are not a measure of accuracy"
                )
    bar = None

    def progress(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = _progress_bar(total, "bench", "signal")
        bar.update(done - bar.n)

    results = bench.run_bench(
        args.dataset,
        model=model,
        detectors=args.detector,
        bearing=args.bearing,
        progress=progress,
        allow_incomplete=args.allow_incomplete,
        workers=args.workers,
    )
    if bar is not None:
        bar.close()
    if in_sample:
        results["in_sample"] = True
    summary, curves = bench.score_summary(results)
    snr_column = next((c for c in ("fault_snr_db", "snr_db") if c in results), None)
    by_snr = by_snr_fault = None
    if snr_column is not None:
        columns = ["detector", "snr_db", "pd_at_pfa_0.01", "ci_low", "ci_high", "signals", "bin"]
        snr_table = bench.by_factor(results, snr_column)
        if len(snr_table):
            by_snr = snr_table.rename(columns={"value": "snr_db"})[columns]
            by_snr_fault = pd.concat(
                [by_snr.assign(fault="all")]
                + [
                    bench.by_factor(results, snr_column, fault=f)
                    .rename(columns={"value": "snr_db"})[columns]
                    .assign(fault=f)
                    for f in bench.FAULT_CLASSES
                ],
                ignore_index=True,
            )
    factors = {
        c: bench.by_factor(results, c)
        for c in bench.FACTORS
        if c not in ("fault_snr_db", "snr_db") and c in results and results[c].nunique() > 1
    }
    factors = {c: t for c, t in factors.items() if len(t)}  # none without faulty signals
    tag = " [IN-SAMPLE]" if in_sample else ""
    print(f"== ROC area and detection at fixed false-alarm rates{tag}")
    print(summary.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    if by_snr is not None:
        print(f"== detection at false alarm 0.01 against {snr_column}{tag}")
        print(by_snr.drop(columns=["bin"]).to_string(index=False, float_format="{:.3f}".format))
    labels = bench.summarise(results)["overall"]
    print(f"== the detectors' own labels{tag}")
    print(labels.to_string(float_format=lambda v: f"{v:.3f}"))
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        if in_sample:
            for frame in (summary, labels):
                frame["in_sample"] = True
        results.to_csv(out / "results.csv", index=False)
        summary.to_csv(out / "summary.csv", index=False)
        labels.to_csv(out / "labels.csv")
        if by_snr is not None:
            if in_sample:
                by_snr = by_snr.assign(in_sample=True)
            by_snr.drop(columns=["bin"]).to_csv(out / "by_snr.csv", index=False)
            by_snr_fault.drop(columns=["bin"]).to_csv(out / "by_snr_fault.csv", index=False)
        if factors:
            table = pd.concat([t.assign(factor=c) for c, t in factors.items()], ignore_index=True)
            table.to_csv(out / "by_factor.csv", index=False)
        title = f"{Path(args.dataset).name}{tag}"
        written = [bench.plot_roc(curves, out / "roc.png", title=f"ROC: {title}")]
        if by_snr is not None:
            written.append(
                bench.plot_pd_vs_snr(
                    by_snr_fault, out / "pd_vs_snr.png", title=f"detection against SNR: {title}"
                )
            )
        written.append(
            bench.write_report(
                out / "report.md",
                Path(args.dataset).name,
                summary,
                by_snr if by_snr is not None else summary.iloc[0:0],
                factors,
                in_sample=in_sample,
            )
        )
        for path in written:
            print(f"wrote {path}")
    return 0


def cmd_demo(args: argparse.Namespace) -> int:
    """The main job on the embedded default."""
    from .demo import run_demo

    return run_demo(Path(args.out))


def _add_allow_incomplete(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--allow-incomplete",
        action="store_true",
        help="use a dataset whose generation did not finish (no _dataset.json)",
    )


def _positive_int(text: str) -> int:
    """An argparse type: an integer of at least 1 (workers, counts)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{value} is outside the allowed range [1, inf)")
    return value


class _Parser(argparse.ArgumentParser):
    """argparse with one-line usage errors (``cmtool CMD: error: ...``, exit 2)."""

    def error(self, message: str):  # noqa: D102 - argparse's hook
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``cmtool``."""
    parser = _Parser(prog="cmtool", description=(__doc__ or "").strip().split("\n")[0])
    parser.add_argument("--version", action="version", version=f"cmtool {__version__}")
    parser.add_argument("-v", "--verbose", action="count", default=0)
    commands = parser.add_subparsers(dest="command", required=True)

    class _Commands:
        """Sub-parsers that show every option's default in --help."""

        @staticmethod
        def add_parser(name: str, **kwargs) -> argparse.ArgumentParser:
            kwargs.setdefault("formatter_class", argparse.ArgumentDefaultsHelpFormatter)
            return commands.add_parser(name, **kwargs)

    sub = _Commands()

    p = sub.add_parser("simulate", help="simulate one housing vibration signal")
    _add_model_arguments(p)
    p.add_argument("--out", help="output file (.parquet or .csv)")
    p.add_argument("--plot", help="spectrum plot (.png)")
    p.add_argument(
        "--envelope-plot",
        help="envelope spectrum plot of the housing acceleration (.png; band by the kurtogram)",
    )
    p.set_defaults(func=cmd_simulate)

    p = sub.add_parser("frequencies", help="characteristic frequencies of a catalog bearing")
    p.add_argument("--bearing", default="6205", choices=sorted(BEARINGS))
    p.add_argument("--rpm", type=float, required=True, help="shaft speed [rev/min]")
    p.add_argument("--json", action="store_true")
    p.set_defaults(func=cmd_frequencies)

    p = sub.add_parser(
        "fidelity", help="speed against accuracy of every model level and integrator setting"
    )
    _add_model_arguments(p)
    p.add_argument("--levels", default="shaft,shaft+housing,full")
    p.add_argument("--steps", default=None, help="comma-separated RK4 steps [s]")
    p.add_argument("--rtols", default=None, help="comma-separated DOPRI5 tolerances")
    p.add_argument("--f-max", type=float, default=5000.0, help="spectrum error band [Hz]")
    p.add_argument(
        "--error-bound",
        type=float,
        default=0.01,
        help="band amplitude error bound for the recommendation [-]",
    )
    p.add_argument("--out", help="table as CSV")
    p.add_argument("--plot", help="runtime against error plot (.png)")
    p.set_defaults(func=cmd_fidelity)

    p = sub.add_parser("generate", help="generate a labelled synthetic dataset from a recipe")
    p.add_argument("recipe", help="TOML recipe (see datasets/)")
    p.add_argument("--out", required=True, help="dataset folder")
    p.add_argument(
        "--workers",
        type=_positive_int,
        default=os.cpu_count() or 1,
        help="local worker threads (default: all cores)",
    )
    p.add_argument("--resume", action="store_true", help="continue an interrupted run")
    p.add_argument(
        "--scheduler",
        default=None,
        help="Dask distributed scheduler address (e.g. tcp://127.0.0.1:8786)",
    )
    p.set_defaults(func=cmd_generate)

    p = sub.add_parser("dataset", help="inspect a dataset")
    dsub = p.add_subparsers(dest="dataset_command", required=True)
    q = dsub.add_parser("info", help="counts per label and parameter ranges")
    q.add_argument("path")
    q.set_defaults(func=cmd_dataset_info)

    p = sub.add_parser("train", help="train a classifier on a dataset")
    p.add_argument("dataset", help="dataset folder (cmtool generate)")
    p.add_argument("--out", required=True, help="model file (skops archive, e.g. model.skops)")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument(
        "--feature-set",
        default="evidence+scale-free",
        choices=["all", "scale-free", "envelope", "evidence", "evidence+scale-free"],
        help="features (default: evidence+scale-free, the set that carried over best between "
        "simulated rigs: benchmarks/cross_domain.py); all; scale-free (none in the signal's "
        "unit); envelope (envelope line-to-floor ratios); evidence (the rule detector's "
        "evidence)",
    )
    p.add_argument(
        "--min-fault-snr",
        type=float,
        default=-10.0,
        metavar="DB",
        help="leave out faulty signals whose fault SNR is below DB (nothing in them shows the "
        "fault; default -10 dB)",
    )
    _add_allow_incomplete(p)
    p.set_defaults(func=cmd_train)

    p = sub.add_parser("evaluate", help="accuracy and confusion matrix of a model")
    p.add_argument("model")
    p.add_argument("dataset")
    p.add_argument("--out", help="folder for confusion.png and evaluation.json")
    p.add_argument(
        "--allow-training-data",
        action="store_true",
        help="score the model even on signals it was trained on (outputs labelled in-sample)",
    )
    _add_allow_incomplete(p)
    p.set_defaults(func=cmd_evaluate)

    p = sub.add_parser("diagnose", help="diagnose a measured recording")
    p.add_argument("recording", help="CSV, WAV, MATLAB .mat, .npy/.npz or parquet file")
    p.add_argument("--fs", type=float, default=None, help="sample rate [Hz] (if not in file)")
    p.add_argument("--rpm", type=float, default=None, help="shaft speed [rev/min]")
    p.add_argument(
        "--bearing",
        default=None,
        choices=sorted(BEARINGS),
        help="bearing (required unless the file says: cmtool parquet files, the CWRU and "
        "MFPT layouts)",
    )
    p.add_argument("--variable", default=None, help="variable of a .mat/.npz file")
    p.add_argument("--channel", default=None, help="column or channel")
    p.add_argument("--model", default=None, help="trained model (cmtool train)")
    p.add_argument("--report", default=None, help="folder for report.md and plots")
    p.add_argument(
        "--baseline",
        default=None,
        help="a healthy recording of the same machine: ISO 15242 bands and the waviness line "
        "reported against it",
    )
    p.add_argument("--json", action="store_true", help="print the verdict as JSON")
    p.set_defaults(func=cmd_diagnose)

    p = sub.add_parser("bench", help="benchmark detectors on a labelled dataset")
    p.add_argument("dataset", help="cmtool dataset folder, or a folder with MANIFEST.csv")
    p.add_argument("--model", default=None, help="trained model (adds the 'model' detector)")
    p.add_argument(
        "--detector",
        action="append",
        default=[],
        metavar="MODULE:FUNCTION",
        help="user detector f(x, fs, rpm, bearing) -> label, or {'label': ..., 'scores': "
        "{'outer race': s, 'inner race': s, 'ball': s}}; repeatable",
    )
    p.add_argument(
        "--workers",
        type=_positive_int,
        default=1,
        help="processes, each running whole signals through every detector",
    )
    p.add_argument(
        "--bearing",
        default="6205",
        choices=sorted(BEARINGS),
        help="bearing when the manifest does not say",
    )
    p.add_argument("--out", default=None, help="folder for CSV tables and plots")
    p.add_argument(
        "--allow-training-data",
        action="store_true",
        help="run --model even on signals it was trained on (outputs labelled in-sample)",
    )
    _add_allow_incomplete(p)
    p.set_defaults(func=cmd_bench)

    p = sub.add_parser(
        "realism", help="how well simulated signals pass for measured ones (ROC AUC)"
    )
    p.add_argument("dataset", help="cmtool dataset folder (simulated)")
    p.add_argument("recordings", help="folder of recordings with a MANIFEST.csv")
    p.add_argument(
        "--feature-set",
        default="scale-free",
        choices=["scale-free", "envelope", "evidence"],
        help="features compared (default: scale-free, nothing in the signal's unit)",
    )
    p.add_argument("--workers", type=_positive_int, default=1, help="feature-extraction processes")
    p.add_argument("--out", default=None, help="folder for realism.json and realism.png")
    _add_allow_incomplete(p)
    p.set_defaults(func=cmd_realism)

    p = sub.add_parser("demo", help="the main job on the embedded default")
    p.add_argument("--out", default="out/demo", help="output folder")
    p.set_defaults(func=cmd_demo)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run ``cmtool``; returns the exit code (2 for input errors, 3 for a diverged run)."""
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.WARNING - 10 * min(args.verbose, 2),
        format="%(levelname)s %(name)s: %(message)s",
    )
    try:
        return int(args.func(args))
    except (CliError, ParameterError, ValueError, FileNotFoundError) as exc:
        print(f"cmtool {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except SimulationDivergedError as exc:
        print(f"cmtool {args.command}: simulation diverged: {exc}", file=sys.stderr)
        return 3
    except BrokenPipeError:  # the reader of our output went away (``| head``): stop quietly
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
