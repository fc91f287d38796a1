#!/usr/bin/env python3
"""Splices two stretches of a CARMEN log (FLASER/ODOM) into one, as if the robot had been carried
from the end of the first to the start of the second: the second stretch's odometry is moved
rigidly to go on from where the first stretch's ended (the odometry never saw the carry), its
timestamps are kept (they jump forward at the splice, so that both stretches still match the
original log's trajectory by time).

  scripts/splice-carmen.py LOG.clf[.gz] FIRST_START SECOND_START COUNT > spliced.clf

Stretches are counted in FLASER scans; SECOND_START must be at least FIRST_START + COUNT.
"""
import gzip
import math
import sys


def compose(a, b):
    x, y, t = a
    return (x + math.cos(t) * b[0] - math.sin(t) * b[1], y + math.sin(t) * b[0] + math.cos(t) * b[1],
            t + b[2])


def inverse(a):
    x, y, t = a
    c, s = math.cos(t), math.sin(t)
    return (-c * x - s * y, s * x - c * y, -t)


def poses(fields):
    """Indices of the (x, y, theta) triples in an FLASER or ODOM line."""
    if fields[0] == "ODOM":
        return [1]
    n = int(fields[1])
    return [2 + n, 5 + n]  # the laser's pose, then the robot's odometry


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    path, first, second, count = sys.argv[1], *map(int, sys.argv[2:])
    if second < first + count:
        sys.exit("splice-carmen: SECOND_START must be at least FIRST_START + COUNT")
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as log:
        lines = [line.rstrip("\n") for line in log]
    scan = -1
    header, stretch = [], {0: [], 1: []}
    for line in lines:
        fields = line.split()
        if not fields:
            continue
        if fields[0] not in ("FLASER", "ODOM"):
            if scan < 0:
                header.append(line)
            continue
        if fields[0] == "FLASER":
            scan += 1
        part = 0 if first <= scan < first + count else 1 if second <= scan < second + count else None
        if part is not None:
            stretch[part].append(fields)
    if len(stretch[0]) == 0 or len(stretch[1]) == 0:
        sys.exit("splice-carmen: a stretch is empty (the log has %d scans)" % (scan + 1))
    last_first = next(f for f in reversed(stretch[0]) if f[0] == "FLASER")
    first_second = next(f for f in stretch[1] if f[0] == "FLASER")
    odom = lambda f: tuple(float(v) for v in f[poses(f)[-1]:poses(f)[-1] + 3])
    carry = compose(odom(last_first), inverse(odom(first_second)))
    out = sys.stdout
    for line in header:
        out.write(line + "\n")
    for fields in stretch[0]:
        out.write(" ".join(fields) + "\n")
    for fields in stretch[1]:
        for i in poses(fields):
            x, y, t = compose(carry, tuple(float(v) for v in fields[i:i + 3]))
            fields[i:i + 3] = ["%.6f" % x, "%.6f" % y, "%.6f" % math.atan2(math.sin(t), math.cos(t))]
        out.write(" ".join(fields) + "\n")


if __name__ == "__main__":
    main()
