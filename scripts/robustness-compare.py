#!/usr/bin/env python3
"""Two runs of scripts/robustness-sessions.sh side by side: what a change did over all 130 runs.

    scripts/robustness-compare.py BEFORE AFTER

BEFORE and AFTER are the OUT folders of two harness runs with the same perturbations (each holds
pI/perturbation and pI/NAME.evaluation.json, as robustness-summary.py reads them). Per run name:
the mean of its runs' mean errors, the median and the worst of their max errors, and how many runs
miss issue 15's target (the same targets as robustness-summary.py), before -> after. A row whose
misses or worst changed is marked. Runs that failed or hold no scores count as misses; a folder
that is not a harness run, or two runs over different perturbations, is an error.
"""
import os
import runpy
import statistics
import sys
import types


def summary_module():
    """robustness-summary.py's loader, targets and run names (its main() does not run)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "robustness-summary.py")
    return types.SimpleNamespace(**runpy.run_path(path))


def perturbations(out):
    """The labels of the harness run in `out`, in order; exits with a message when it is none."""
    labels = []
    while os.path.isfile(os.path.join(out, f"p{len(labels)}", "perturbation")):
        with open(os.path.join(out, f"p{len(labels)}", "perturbation")) as f:
            labels.append(f.read().strip())
    if not labels:
        sys.exit(f"robustness-compare: {out}: no p0/perturbation (expected the OUT folder of "
                 f"scripts/robustness-sessions.sh)")
    return labels


def cell(summary, out, name, count):
    """(text, misses, worst) of one run name in one harness run."""
    scores = [(summary.load(os.path.join(out, f"p{i}", f"{name}.evaluation.json")),
               summary.load(os.path.join(out, f"p{i}", f"{name}.local.evaluation.json")))
              for i in range(count)]
    known = [s for s, _ in scores if s]
    missed = summary.misses(name, scores)
    if not known:
        return "no scores", missed, None
    worst = max(s["max"] for s in known)
    text = (f"{statistics.mean(s['mean'] for s in known):.4f} / "
            f"{statistics.median(s['max'] for s in known):.2f} / {worst:.2f}, {missed} missed")
    if len(known) < count:
        text += f" ({count - len(known)} failed)"
    return text, missed, worst


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: scripts/robustness-compare.py BEFORE AFTER")
    before, after = sys.argv[1], sys.argv[2]
    labels = perturbations(before)
    if perturbations(after) != labels:
        sys.exit(f"robustness-compare: {before} and {after} ran different perturbations")
    summary = summary_module()
    print(f"{len(labels)} perturbations. Per run: mean of the mean errors / median max / worst max "
          f"[m], runs missing issue 15's target.")
    print()
    print("| run | before | after | |")
    print("|---|---|---|---|")
    totals = [0, 0]
    for name in summary.RUNS:
        was, was_missed, was_worst = cell(summary, before, name, len(labels))
        now, now_missed, now_worst = cell(summary, after, name, len(labels))
        totals[0] += was_missed
        totals[1] += now_missed
        mark = ""
        if now_missed != was_missed:
            mark = "more misses" if now_missed > was_missed else "fewer misses"
        elif was_worst is not None and now_worst is not None and abs(now_worst - was_worst) > 0.005:
            mark = "worst up" if now_worst > was_worst else "worst down"
        print(f"| {name} | {was} | {now} | {mark} |")
    print()
    print(f"Runs missing issue 15's target: {totals[0]} -> {totals[1]} of "
          f"{len(labels) * len(summary.RUNS)}")


if __name__ == "__main__":
    main()
