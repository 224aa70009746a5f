"""``cmtool simulate``, ``frequencies`` and ``fidelity``: the model's own commands."""

from __future__ import annotations

import argparse
import dataclasses
import logging
import math
import sys
import warnings
from pathlib import Path

from generators import (
    BEARINGS,
    CHANNELS,
    LUBRICANTS,
    OperatingCondition,
    Rig,
    Scene,
    SimulationDivergedError,
    SimulationSettings,
    Waviness,
    bearing,
    characteristic_frequencies,
    form_waviness,
    waviness_passage_frequencies,
)
from generators.params import check_real, check_shaft_speed_rpm

from .common import CliError, check_output_file, progress_bar, seed_int
from .specs import (
    parse_defect,
    parse_form_waviness,
    parse_geometry,
    parse_waviness,
    parse_wpf,
)

logger = logging.getLogger("cmtool")


def _default(cls: type, name: str):
    """The default of a parameter object's field (the one place it is written)."""
    import dataclasses

    return next(f.default for f in dataclasses.fields(cls) if f.name == name)


def add_model_arguments(p: argparse.ArgumentParser) -> None:
    """The model's arguments (bearing, operating point, defects, scene, rig, settings) on ``p``.

    Parameters
    ----------
    p : argparse.ArgumentParser
        The command's parser (``simulate``, ``fidelity``).
    """
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
        "--form-waviness",
        type=parse_form_waviness,
        default=(0.0, 0.0, 0.0),
        metavar="INNER,OUTER,BALL",
        help="the bearing's own form errors [m]: inner and outer race waviness at order Z, ball "
        "waviness at order 2 (generators.form_waviness; a new bearing: about 1e-8 to 2e-7)",
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
    s.add_argument(
        "--scene",
        default=_default(Scene, "level"),
        choices=SCENE_LEVELS,
        help="shaft: 2 DOF on massless balls; shaft+housing: 4 DOF; full: a DOF per ball as "
        "well; auto: the cheapest whose dropped physics is within --auto-error-bound",
    )
    s.add_argument(
        "--ehl",
        dest="ehl",
        action="store_true",
        default=True,
        help="include the EHL film (default)",
    )
    s.add_argument("--no-ehl", dest="ehl", action="store_false", help="dry contacts")
    s.add_argument(
        "--auto-error-bound",
        type=float,
        default=_default(Scene, "auto_error_bound"),
        help="relative error the auto scene may drop [-]",
    )
    r = p.add_argument_group("rig (as docs/model.md 6.3 unless given)")
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
    r.add_argument(
        "--film-damping-factor",
        type=float,
        default=d.film_damping_factor,
        help="multiplier on the EHL film's squeeze damping [-]",
    )
    r.add_argument(
        "--film-entrainment-factor",
        type=float,
        default=d.film_entrainment_factor,
        help="the film's load at light load as a share of a flooded contact's rigid-isoviscous "
        "load, 0-1 (0: none, the film carries nothing before the EHL contact; 1: flooded; "
        "docs/model.md 4.6) [-]",
    )
    r.add_argument(
        "--lubricant",
        default=next(k for k, v in LUBRICANTS.items() if v == d.lubricant),
        choices=sorted(LUBRICANTS),
        help="lubricant of the EHL film (ISO viscosity grade, or grease)",
    )
    r.add_argument(
        "--loading-stiffness",
        type=float,
        default=0.0,
        help="loading spring [N/m]; 0 = constant force",
    )
    r.add_argument("--unbalance", type=float, default=0.0, help="m_u e [kg m]")
    r.add_argument(
        "--no-gravity",
        dest="gravity",
        action="store_false",
        default=True,
        help="leave out gravity on the shaft, housing and balls",
    )
    n = p.add_argument_group("integration and sampling")
    sim = SimulationSettings()
    n.add_argument("--fs", type=float, default=sim.fs, help="output sample rate [Hz]")
    n.add_argument("--duration", type=float, default=sim.duration, help="recorded duration [s]")
    n.add_argument(
        "--settle", type=float, default=sim.settle_time, help="settling time discarded [s]"
    )
    n.add_argument(
        "--integrator",
        default=sim.integrator,
        choices=INTEGRATORS,
        help="rk4: fixed step; dopri5: adaptive Dormand-Prince 5(4)",
    )
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
    n.add_argument(
        "--seed",
        type=seed_int,
        default=None,
        help="seed of the run's random draws (waviness phases, slip); default: one is drawn, "
        "printed and written with the signal",
    )


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
    defects = list(form_waviness(geometry.ball_count, *args.form_waviness))
    defects += [parse_waviness(s) for s in args.waviness]
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
        film_entrainment_factor=args.film_entrainment_factor,
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
        error_bound=getattr(args, "step_error_bound", None),
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

    from ..io import estimated_file_bytes

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


