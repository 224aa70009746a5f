"""A local fault judged against a healthy recording of the same machine (``--baseline``).

An analyst who has a recording of the machine in good condition does not call a fault on lines
that were already there: a bearing's own form errors make its balls' entries into the load
zone jitter, and that train reads as an outer-race fault to the rule on its own
(docs/diagnosis.md, "Form errors read as a local fault"), in the baseline as in the record.
With a baseline, each fault's margin over the detection threshold is compared with the
baseline's margin for the same fault, each in its own band and against its own threshold
(records of other lengths or rates compare on the same false-alarm scale), and a fault stands
only where its margin rises ``BASELINE_RISE_DB`` or more over the baseline's
(docs/diagnosis.md, "Local faults against a baseline").
"""

from __future__ import annotations

#: How far a fault's margin over the threshold must rise over the baseline's margin for the
#: same fault [dB]. Chosen on simulation before the check it was judged by (docs/diagnosis.md,
#: "Local faults against a baseline"; ``benchmarks/baseline_rise.py A``): healthy 6205, 6203
#: and MFPT-rig bearings with 0.1 um form errors on the inner race, the balls or both, 1200
#: and 1797 rpm, 100 and 400 N, white noise at 5 and 50 % of the RMS, each against itself at
#: 1.2 x the load and 1.005 x the speed with fresh noise: the rule called 64 of the 72 records
#: faulty, with rises of at most 11.5 dB; the next whole dB and 3 dB more.
BASELINE_RISE_DB = 15.0


def fault_margins(candidates: list[dict], threshold_db: float) -> dict[str, float]:
    """Each fault's weighed evidence over the detection threshold [dB], by fault name."""
    return {c["fault"]: float(c["evidence_db"]) - threshold_db for c in candidates}


def weigh_against_baseline(
    candidates: list[dict],
    threshold_db: float,
    baseline_margins: dict[str, float],
    rise_db: float = BASELINE_RISE_DB,
) -> list[str]:
    """Mark each candidate with its rise over the baseline; set aside what does not rise.

    Each candidate gets ``baseline_margin_db`` (the baseline's margin for its fault [dB]) and
    ``over_baseline_db`` (its own margin less that [dB]). A detected candidate whose rise is
    below ``rise_db`` is no longer detected: ``as_in_baseline`` is set, and its confidence and
    ``effective_margin_db`` (the margin the verdict's confidence reads) are those of the rise
    less ``rise_db``, a negative margin. The candidates are changed in place.

    Parameters
    ----------
    candidates : list of dict
        ``cmtool.diagnose.rule_candidates`` of the record.
    threshold_db : float
        The record's detection threshold [dB].
    baseline_margins : dict of str to float
        :func:`fault_margins` of the baseline [dB].
    rise_db : float
        Rise a fault needs over the baseline [dB].

    Returns
    -------
    list of str
        The faults set aside, strongest first.

    Examples
    --------
    >>> c = [{"fault": "outer race", "evidence_db": 30.0, "detected": True, "confidence": 1.0}]
    >>> weigh_against_baseline(c, 14.0, {"outer race": 12.0})
    ['outer race']
    >>> c[0]["over_baseline_db"], c[0]["detected"], c[0]["effective_margin_db"]
    (4.0, False, -11.0)
    """
    from .diagnose import CONFIDENCE_OFFSET_DB, CONFIDENCE_SCALE_DB, confidence_of_margin

    set_aside = []
    for c in candidates:
        margin = float(c["evidence_db"]) - threshold_db
        base = baseline_margins[c["fault"]]
        c["baseline_margin_db"] = round(base, 2)
        c["over_baseline_db"] = round(margin - base, 2)
        if c["detected"] and margin - base < rise_db:
            c["detected"] = False
            c["as_in_baseline"] = True
            short = margin - base - rise_db  # how far the rise falls short, < 0 [dB]
            c["effective_margin_db"] = round(short, 2)
            c["confidence"] = round(
                confidence_of_margin(short, CONFIDENCE_SCALE_DB, CONFIDENCE_OFFSET_DB), 4
            )
            set_aside.append(c["fault"])
    return set_aside


def set_aside_text(candidates: list[dict], rise_db: float = BASELINE_RISE_DB) -> str:
    """What the verdict's basis says of the faults the baseline accounts for ('' if none)."""
    parts = [
        f"{c['fault']} {c['over_baseline_db'] + c['baseline_margin_db']:.1f} dB over the "
        f"threshold here, {c['baseline_margin_db']:.1f} dB in the baseline"
        for c in candidates
        if c.get("as_in_baseline")
    ]
    if not parts:
        return ""
    return (
        "; lines that stand as clearly in the healthy baseline, not a fault here (a fault "
        f"needs {rise_db:g} dB over the baseline's margin): " + ", ".join(parts)
    )
