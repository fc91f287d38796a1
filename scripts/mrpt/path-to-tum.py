#!/usr/bin/env python3
"""Writes icp-slam's estimated path as a TUM trajectory on the log's own timestamps, for
`scanloc evaluate` (scripts/mrpt/compare-icp-slam.sh).

icp-slam logs one pose per observation ("step x y phi"); every scan of the converted rawlog is an
odometry observation followed by the scan itself (MRPT's carmen2rawlog), so scan k's pose is the one
logged after step 2k + 1, ICP applied. STAMPS holds the scans' timestamps in order
(scripts/mrpt/carmen-to-robotlaser.py).
  path-to-tum.py STAMPS log_estimated_path.txt OUT.tum
"""
import math
import sys


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    stamps = [line.strip() for line in open(sys.argv[1]) if line.strip()]
    rows = [line.split() for line in open(sys.argv[2]) if line.strip()]
    if len(rows) != 2 * len(stamps):
        sys.exit(f"path-to-tum: {sys.argv[2]}: {len(rows)} poses, expected two per scan "
                 f"({2 * len(stamps)} for the {len(stamps)} scans of {sys.argv[1]})")
    with open(sys.argv[3], "w") as out:
        for k, stamp in enumerate(stamps):
            step, x, y, phi = rows[2 * k + 1]
            if int(step) != 2 * k + 1:
                sys.exit(f"path-to-tum: {sys.argv[2]}: line {2 * k + 2}: step {step}, expected {2 * k + 1}")
            half = float(phi) / 2
            out.write(f"{stamp} {x} {y} 0 0 0 {math.sin(half):.9f} {math.cos(half):.9f}\n")


if __name__ == "__main__":
    main()
