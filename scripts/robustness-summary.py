#!/usr/bin/env python3
"""The table of scripts/robustness-sessions.sh, and issue 15's targets counted over every run.

    scripts/robustness-summary.py OUT COUNT

OUT holds OUT/pI/perturbation and, per run NAME of perturbation I, OUT/pI/NAME.evaluation.json
(all relations), OUT/pI/NAME.local.evaluation.json (Radish: relations of scans <= 15 s apart) and
OUT/pI/NAME/ (the run folder). A run that failed, or whose scores are missing, counts as failed
in every target.
"""
import importlib.util
import json
import os
import statistics
import sys

BENCHMARK = ["intel", "aces", "fr079"]
RADISH = ["seattle", "orebro", "fhw", "edmonton", "acapulco"]
RUNS = BENCHMARK + [f"{log}-{kind}" for log in RADISH for kind in ["noisy", "exact"]]
LOST_M = 1.0  # a Kümmerle run with a relation above this has lost its track (issue 15)
LOCAL_LIMIT_M = 0.5  # Radish noisy: no relation of scans <= 15 s apart may reach this
EXACT_MEAN_M, EXACT_MAX_M = 0.05, 0.5  # Radish perfect odometry: mean and max below these


def load(path):
    try:
        with open(path) as f:
            return json.load(f)["translation_m"]
    except (OSError, ValueError, KeyError):
        return None


def steps_module():
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "radish-steps.py")
    spec = importlib.util.spec_from_file_location("radish_steps", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def step_sum(steps, out, i, datasets):
    """The sum of the ten Radish runs' scan-to-scan errors of perturbation i, or None."""
    total = 0.0
    for log in RADISH:
        truth = steps.load_poses(os.path.join(datasets, "radish", f"{log}.truth.txt"))
        for kind in ["noisy", "exact"]:
            try:
                total += steps.trajectory_steps(os.path.join(out, f"p{i}", f"{log}-{kind}"), truth)[0]
            except OSError:
                return None
    return total


def misses(name, scores):
    """How many of one run name's runs miss issue 15's target (None scores miss)."""
    if name in BENCHMARK:
        return sum(s is None or s["max"] > LOST_M for s, _ in scores)
    if name.endswith("-noisy"):
        return sum(l is None or l["max"] >= LOCAL_LIMIT_M for _, l in scores)
    return sum(s is None or not (s["mean"] < EXACT_MEAN_M and s["max"] < EXACT_MAX_M)
               for s, _ in scores)


def row(name, scores):
    """One log's row: the mean of every run, their median and worst, and its target count."""
    means = [s["mean"] if s else None for s, _ in scores]
    known = [m for m in means if m is not None]
    cells = " ".join("failed" if m is None else f"{m:.3f}" for m in means)
    median = f"{statistics.median(known):.3f}" if known else "–"
    worst = "failed" if None in means else f"{max(means):.3f}"
    missed = misses(name, scores)
    if name in BENCHMARK:
        target = f"{missed} with a relation above {LOST_M:g} m"
    elif name.endswith("-noisy"):
        target = f"{missed} with a local relation of {LOCAL_LIMIT_M:g} m or more"
    else:
        target = f"{missed} not below {EXACT_MEAN_M:g} m mean and {EXACT_MAX_M:g} m max"
    local = [l["max"] for _, l in scores if l]
    local_cell = f"{statistics.median(local):.2f}" if local else "–"
    print(f"| {name} | {cells} | {median} | {worst} | {local_cell} | {target} |")
    return missed


def odometry_model(run_dir):
    """What the run's odometry model concluded (summary.json), as text; "" when it learned none."""
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            model = json.load(f)["loop_closure"]["odometry_model"]
    except (OSError, ValueError, KeyError):
        return ""
    if "heading_rad2_per_m" not in model:
        return "odometry not learned"
    test = model.get("heading_test_statistic")
    test_cell = f" (heading test {test:.1f})" if test is not None else ""
    return (f"heading {model['heading_rad2_per_m']:.2g} rad²/m{test_cell}, position "
            f"{model['position_m2_per_m']:.2g} m²/m, {model['edges_in_graph']} odometry steps in "
            f"the graph")


def exact_misses(out, count):
    """The perfect-odometry runs that miss issue 15's target, each with its odometry model: a
    perfect odometry taken for a noisy one keeps its steps out of the graph."""
    lines = []
    for i in range(count):
        for log in RADISH:
            name = f"{log}-exact"
            s = load(os.path.join(out, f"p{i}", f"{name}.evaluation.json"))
            if s and s["mean"] < EXACT_MEAN_M and s["max"] < EXACT_MAX_M:
                continue
            score = f"{s['mean']:.3f} / {s['max']:.2f} m" if s else "failed"
            model = odometry_model(os.path.join(out, f"p{i}", name))
            lines.append(f"- p{i} {name}: {score}" + (f"; {model}" if model else ""))
    return lines


def main():
    out, count = sys.argv[1], int(sys.argv[2])
    datasets = os.environ.get("SCANLOC_DATASETS", "../shared/datasets")
    labels = [open(os.path.join(out, f"p{i}", "perturbation")).read().strip() for i in range(count)]
    print("Perturbations, in the order of the columns: " +
          "; ".join(f"{i}: {label}" for i, label in enumerate(labels)))
    print()
    print("| run | mean error of each run [m] | median | worst | local max, median [m] "
          "| runs missing issue 15's target |")
    print("|---|---|---|---|---|---|")
    misses = {"benchmark": 0, "noisy": 0, "exact": 0}
    for name in RUNS:
        scores = [(load(os.path.join(out, f"p{i}", f"{name}.evaluation.json")),
                   load(os.path.join(out, f"p{i}", f"{name}.local.evaluation.json")))
                  for i in range(count)]
        group = "benchmark" if name in BENCHMARK else name.split("-")[1]
        misses[group] += row(name, scores)
    steps = steps_module()
    sums = [step_sum(steps, out, i, datasets) for i in range(count)]
    print()
    print("Radish scan-to-scan errors, summed over the ten runs [m], per perturbation: " +
          " ".join("failed" if s is None else f"{s:.1f}" for s in sums))
    print()
    print(f"Kümmerle runs with a relation above {LOST_M:g} m: {misses['benchmark']} of "
          f"{count * len(BENCHMARK)} (target: none)")
    print(f"Radish noisy runs with a local relation of {LOCAL_LIMIT_M:g} m or more: "
          f"{misses['noisy']} of {count * len(RADISH)} (target: none)")
    print(f"Radish perfect-odometry runs not below {EXACT_MEAN_M:g} m mean and {EXACT_MAX_M:g} m "
          f"max: {misses['exact']} of {count * len(RADISH)} (target: none)")
    lines = exact_misses(out, count)
    if lines:
        print()
        print("The perfect-odometry runs that miss it, and what their odometry model learned:")
        print("\n".join(lines))
    failed = os.path.join(out, "failed")
    if os.path.exists(failed):
        print("Failed runs: " + ", ".join(open(failed).read().split("\n")).strip(", "))


if __name__ == "__main__":
    main()
