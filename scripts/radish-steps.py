#!/usr/bin/env python3
"""Scan-to-scan errors of the Radish sessions against the reference poses.

    scripts/radish-steps.py OUT [OUT ...]

OUT is a folder of scripts/radish-sessions.sh (OUT/LOG-noisy and OUT/LOG-exact hold the runs);
the reference poses are $SCANLOC_DATASETS/radish/LOG.truth.txt (default ../shared/datasets).
For each run it prints, per log and odometry:
- the sum over consecutive scans of the translational error of their relative posture, and the
  number of steps whose error exceeds 0.15 m (local consistency: a wrong match shows there);
- over the localised scans the rules did not confirm, how often the refinement's step and how
  often the odometry prediction's step is the closer to the reference's, and the sum of each
  one's error (translation + 5 m × |sin(heading error)|, a wall 5 m away);
- then, over the unconfirmed scans of the noisy-odometry runs, the same two counts split by what
  the record says of the refinement: how far it moved the prediction, its match ratio, and the
  candidate it started from (what might tell a right unconfirmed refinement from a wrong one).
"""
import json
import math
import os
import sys

LOGS = ["seattle", "orebro", "fhw", "edmonton", "acapulco"]
KINDS = ["noisy", "exact"]
STEP_LIMIT_M = 0.15
LEVER_M = 5.0


def load_poses(path):
    poses = {}
    with open(path) as f:
        for line in f:
            fields = line.split()
            if not fields or fields[0].startswith("#"):
                continue
            t, x, y = map(float, fields[:3])
            if len(fields) == 8:  # TUM: t x y z qx qy qz qw
                yaw = 2.0 * math.atan2(float(fields[6]), float(fields[7]))
            else:  # t x y yaw
                yaw = float(fields[3])
            poses[round(t, 3)] = (x, y, yaw)
    return poses


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, math.atan2(math.sin(b[2] - a[2]), math.cos(b[2] - a[2])))


def step_error(estimated, reference):
    return math.hypot(estimated[0] - reference[0], estimated[1] - reference[1])


def pose(p):
    return (p["x_m"], p["y_m"], p["yaw_rad"])


def trajectory_steps(run, truth):
    est = load_poses(os.path.join(run, "trajectory.tum"))
    stamps = sorted(t for t in est if t in truth)
    errors = [step_error(between(est[a], est[b]), between(truth[a], truth[b]))
              for a, b in zip(stamps, stamps[1:])]
    return sum(errors), sum(e > STEP_LIMIT_M for e in errors)


def refinement_features(record):
    """What the record says of an unconfirmed scan's refinement, by feature name."""
    correction = between(pose(record["prediction"]), pose(record["refinement"]["T_world_laser"]))
    kept = min(record["refined_candidates"], key=lambda c: c["cost"])
    heading_deg = abs(math.degrees(correction[2]))
    translation_m = math.hypot(correction[0], correction[1])
    match_ratio = kept["match_ratio"]
    return {
        "heading moved": "< 1°" if heading_deg < 1 else ("1–3°" if heading_deg < 3 else "≥ 3°"),
        "position moved": "< 0.05 m" if translation_m < 0.05 else ("0.05–0.15 m" if translation_m < 0.15 else "≥ 0.15 m"),
        "match ratio": "< 0.4" if match_ratio < 0.4 else ("0.4–0.6" if match_ratio < 0.6 else "≥ 0.6"),
        "started from": "a turned candidate" if "deg" in kept["candidate"] else kept["candidate"],
    }


def unconfirmed_steps(run, truth, features=None):
    """(refinement closer, prediction closer, refinement error sum, prediction error sum); adds
    each scan's (features, refinement closer) to `features` when given."""
    with open(os.path.join(run, "iterations.jsonl")) as f:
        records = [json.loads(line) for line in f]
    counts = [0, 0, 0.0, 0.0]
    for previous, r in zip(records, records[1:]):
        if r["skipped"] or r["validated"] or "refinement" not in r:
            continue
        reference = between(truth[round(previous["timestamp_s"], 3)], truth[round(r["timestamp_s"], 3)])
        start = pose(previous["T_world_robot"])
        # The Radish logs mount the laser at the robot's origin: laser and robot postures agree.
        errors = []
        for candidate in (pose(r["refinement"]["T_world_laser"]), pose(r["prediction"])):
            step = between(start, candidate)
            errors.append(step_error(step, reference) + LEVER_M * abs(math.sin(step[2] - reference[2])))
        counts[0 if errors[0] < errors[1] else 1] += 1
        if features is not None:
            features.append((refinement_features(r), errors[0] < errors[1]))
        counts[2] += errors[0]
        counts[3] += errors[1]
    return counts


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    datasets = os.environ.get("SCANLOC_DATASETS", os.path.join(os.path.dirname(__file__), "../../shared/datasets"))
    truths = {log: load_poses(os.path.join(datasets, "radish", f"{log}.truth.txt")) for log in LOGS}
    print("| run | log | step errors: sum [m] / steps > 0.15 m | unconfirmed: refinement closer / prediction closer "
          "| unconfirmed: error sums, refinement / prediction [m] |")
    print("|---|---|---|---|---|")
    features = []
    for out in sys.argv[1:]:
        total = 0.0
        for log in LOGS:
            for kind in KINDS:
                run = os.path.join(out, f"{log}-{kind}")
                steps, large = trajectory_steps(run, truths[log])
                closer_r, closer_p, sum_r, sum_p = unconfirmed_steps(
                    run, truths[log], features if kind == "noisy" else None)
                total += steps
                print(f"| {out} | {log} {kind} | {steps:.2f} / {large} | {closer_r} / {closer_p} "
                      f"| {sum_r:.2f} / {sum_p:.2f} |")
        print(f"| {out} | all ten | {total:.1f} | | |")
    print_features(features)


def print_features(features):
    print()
    print("| unconfirmed scans, noisy odometry | value | refinement closer | prediction closer |")
    print("|---|---|---|---|")
    for name in features[0][0] if features else []:
        values = sorted({f[name] for f, _ in features})
        for value in values:
            closer_r = sum(1 for f, r in features if f[name] == value and r)
            closer_p = sum(1 for f, r in features if f[name] == value and not r)
            print(f"| {name} | {value} | {closer_r} | {closer_p} |")


if __name__ == "__main__":
    main()