def _warn_of_content(geometry, shaft_frequency, fs, defects, level) -> None:
    """Warn of what the record cannot show of its faults (generators.content)."""
    import warnings

    from generators.content import RecordContentWarning, record_content_warnings

    orders = [d.order for d in defects if isinstance(d, Waviness) and d.surface == "ball"]
    for message in record_content_warnings(geometry, shaft_frequency, fs, orders, level):
        warnings.warn(message, RecordContentWarning, stacklevel=3)


def cmd_simulate(args: argparse.Namespace) -> int:
    """Run one simulation, write the signal and optionally the spectrum plot.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool simulate`` (``cmtool simulate --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    import numpy as np

    import features
    from generators import simulate
    from generators.prepared import EHL_MIN_SHAFT_FREQUENCY

    from ..io import write_signal
    from ..plots import plot_spectrum, waviness_markers

    _check_outputs(args)
    geometry, operating, defects, scene, rig, settings = _model_inputs(args)
    _warn_of_content(geometry, operating.shaft_frequency, settings.fs, defects, scene.level)
    n_samples = int(round(settings.duration * settings.fs))
    streams = _check_run_size(args, settings, n_samples)
    if args.seed is None:  # a run's random draws (slip, phases) are always repeatable: a seed
        args.seed = int(np.random.SeedSequence().generate_state(1)[0])  # drawn, said, written
        print(f"random seed {args.seed} (drawn; --seed {args.seed} repeats this run)")
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
    result.parameters["seed"] = args.seed
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
            log=False,
            top_from=0.5 * f.ftf,
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
    stats = run.parameters.get("integrator_stats", {})
    if "line_error_estimate" in stats:
        print(
            f"RK4 step {stats['step_s']:.3g} s for the error bound {stats['error_bound']:g} "
            f"(estimated error of the lines and bands {stats['line_error_estimate']:.2g})"
        )
    oversample = run.parameters.get("oversample")
    if oversample:  # what the record was (docs/performance.md, "Records at 96 kHz or more")
        step = stats.get("step_s")
        integrator = (
            f"RK4 step {step * 1e6:.4g} us"
            if settings.integrator == "rk4" and step
            else settings.integrator
        )
        print(
            f"{integrator}, recorded at {oversample * settings.fs / 1e3:g} kHz "
            f"({oversample} x fs) and anti-alias decimated to {settings.fs / 1e3:g} kHz"
        )
    f = run.frequencies
    print(
        f"FTF {f.ftf:.3f} Hz  BPFO {f.bpfo:.3f} Hz  BPFI {f.bpfi:.3f} Hz  "
        f"BSF {f.bsf:.3f} Hz  2xBSF {f.two_bsf:.3f} Hz"
    )


def _simulate_streamed(args, geometry, operating, defects, scene, rig, settings, film) -> int:
    """A long run: integrated and written block by block, with a progress bar."""
    from generators.model import MAX_STEP_HALVINGS, step_shortened
    from generators.stream import simulate_stream

    from ..io import write_signal_stream

    # as generators.model.integrate does in memory: RK4's default step, diverged, is halved
    # and the run made again from its start (the file is written whole or not at all)
    retry = settings.integrator == "rk4" and settings.step is None and not settings.error_bound
    attempt, halvings, default_step, failed = settings, 0, math.nan, None
    while True:
        stream = simulate_stream(
            geometry,
            operating,
            defects,
            scene=scene,
            rig=rig,
            settings=attempt,
            random_state=args.seed,
        )
        stream.parameters["seed"] = args.seed
        if halvings == 0:
            default_step = stream.parameters["integrator_stats"]["step_s"]
        else:  # in the file's header, which is written before the first block
            stream.parameters["integrator_stats"]["step_halvings"] = halvings
        try:
            with progress_bar(stream.n_samples, "simulate", "sample", unit_scale=True) as bar:
                if args.out:
                    path = write_signal_stream(
                        stream, args.out, channels=_requested_channels(args), progress=bar.update
                    )
                else:
                    path = None
                    for block in stream:
                        bar.update(len(block.time))
            break
        except SimulationDivergedError as error:
            if not retry or halvings == MAX_STEP_HALVINGS:
                raise
            failed = failed or error
            halvings += 1
            attempt = dataclasses.replace(settings, step=default_step / 2.0**halvings)
    if halvings:
        used = stream.parameters["integrator_stats"]["step_s"]
        warnings.warn(step_shortened(default_step, failed.time, failed.scene, used), stacklevel=2)
    _print_run(stream, settings, geometry, operating, film)
    if path is not None:
        print(f"wrote {path} (streamed in blocks of {stream.block_samples:,} samples)")
    return 0


def cmd_frequencies(args: argparse.Namespace) -> int:
    """Print a bearing's characteristic frequencies, and its WPF for ``--wpf``.

    The bearing is a catalog one or a given geometry; the waviness passage frequencies are
    those of the orders asked for (docs/model.md 2.1); with ``--cage-slip`` s, every rate is
    the slipping cage's (docs/realism.md 1).

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool frequencies`` (``cmtool frequencies --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    geometry = parse_geometry(args.geometry) if args.geometry else bearing(args.bearing)
    rpm = check_shaft_speed_rpm("--rpm", args.rpm)
    slip = check_real("--cage-slip", args.cage_slip, low=0.0, high=0.5, high_inclusive=False)
    f = characteristic_frequencies(geometry, rpm / 60.0, cage_slip=slip)
    data = f.as_dict()
    wpf = []
    for spec in args.wpf or []:
        surface, orders = parse_wpf(spec)
        for order in orders:
            lines = waviness_passage_frequencies(
                geometry, rpm / 60.0, surface, order, max_harmonic=args.harmonics, cage_slip=slip
            )
            wpf.append(
                {
                    "surface": surface,
                    "order": order,
                    "lines": [dataclasses.asdict(x) for x in lines],
                }
            )
    if args.json:
        out = {"bearing": geometry.name, "rpm": args.rpm, "cage_slip": slip}
        out["frequencies_hz"] = data
        out["orders"] = f.orders()
        if wpf:
            out["waviness_passage_frequencies_hz"] = wpf
        from ..io import json_text

        print(json_text(out))
        return 0
    if slip:
        print(f"cage slip {slip:g}: the cage at {1 - slip:g} of its kinematic speed")
    for key, value in data.items():
        print(f"{key:>24s} {value:10.4f} Hz  {value / f.shaft:8.5f} x shaft")
    if wpf:
        print(
            "waviness passage frequencies [Hz] (docs/model.md 2.1; q the ball-pass harmonic, for "
            "the balls the order 2p of 2p f_b; "
            "strong: the exact-order rules, weak: higher load-zone harmonics; radial: a "
            "rotating pattern, load: in the load direction only)"
        )
    for entry in wpf:
        lines = ", ".join(
            f"{x['frequency']:.3f} (q {x['harmonic']}, {x['direction']}, {x['strength']})"
            for x in entry["lines"]
        )
        none = "no line (an odd order does not compress the ball)"
        print(f"  {entry['surface']:>5s} N_w = {entry['order']:<3d} {lines or none}")
    return 0


def _number_list(option: str, text: str | None) -> tuple[float, ...] | None:
    """A comma-separated list of numbers, or None; an entry that is none is named."""
    if not text:
        return None
    values = []
    for item in text.split(","):
        try:
            values.append(float(item))
        except ValueError:
            raise CliError(
                f"{option} {text!r}: {item.strip()!r} is not a number (comma-separated numbers)"
            ) from None
    return tuple(values)


def cmd_fidelity(args: argparse.Namespace) -> int:
    """Run the speed/accuracy study and print, write and plot the table.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool fidelity`` (``cmtool fidelity --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    check_output_file("--out", args.out, "a CSV file")
    check_output_file("--plot", args.plot, "a PNG file")
    _check_outputs(argparse.Namespace(plot=args.plot))  # its suffix, before the runs
    from ..fidelity import fidelity_study, plot_fidelity, recommend

    geometry, operating, defects, _, rig, settings = _model_inputs(args)
    steps = _number_list("--steps", args.steps)
    rtols = _number_list("--rtols", args.rtols)
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
            bar = progress_bar(total, "fidelity")
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
        error_bound=args.error_bound,
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
        from ..io import atomic_write

        atomic_write(Path(args.out), lambda tmp: table.to_csv(tmp, index=False))
        print(f"wrote {args.out}")
    if args.plot:
        print(f"wrote {plot_fidelity(table, args.plot, error_bound=args.error_bound)}")
    return 0
