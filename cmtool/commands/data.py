"""``cmtool generate``, ``dataset info``, ``train`` and ``evaluate``: datasets and models."""

from __future__ import annotations

import argparse
import logging
import sys
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pandas as pd

from .common import CliError, StageBars, check_output_file, check_output_folder, progress_bar

logger = logging.getLogger("cmtool")


def cmd_generate(args: argparse.Namespace) -> int:
    """Generate a dataset from a recipe.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool generate`` (``cmtool generate --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    check_output_folder("--out", args.out, "a folder for the dataset")
    from ..datasets import generate_dataset

    bar = None

    def progress(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = progress_bar(total, "generate", "signal", initial=done)
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
    """Print counts per label and parameter ranges.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool dataset info`` (``cmtool dataset info --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    from ..datasets import dataset_info

    print(dataset_info(args.path))
    return 0


def cmd_train(args: argparse.Namespace) -> int:
    """Train classifiers with grouped cross-validation and save the best.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool train`` (``cmtool train --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    check_output_file("--out", args.out, "a model file, e.g. model.skops")
    import numpy as np

    from ..classifier import save_model, scores_by_rig, train, visible_faults
    from ..datasets import read_dataset
    from ..fits import FIT_STAGE

    frame = read_dataset(args.dataset, allow_incomplete=args.allow_incomplete)
    recipe = Path(args.dataset, "recipe.toml")
    with StageBars("train", units={FIT_STAGE: "fit"}) as progress:
        bundle = train(
            frame,
            recipe=recipe.read_text() if recipe.is_file() else "",
            random_state=args.seed,
            feature_set=args.feature_set,
            min_fault_snr_db=None if args.min_fault_snr is None else float(args.min_fault_snr),
            classifier=None if args.classifier == "best-cv" else args.classifier,
            workers=args.workers,
            progress=progress,
        )
    print(
        f"trained on {len(frame) - bundle['left_out']} signals ({bundle['left_out']} faulty "
        f"ones below the fault SNR floor left out), {frame['operating_point_id'].nunique()} "
        f"operating points, features {bundle['feature_set']}; grouped "
        f"{bundle['n_splits']}-fold balanced accuracy (the mean of the per-class recalls; no "
        "operating point in both train and test):"
    )
    for name, score in sorted(bundle["scores"].items(), key=lambda kv: -kv[1]):
        print(f"  {name:<22s} {score:.3f}{'  <- kept' if name == bundle['best'] else ''}")
    truth = np.asarray(bundle["cv_labels"])
    predicted = np.asarray(bundle["cv_predictions"])
    recalls = ", ".join(
        f"{label} {np.mean(predicted[truth == label] == label):.2f}" for label in bundle["classes"]
    )
    print(f"  recall per class of the kept model (out of fold): {recalls}")
    kept = visible_faults(frame, args.min_fault_snr)  # the rows train kept, in its order
    for rig, part in scores_by_rig(frame.loc[kept.to_numpy(), "bearing"], truth, predicted).items():
        print(f"  {_rig_line(rig, part)} (out of fold)")
    if bundle["extrapolation"]:
        print(
            "  accuracy at each end of the speed and load ranges, trained without it (the "
            "extreme tenth or grid level):"
        )
    for key, value in bundle["extrapolation"].items():
        print(f"  extrapolation {key:<28s} {value:.3f}")
    print(f"wrote {save_model(bundle, args.out)}")
    return 0


def cmd_evaluate(args: argparse.Namespace) -> int:
    """Accuracy, per-class precision/recall and confusion matrix of a model on a dataset.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options of ``cmtool evaluate`` (``cmtool evaluate --help``).

    Returns
    -------
    int
        The exit code, 0 on success.
    """
    check_output_folder("--out", args.out, "a folder for confusion.png and evaluation.json")
    from ..bench import confusion_plot_name
    from ..classifier import class_kinds, evaluate, load_model, visible_faults
    from ..datasets import read_dataset
    from ..io import atomic_write, json_text
    from ..plots import plot_confusion

    bundle = load_model(args.model)
    frame = read_dataset(args.dataset, allow_incomplete=args.allow_incomplete)
    kept = visible_faults(frame, args.min_fault_snr).to_numpy()
    if not kept.any():
        raise CliError(
            f"every signal of {args.dataset} is a fault below --min-fault-snr "
            f"{args.min_fault_snr:g} dB: nothing to score"
        )
    frame = frame[kept].reset_index(drop=True)
    in_sample = check_training_overlap(bundle, frame, args)
    theirs, ours = bundle.get("class_kinds") or {}, class_kinds(frame)
    unlike = {
        label: (theirs[label], kind)
        for label, kind in ours.items()
        if label in theirs and kind != theirs[label] and "none" not in (kind, theirs[label])
    }
    for label, (learnt, here) in unlike.items():
        print(
            f"warning: the model learnt {label!r} from {learnt} faults and this dataset's "
            f"{label!r} signals are {here}: their scores compare different faults"
        )
    with StageBars("evaluate") as progress:
        result = evaluate(bundle, frame, workers=args.workers, progress=progress)
    result["in_sample_fraction"] = in_sample
    result["min_fault_snr_db"] = args.min_fault_snr
    result["left_out"] = int((~kept).sum())
    result["kinds_unlike"] = {k: {"model": m, "dataset": d} for k, (m, d) in unlike.items()}
    if result["left_out"]:
        print(
            f"left out {result['left_out']} faulty signals below {args.min_fault_snr:g} dB "
            "fault SNR (nothing in them shows the fault; --min-fault-snr)"
        )
    tag = " (IN-SAMPLE: signals the model was trained on; not a measure of accuracy)"
    print(
        f"accuracy {result['accuracy']:.3f} on {len(result['predictions'])} signals"
        + (tag if in_sample else "")
    )
    print(f"{'label':<12s} {'precision':>9s} {'recall':>7s} {'f1':>6s}")
    for label, m in result["per_class"].items():
        print(f"{label:<12s} {m['precision']:9.3f} {m['recall']:7.3f} {m['f1-score']:6.3f}")
    for rig, part in result["by_rig"].items():
        print(f"  {_rig_line(rig, part)}")
    labels = result["labels"]
    print("confusion matrix (rows true, columns predicted): " + ", ".join(labels))
    for label, row in zip(labels, result["confusion"], strict=True):
        print(f"  {label:<12s} " + " ".join(f"{v:4d}" for v in row))
    if args.out:
        out = Path(args.out)
        kept = {k: v for k, v in result.items() if k != "predictions"}
        text = json_text(kept)
        atomic_write(out / "evaluation.json", lambda tmp: tmp.write_text(text))
        # the whole dataset's matrix, and each bearing's when it has several
        matrices = [("confusion.png", result["confusion"], "")]
        matrices += [
            (confusion_plot_name(rig), part["confusion"], f", bearing {rig}")
            for rig, part in result["by_rig"].items()
        ]
        for name, matrix, which in matrices:
            path = plot_confusion(
                matrix,
                labels,
                out / name,
                title=f"{Path(args.model).name} on {Path(args.dataset).name}{which}"
                + (" (in-sample)" if in_sample else ""),
            )
            print(f"wrote {path}")
    return 0


def _rig_line(rig: str, part: dict) -> str:
    """One bearing's scores (``classifier.scores_by_rig``) as a line of text."""
    recalls = ", ".join(f"{c} {v:.3f}" for c, v in part["recall"].items())
    return (
        f"bearing {rig}: accuracy {part['accuracy']:.3f} on {part['signals']} signals; recall "
        f"{recalls}"
    )


def check_training_overlap(bundle: dict, frame: pd.DataFrame, args: argparse.Namespace) -> float:
    """Refuse to score a model on its own training signals unless --allow-training-data.

    Parameters
    ----------
    bundle : dict
        The model bundle.
    frame : pandas.DataFrame
        The dataset to score.
    args : argparse.Namespace
        The command's options (``allow_training_data``, and the paths named in the error).

    Returns
    -------
    float
        The fraction of ``frame``'s signals the model was trained on (0 when none).

    Raises
    ------
    CliError
        When some were and ``--allow-training-data`` was not given.
    """
    from ..classifier import training_overlap

    overlap = training_overlap(bundle, frame)
    if overlap > 0 and not args.allow_training_data:
        raise CliError(
            f"{overlap:.0%} of the signals in {args.dataset} were used to train "
            f"{args.model}: scores on them say nothing about new data. Evaluate on a dataset "
            "generated with another seed, or pass --allow-training-data to run anyway "
            "(every output is then labelled in-sample)"
        )
    return overlap
