"""Calibrate the rule detector's confidence on simulated data (issue 18: a calibrated confidence).

Each fault's line confidence is c = 1 / (1 + exp(-(margin - offset) / scale)), margin the
fault line over the detection threshold [dB]. Read as "the probability that the signal has
this fault", (scale, offset) are fitted by logistic regression of [the signal has fault i] on
margin_i over every (signal, fault) pair of a calibration dataset: the detector-bench recipe
(``datasets/detector-bench.toml``) with another seed and half the signals, simulated only.
The fit is checked on the benchmark dataset itself (held out: another seed) by the expected
calibration error (ECE, 10 bins) of the verdict's confidence against its correctness,
before and after.

The probabilities are those of the recipe's population (45 % healthy, pits of every kind and
size at fault SNRs of -20 to +10 dB): another population (a fleet where 1 % of the bearings
are faulty) shifts them, as any calibration depends on its prior.

Run: python benchmarks/calibrate_confidence.py [calibration-dir] [benchmark-dir]
(generates the calibration set if missing; the benchmark set is ``make detector-bench``'s
``out/detector-bench``, generated if missing).
"""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
FAULTS = ("outer race", "inner race", "ball")


def _dataset(path: Path, *, seed: int | None, half: bool) -> Path:
    from cmtool.datasets import generate_dataset

    if (path / "_dataset.json").is_file():
        return path
    text = (ROOT / "datasets" / "detector-bench.toml").read_text()
    if seed is not None:
        text = re.sub(r"^seed = \d+", f"seed = {seed}", text, flags=re.MULTILINE)
    if half:
        text = text.replace("count = 1000", "count = 500").replace("count = 400", "count = 200")
    with tempfile.TemporaryDirectory() as tmp:
        recipe = Path(tmp) / "recipe.toml"
        recipe.write_text(text)
        generate_dataset(recipe, path, workers=2, resume=True)
    return path


def _margins(path: Path):
    """Per signal: the true label and the rule detector's margin per fault [dB]."""
    from cmtool.bench import run_bench

    results = run_bench(path, workers=2)
    rule = results[results["detector"] == "envelope"]
    margins = rule[["score_outer_race", "score_inner_race", "score_ball"]].to_numpy()
    return rule["label"].to_numpy(), margins


def _confidence(margins: np.ndarray, scale: float, offset: float) -> np.ndarray:
    return 1.0 / (1.0 + np.exp(-(margins - offset) / scale))


def _verdicts(margins: np.ndarray, healthy: tuple[float, float], fault: tuple[float, float]):
    """The rule verdict (top line detected at margin >= 0) and its confidence, as diagnose:
    logistic in the top margin, one (scale, offset) for fault verdicts, one for healthy."""
    top = np.argmax(margins, axis=1)
    m = margins[np.arange(len(top)), top]
    detected = m >= 0.0
    verdict = np.where(detected, np.array(FAULTS)[top], "healthy")
    c_fault = _confidence(m, *fault)
    c_healthy = 1.0 - _confidence(m, *healthy)
    return verdict, np.where(detected, c_fault, c_healthy)


def _fit(x: np.ndarray, y: np.ndarray) -> tuple[float, float] | None:
    """(scale, offset) [dB] of P(y) = 1 / (1 + exp(-(x - offset) / scale)); None when y is
    all one value (no logistic to fit: since stop 44 every fault verdict of the calibration
    set is right)."""
    from sklearn.linear_model import LogisticRegression

    if len(np.unique(y)) < 2:
        return None
    fit = LogisticRegression(C=1e6).fit(x.reshape(-1, 1), y)
    slope, intercept = float(fit.coef_[0, 0]), float(fit.intercept_[0])
    return 1.0 / slope, -intercept / slope


def main() -> None:
    from cmtool import diagnose as D
    from cmtool.classifier import expected_calibration_error

    calibration = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "out" / "calibration"
    benchmark = Path(sys.argv[2]) if len(sys.argv) > 2 else ROOT / "out" / "detector-bench"
    labels, margins = _margins(_dataset(calibration, seed=9173, half=True))
    # each fault's line: P(the signal has this fault | its margin)
    line = _fit(margins.reshape(-1), (labels[:, None] == np.array(FAULTS)[None, :]).reshape(-1))
    # the verdict: P(right | top margin), fault verdicts and healthy verdicts apart
    top = margins.max(axis=1)
    called = np.array(FAULTS)[np.argmax(margins, axis=1)]
    detected = top >= 0.0
    fault = _fit(top[detected], (called == labels)[detected])
    healthy = _fit(top[~detected], (labels != "healthy")[~detected])
    print(f"calibration set {calibration.name}: {len(labels)} signals")

    def _say(name: str, fitted, n: int) -> str:
        if fitted is None:
            return f"{name}: all {n} alike, nothing to fit (rule of three: errors below 3/{n})"
        return f"{name} ({fitted[0]:.2f}, {fitted[1]:.2f}) dB"

    print(
        f"fitted: {_say('line (scale, offset) =', line, margins.size)}; "
        f"{_say('fault verdicts', fault, int(detected.sum()))}; "
        f"{_say('healthy verdicts', healthy, int((~detected).sum()))}"
    )
    test_labels, test_margins = _margins(_dataset(benchmark, seed=None, half=False))
    before = (D.CONFIDENCE_SCALE_DB, D.CONFIDENCE_OFFSET_DB)
    in_use = (
        ("uncalibrated (3 dB, 0 dB: the previous constants)", (3.0, 0.0), (3.0, 0.0)),
        ("in use (cmtool.diagnose)", D.HEALTHY_CONFIDENCE, D.FAULT_CONFIDENCE),
        ("fitted now", healthy, fault),
    )
    for name, h, f in in_use:
        if h is None or f is None:
            print(f"{name}: not scored (nothing was fitted)")
            continue
        verdict, confidence = _verdicts(test_margins, h, f)
        correct = verdict == test_labels
        ece = expected_calibration_error(confidence, correct)
        print(
            f"{name} on {benchmark.name} ({len(test_labels)} signals): accuracy "
            f"{correct.mean():.3f}, mean confidence {confidence.mean():.3f}, ECE {ece:.3f}"
        )
        fault_verdict = verdict != "healthy"
        for part, sel in (("fault verdicts", fault_verdict), ("healthy verdicts", ~fault_verdict)):
            if sel.any():
                print(
                    f"  {part}: {int(sel.sum())}, right {correct[sel].mean():.3f}, mean "
                    f"confidence {confidence[sel].mean():.3f}, ECE "
                    f"{expected_calibration_error(confidence[sel], correct[sel]):.3f}"
                )
    del before


if __name__ == "__main__":
    main()
