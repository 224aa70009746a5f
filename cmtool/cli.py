"""The ``cmtool`` command line.

Each subcommand is one job of a vibration analyst's (``cmtool COMMAND --help``); ``demo`` runs
the main job on the embedded default. Units at the edge: ``--rpm`` in rev/min, everything else
SI (m, N, s, Hz, Pa s).
"""

from __future__ import annotations

import argparse
import logging
import os
import sys
import warnings
from collections.abc import Sequence

from generators import (
    BEARINGS,
    ParameterError,
    SimulationDivergedError,
)

from . import __version__
from .commands.analysis import cmd_bench, cmd_demo, cmd_diagnose, cmd_realism
from .commands.common import CliError, finite_float, positive_float, seed_int
from .commands.data import cmd_dataset_info, cmd_evaluate, cmd_generate, cmd_train
from .commands.simulate import add_model_arguments, cmd_fidelity, cmd_frequencies, cmd_simulate
from .commands.specs import parse_defect, parse_waviness
from .vibration_zones import MACHINE_CLASSES, parse_zone_limits

logger = logging.getLogger("cmtool")

__all__ = ["main", "parse_waviness", "parse_defect", "build_parser"]


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


def _zone_limits(text: str) -> tuple[float, float, float]:
    """An argparse type: zone boundaries A/B, B/C, C/D [mm/s] (``parse_zone_limits``)."""
    try:
        return parse_zone_limits(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


class _Parser(argparse.ArgumentParser):
    """argparse with one-line usage errors (``cmtool CMD: error: ...``, exit 2)."""

    def error(self, message: str):  # noqa: D102 - argparse's hook
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


class _DefaultsHelp(argparse.ArgumentDefaultsHelpFormatter):
    """Each option's default in --help, unless its help already says it or there is none.

    None is an option without a default, False a flag that is off unless given; a flag that
    turns something off (``--no-ehl``) says so in its words, not as "(default: True)".
    """

    def _get_help_string(self, action: argparse.Action) -> str | None:
        text = action.help or ""
        flag = isinstance(action, (argparse._StoreTrueAction, argparse._StoreFalseAction))
        if flag or "default" in text.lower() or action.default in (None, False, argparse.SUPPRESS):
            return text
        return super()._get_help_string(action)


#: Help of ``--geometry`` (diagnose, frequencies).
GEOMETRY_HELP = (
    "a bearing not in the catalog: NAME:balls=Z:ball_diameter=d:pitch_diameter=D"
    "[:contact_angle_deg=A] (diameters [m], e.g. 6310:balls=8:ball_diameter=20.64e-3:"
    "pitch_diameter=77.5e-3)"
)


#: What ``cmtool --help`` says first and last.
DESCRIPTION = (
    "Condition monitoring of rolling-element bearings: simulate a lubricated ball bearing, "
    "generate labelled datasets, train and evaluate classifiers, diagnose measured recordings, "
    "benchmark detectors."
)
EPILOG = (
    "Start with 'cmtool demo'; 'cmtool COMMAND --help' gives each command's options. Units: "
    "--rpm in rev/min, everything else SI (m, N, s, Hz)."
)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of ``cmtool``.

    Returns
    -------
    argparse.ArgumentParser
        With a sub-parser per command.
    """
    parser = _Parser(prog="cmtool", description=DESCRIPTION, epilog=EPILOG)
    parser.add_argument("--version", action="version", version=f"cmtool {__version__}")
    parser.add_argument(
        "-v", "--verbose", action="count", default=0, help="more log messages (-v info, -vv debug)"
    )
    commands = parser.add_subparsers(dest="command", required=True)

    class _Commands:
        """Sub-parsers that show every option's default in --help."""

        @staticmethod
        def add_parser(name: str, **kwargs) -> argparse.ArgumentParser:
            kwargs.setdefault("formatter_class", _DefaultsHelp)
            return commands.add_parser(name, **kwargs)

    sub = _Commands()

    p = sub.add_parser("simulate", help="simulate one housing vibration signal")
    add_model_arguments(p)
    p.add_argument(
        "--error-bound",
        dest="step_error_bound",
        type=float,
        default=None,
        help="RK4 without --step: the longest step whose relative error in the bearing's "
        "characteristic line amplitudes and in each octave of the spectrum above 500 Hz is at "
        "most this (e.g. 0.01), measured by pilot runs; --step wins",
    )
    p.add_argument("--out", help="output file (.parquet or .csv)")
    p.add_argument("--plot", help="spectrum plot (.png)")
    p.add_argument(
        "--envelope-plot",
        help="envelope spectrum plot of the housing acceleration (.png; the band cmtool "
        "diagnose chooses, named in the title)",
    )
    p.set_defaults(func=cmd_simulate)

    p = sub.add_parser("frequencies", help="characteristic frequencies of a catalog bearing")
    which = p.add_mutually_exclusive_group()
    which.add_argument(
        "--bearing", default="6205", choices=sorted(BEARINGS), help="catalog bearing"
    )
    which.add_argument("--geometry", default=None, help=GEOMETRY_HELP)
    p.add_argument("--rpm", type=float, required=True, help="shaft speed [rev/min]")
    p.add_argument(
        "--wpf",
        action="append",
        metavar="SURFACE:ORDERS",
        help="waviness passage frequencies of these waviness orders on a surface (outer, "
        "inner, ball), e.g. outer:9 or inner:8-10,17-19; repeatable",
    )
    p.add_argument(
        "--harmonics", type=_positive_int, default=3, help="ball-pass harmonics q for --wpf"
    )
    p.add_argument(
        "--cage-slip",
        type=float,
        default=0.0,
        help="the cage's mean slip s [-], 0 to 0.5: the cage turns at 1 - s of its kinematic "
        "speed, so FTF, BPFO and BSF lie lower by s and BPFI higher by s BPFO/BPFI (real "
        "bearings: up to 1-2 %%)",
    )
    p.add_argument("--json", action="store_true", help="print the frequencies as JSON")
    p.set_defaults(func=cmd_frequencies)

    p = sub.add_parser(
        "fidelity", help="speed against accuracy of every model level and integrator setting"
    )
    add_model_arguments(p)
    p.add_argument(
        "--levels", default="shaft,shaft+housing,full", help="comma-separated model levels"
    )
    p.add_argument("--steps", default=None, help="comma-separated RK4 steps [s]")
    p.add_argument("--rtols", default=None, help="comma-separated DOPRI5 tolerances")
    p.add_argument("--f-max", type=positive_float, default=5000.0, help="spectrum error band [Hz]")
    p.add_argument(
        "--error-bound",
        type=float,
        default=0.01,
        help="band amplitude error bound for the recommendation, and the bound each level's "
        "error-bound step is chosen for (rows chosen_for_bound) [-]",
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
    p.add_argument(
        "--seed",
        type=seed_int,
        default=0,
        help="seed of the classifiers (the same seed, the same model)",
    )
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
        type=finite_float,
        default=-10.0,
        metavar="DB",
        help="leave out faulty signals whose fault SNR is below DB (nothing in them shows the "
        "fault; default -10 dB)",
    )
    p.add_argument(
        "--classifier",
        default="recipe",
        choices=[
            "recipe",
            "best-cv",
            "extra_trees",
            "random_forest",
            "gradient_boosting",
            "logistic_regression",
        ],
        help="classifier kept (default: the one the dataset's recipe names in [training] "
        "classifier, the rig recipes the one that carried over best between simulated rigs; "
        "else best-cv: the best grouped cross-validation score on this dataset)",
    )
    p.add_argument(
        "--workers",
        type=_positive_int,
        default=os.cpu_count() or 1,
        help="processes for the features, the rule evidence of the calibration and the model "
        "fits (default: all cores; the model is the same for any count)",
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
    p.add_argument(
        "--workers",
        type=_positive_int,
        default=os.cpu_count() or 1,
        help="feature-extraction processes (default: all cores)",
    )
    p.add_argument(
        "--min-fault-snr",
        type=finite_float,
        default=-10.0,
        metavar="DB",
        help="leave out faulty signals whose fault SNR is below DB, as train does (nothing in "
        "them shows the fault: a pit the balls never meet; default -10 dB)",
    )
    _add_allow_incomplete(p)
    p.set_defaults(func=cmd_evaluate)

    p = sub.add_parser("diagnose", help="diagnose a measured recording")
    p.add_argument(
        "recording",
        help="CSV, Excel .xlsx, WAV, MATLAB .mat (v4-v7.3), .npy/.npz, parquet, LabVIEW .tdms "
        "or UFF .uff/.unv (data-set 58) file, or a folder whose MANIFEST.csv lists "
        "recordings with their rate, speed and bearing (a line each; --report: a report each "
        "and verdicts.csv)",
    )
    p.add_argument("--fs", type=float, default=None, help="sample rate [Hz] (if not in file)")
    p.add_argument("--rpm", type=float, default=None, help="shaft speed [rev/min]")
    p.add_argument(
        "--speed-source",
        default=None,
        choices=("given", "spectrum", "auto"),
        help="the fault rates' shaft speed: the one given (--rpm, the file's or the "
        "manifest's), the spectrum's 1x line found within 5 %% of it (a nameplate speed is "
        "1-4 %% off a loaded motor's; the speed given where no line stands out), or auto "
        "(default; given with --tacho): the speed given unless the line lies more than 1 %% "
        "from it",
    )
    which = p.add_mutually_exclusive_group()
    which.add_argument(
        "--bearing",
        default=None,
        choices=sorted(BEARINGS),
        help="catalog bearing (required unless the file says: cmtool parquet and CSV files, "
        "the CWRU and MFPT layouts; or give --geometry)",
    )
    which.add_argument("--geometry", default=None, help=GEOMETRY_HELP)
    p.add_argument(
        "--variable",
        default=None,
        help="variable of a .mat/.npz file, group/channel of a .tdms file, ID line of a UFF record",
    )
    p.add_argument("--channel", default=None, help="column or channel")
    p.add_argument(
        "--tacho",
        default=None,
        metavar="CHANNEL",
        help="the file's tachometer or key-phasor channel (column or number): the shaft speed "
        "from its pulses, used as the speed given (--speed-source given unless another is "
        "asked for); its spread over the record is stated",
    )
    p.add_argument(
        "--pulses-per-rev",
        type=int,
        default=1,
        help="tachometer pulses per shaft revolution (default 1)",
    )
    p.add_argument(
        "--order-track",
        action="store_true",
        help="with --tacho: resample the record to constant shaft speed (its mean) before "
        "diagnosing, so that a fault's lines stay lines while the speed drifts (computed "
        "order tracking)",
    )
    p.add_argument("--model", default=None, help="trained model (cmtool train)")
    p.add_argument("--report", default=None, help="folder for report.md and plots")
    p.add_argument(
        "--baseline",
        default=None,
        help="a healthy recording of the same machine: ISO 15242 bands and the waviness line "
        "reported against it",
    )
    p.add_argument(
        "--load",
        type=float,
        default=None,
        help="radial load [N] of the healthy model that waviness lines are judged against "
        "without --baseline (default: the load a cmtool simulate file holds, else 500 N, "
        "stated as assumed); given or from the file, it also narrows a spall size's interval",
    )
    p.add_argument(
        "--allow-clipping",
        action="store_true",
        help="diagnose a record (or baseline) with 3 %% or more of its samples at full scale "
        "instead of refusing it (its verdict then carries a warning)",
    )
    p.add_argument(
        "--unit",
        default=None,
        choices=("g", "m/s^2", "mm/s", "m/s", "in/s"),
        help="the recording's unit, for velocity bands in mm/s: an acceleration's, or a "
        "velocity's (a velocity transducer's record, diagnosed by its derivative) (default: "
        "the file's where it says: g in CWRU and MFPT files, m/s^2 in cmtool's, a CSV's "
        "units row or bracketed unit)",
    )
    zones = p.add_mutually_exclusive_group()
    zones.add_argument(
        "--machine-class",
        default=None,
        choices=tuple(MACHINE_CLASSES),
        help="the machine's class for the overall velocity's evaluation zone A-D: ISO 10816-3 "
        "group 1 (over 300 kW) or 2 (15-300 kW) on rigid or flexible support, or ISO 10816-1 "
        "class I-IV (class-I: small machines up to 15 kW) (default: no zone; a folder's "
        "manifest may give one per recording, column machine_class)",
    )
    zones.add_argument(
        "--zone-limits",
        default=None,
        type=_zone_limits,
        metavar="AB,BC,CD",
        help="the zone boundaries A/B, B/C, C/D a site uses [mm/s RMS], e.g. 1.4,2.8,4.5, "
        "instead of a class",
    )
    p.add_argument(
        "--workers",
        type=_positive_int,
        default=1,
        help="processes for a folder's recordings (each diagnoses whole recordings)",
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
    """Run ``cmtool``; returns the exit code (2 for input errors, 3 for a diverged run).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default the process's, ``sys.argv[1:]``).

    Returns
    -------
    int
        0 on success.
    """
    parser = build_parser()
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=logging.WARNING - 10 * min(args.verbose, 2),
        format="%(levelname)s %(name)s: %(message)s",
    )

    shown: set[str] = set()

    def show_warning(message, category, filename, lineno, file=None, line=None) -> None:
        if str(message) not in shown:  # once, wherever it comes from
            shown.add(str(message))
            print(f"cmtool {args.command}: warning: {message}", file=sys.stderr)

    try:
        with warnings.catch_warnings():  # a library warning as one line of the command's
            warnings.showwarning = show_warning
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
