#!/usr/bin/env python3
"""How far a session's corrections of the odometry add up over a stretch of path.

    scripts/correction-drift.py RUN_DIR [WINDOW_M]

For every localised scan of RUN_DIR/iterations.jsonl, sums the corrections the session made to the
odometry's prediction (`correction_from_prediction_mm_mm_mrad`, turned into the world frame by the
prediction's heading) over the scans of the last WINDOW_M metres of path (default 5), and prints
the largest sum with where it happened, the 99th and 90th percentiles, and the correction gate's
bound in force there. Odometry errors partly cancel from scan to scan. A matcher that slides along
a corridor corrects the same way every time, and the sum grows with the path.
"""
import collections
import json
import math
import sys


def corrections(path):
    """(path length so far [m], world-frame correction x, y [m], timestamp, bound [m]) per scan."""
    out, last, length = [], None, 0.0
    with open(path) as records:
        for number, line in enumerate(records, 1):
            try:
                record = json.loads(line)
                pose = record["T_world_robot"]
                if last is not None:
                    length += math.hypot(pose["x_m"] - last["x_m"], pose["y_m"] - last["y_m"])
                last = pose
                correction = record.get("correction_from_prediction_mm_mm_mrad")
                if not correction:
                    continue
                yaw = record["prediction"]["yaw_rad"]
                c, s = math.cos(yaw), math.sin(yaw)
                x, y = correction[0] / 1000.0, correction[1] / 1000.0
                bound = (record.get("correction_bound_m_rad") or [float("nan")])[0]
                out.append((length, c * x - s * y, s * x + c * y, record["timestamp_s"], bound))
            except (ValueError, KeyError, TypeError, IndexError) as error:
                sys.exit(f"correction-drift: {path}:{number}: expected an iterations.jsonl record "
                         f"with T_world_robot, prediction and timestamp_s ({error})")
    return out


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: scripts/correction-drift.py RUN_DIR [WINDOW_M]")
    window_m = float(sys.argv[2]) if len(sys.argv) == 3 else 5.0
    if not window_m > 0.0:
        sys.exit(f"correction-drift: WINDOW_M must be positive, got {sys.argv[2]}")
    path = f"{sys.argv[1]}/iterations.jsonl"
    try:
        scans = corrections(path)
    except OSError as error:
        sys.exit(f"correction-drift: {error}")
    if not scans:
        sys.exit(f"correction-drift: {path}: no localised scan with a correction from a prediction")
    window, sums = collections.deque(), []
    largest = (0.0, None, None)
    for scan in scans:
        window.append(scan)
        while scan[0] - window[0][0] > window_m:
            window.popleft()
        total = math.hypot(sum(w[1] for w in window), sum(w[2] for w in window))
        sums.append(total)
        if total > largest[0]:
            largest = (total, scan[3], scan[4])
    sums.sort()
    print(f"{sys.argv[1]}: over {window_m:g} m of path the corrections sum to at most "
          f"{largest[0]:.3f} m (t = {largest[1]:.1f} s, gate bound there {largest[2]:.3f} m); "
          f"99th percentile {sums[int(0.99 * (len(sums) - 1))]:.3f} m, 90th "
          f"{sums[int(0.9 * (len(sums) - 1))]:.3f} m, {len(sums)} scans")


if __name__ == "__main__":
    main()
