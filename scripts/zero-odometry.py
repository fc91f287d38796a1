#!/usr/bin/env python3
"""Writes a CARMEN log with every FLASER pose field set to zero (the laser's x y θ and the
odometry's): a log whose odometry was never filled in, as one converted from a hand-held laser.
Every other line is copied as it is.

  scripts/zero-odometry.py LOG.clf[.gz] > zeroed.clf
"""
import gzip
import sys


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip())
    path = sys.argv[1]
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as log:
        for line in log:
            fields = line.split()
            if len(fields) > 2 and fields[0] == "FLASER":
                beams = int(fields[1])
                for f in range(2 + beams, min(8 + beams, len(fields))):
                    fields[f] = "0"
                line = " ".join(fields) + "\n"
            sys.stdout.write(line)


if __name__ == "__main__":
    main()
