#!/usr/bin/env python3
"""Scan-to-scan errors of a trajectory against reference poses.

    scripts/trajectory-steps.py TRAJECTORY.tum REFERENCE [WORST]

REFERENCE holds `t x y theta` per line (a Radish truth.txt, a corrected-poses file). For every
pair of consecutive postures of TRAJECTORY whose timestamps (to the millisecond) are in REFERENCE,
the error of their relative posture against the reference's: the median and 90th percentile of
the translation (m) and of the heading (rad), then the WORST (default 10) steps.
"""
import math
import sys


def load_tum(path):
    poses = {}
    for line in open(path):
        fields = line.split()
        if len(fields) < 8 or line.startswith("#"):
            continue
        yaw = 2.0 * math.atan2(float(fields[6]), float(fields[7]))
        poses[round(float(fields[0]), 3)] = (float(fields[1]), float(fields[2]), yaw)
    return poses


def load_reference(path):
    poses = {}
    for line in open(path):
        fields = line.split()
        if len(fields) >= 4 and not line.startswith("#"):
            poses[round(float(fields[0]), 3)] = tuple(map(float, fields[1:4]))
    return poses


def wrap(angle):
    return math.atan2(math.sin(angle), math.cos(angle))


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return (c * dx + s * dy, -s * dx + c * dy, wrap(b[2] - a[2]))


def quantile(values, q):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * len(ordered)))]


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    trajectory, reference = load_tum(sys.argv[1]), load_reference(sys.argv[2])
    worst = int(sys.argv[3]) if len(sys.argv) == 4 else 10
    times = sorted(t for t in trajectory if t in reference)
    if len(times) < 2:
        sys.exit(f"trajectory-steps: fewer than two postures of {sys.argv[1]} are in {sys.argv[2]}")
    steps = []
    for i in range(1, len(times)):
        got = between(trajectory[times[i - 1]], trajectory[times[i]])
        want = between(reference[times[i - 1]], reference[times[i]])
        steps.append((math.hypot(got[0] - want[0], got[1] - want[1]), wrap(got[2] - want[2]), i,
                      times[i]))
    translation = [s[0] for s in steps]
    heading = [abs(s[1]) for s in steps]
    print(f"{len(steps)} steps ({len(trajectory)} postures, {len(reference)} reference poses)")
    print(f"translation: median {quantile(translation, 0.5):.4f} m, 90 % {quantile(translation, 0.9):.4f} m, "
          f"max {max(translation):.4f} m")
    print(f"heading: median {quantile(heading, 0.5):.5f} rad, 90 % {quantile(heading, 0.9):.5f} rad, "
          f"max {max(heading):.5f} rad")
    for error_m, error_rad, index, t in sorted(steps, reverse=True)[:worst]:
        print(f"  step {index:5d} (t {t:.3f})  {error_m:.3f} m  {error_rad:+.4f} rad")


if __name__ == "__main__":
    main()
