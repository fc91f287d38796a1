#!/usr/bin/env python3
"""Rewrites a CARMEN log's FLASER lines as ROBOTLASER1 lines that spell out the scan geometry, for
MRPT's carmen2rawlog (scripts/mrpt/compare-icp-slam.sh).

Why: carmen2rawlog gives a FLASER scan an aperture of n × laser_front_laser_resolution (0.5° unless
a PARAM says otherwise: 90° for 180 beams) and spreads the beams over it end to end, while a
Freiburg FLASER scan of n beams starts at -90° and steps by 180°/n (even n) or 180°/(n - 1) (odd n),
as scanloc reads it. A ROBOTLASER1 line states the aperture; MRPT spreads its beams symmetrically
about the sensor's heading, so the sensor is turned by half the asymmetry.

Timestamps: MRPT 2.5's carmen2rawlog adds a line's timestamp to the time it runs as if it were in
picoseconds. Measured: stamps in seconds (70.2899, 70.410399, ... 1435.81 on ACES) all came out at
the same microsecond, and icp-slam then never corrects a pose; the same stamps written in
picoseconds come out 0.120499 s apart and span the log's 1,365.52 s. So each line carries its time
since the first scan in picoseconds, and OUT.stamps keeps the log's own timestamp of every scan, in
order, to which the estimated path is matched back (scripts/mrpt/path-to-tum.py).
  carmen-to-robotlaser.py LOG[.gz] OUT
"""
import gzip
import math
import sys

MAX_RANGE_M = 81.0  # carmen2rawlog's own FLASER default: longer ranges are no return


def increment_rad(n):
    return math.pi / n if n % 2 == 0 else math.pi / (n - 1)


def convert(lines, out, stamps):
    offset_m = 0.0
    start = None
    for number, line in enumerate(lines, 1):
        f = line.split()
        if len(f) >= 3 and f[0] == "PARAM" and f[1] == "robot_frontlaser_offset":
            offset_m = float(f[2])
        if not f or f[0] != "FLASER":
            continue
        n = int(f[1])
        if len(f) < n + 11:
            sys.exit(f"carmen-to-robotlaser: line {number}: FLASER with {n} beams needs {n + 11} fields")
        ranges = f[2:2 + n]
        ox, oy, oth = (float(v) for v in f[5 + n:8 + n])
        stamp = f[8 + n]
        start = float(stamp) if start is None else start
        picoseconds = round((float(stamp) - start) * 1e12)
        step = increment_rad(n)
        aperture = step * (n - 1)
        first = -math.pi / 2
        turn = first + aperture / 2  # the symmetric spread's centre, relative to the robot's heading
        lx = ox + offset_m * math.cos(oth)
        ly = oy + offset_m * math.sin(oth)
        lth = oth + turn
        out.write(f"ROBOTLASER1 0 {first:.9f} {aperture:.9f} {step:.9f} {MAX_RANGE_M} 0.01 0 {n} "
                  f"{' '.join(ranges)} 0 {lx:.6f} {ly:.6f} {lth:.9f} {ox:.6f} {oy:.6f} {oth:.9f} "
                  f"0 0 0 0 0 {picoseconds} nohost {picoseconds}\n")
        stamps.write(stamp + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source = sys.argv[1]
    opener = gzip.open if source.endswith(".gz") else open
    with opener(source, "rt") as lines, open(sys.argv[2], "w") as out, \
            open(sys.argv[2] + ".stamps", "w") as stamps:
        convert(lines, out, stamps)


if __name__ == "__main__":
    main()
