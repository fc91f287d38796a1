#!/usr/bin/env python3
"""The scales a log's odometry is off by, measured against reference poses.

  scripts/odometry-scales.py LOG.clf[.gz] REFERENCE

REFERENCE holds `t x y theta` per line (a Radish `*.truth.txt`, or a Kümmerle
`*.corrected-poses.txt`). As the session's odometry calibration does (odometry_calibration.hpp),
a step runs from one reference pose with a FLASER line at its timestamp to the first later one
the odometry reached 0.5 m or 0.25 rad from; the reference step along the odometry's direction is
regressed on the odometry step's length, and the reference turn on the odometry's, through the
origin (plain least squares). Prints the two scales: below 1, the odometry reports too much.
"""

import gzip
import math
import sys

MIN_STEP_M, MIN_STEP_RAD = 0.5, 0.25


def relative(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], 2 * math.pi)


def odometry_by_time(path):
    opener = gzip.open if path.endswith(".gz") else open
    odometry = {}
    with opener(path, "rt") as log:
        for line in log:
            f = line.split()
            if f and f[0] == "FLASER":
                rest = f[2 + int(f[1]):]
                odometry[round(float(rest[6]), 3)] = tuple(map(float, rest[3:6]))
    return odometry


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip())
    odometry = odometry_by_time(sys.argv[1])
    reference = []
    for line in open(sys.argv[2]):
        f = line.split()
        if len(f) == 4 and not line.startswith("#"):
            reference.append((round(float(f[0]), 3), tuple(map(float, f[1:4]))))
    moved = moved_sq = turned = turned_sq = 0.0
    steps = 0
    anchor = None
    for t1, p1 in reference:
        if t1 not in odometry:
            continue
        if anchor is None:
            anchor = (t1, p1)
            continue
        t0, p0 = anchor
        o, r = relative(odometry[t0], odometry[t1]), relative(p0, p1)
        length = math.hypot(o[0], o[1])
        if length < MIN_STEP_M and abs(o[2]) < MIN_STEP_RAD:
            continue
        anchor = (t1, p1)
        along = (r[0] * o[0] + r[1] * o[1]) / length if length > 0 else 0.0
        moved += length * along
        moved_sq += length * length
        turned += o[2] * r[2]
        turned_sq += o[2] * o[2]
        steps += 1
    if steps == 0 or moved_sq == 0 or turned_sq == 0:
        sys.exit("%s: no step of the reference has odometry at both ends" % sys.argv[2])
    print("%d steps: distance × %.4f, turn × %.4f" % (steps, moved / moved_sq, turned / turned_sq))


if __name__ == "__main__":
    main()
