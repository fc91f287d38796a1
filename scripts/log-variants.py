#!/usr/bin/env python3
"""Derives, from a benchmark log with real odometry, a variant as another robot might have logged it.

  scripts/log-variants.py sparse LOG.clf.gz REFERENCE OUT.clf OUT.relations
  scripts/log-variants.py short-range LOG.clf.gz OUT.clf [RANGE_M]
  scripts/log-variants.py range-noise LOG.clf.gz OUT.clf [SIGMA_M [SEED]]
  scripts/log-variants.py narrow LOG.clf.gz OUT.clf [FOV_DEG]
  scripts/log-variants.py odometry-scale LOG.clf.gz OUT.clf [DISTANCE_SCALE [TURN_SCALE]]

- sparse: only the scans with a reference pose, one after every 0.8 m or 0.3 rad of the log's
  odometry (a log kept as the Radish logs are, a scan every metre or so). Every other line (ODOM,
  PARAM) is kept. The relations are built from REFERENCE (`t x y theta`, the corrected poses) as
  the Radish relations are: each kept scan to the kept scans about 1 s and 10 s later, and 1,500
  random pairs (seed 1).
- short-range: every FLASER reading beyond RANGE_M (default 5.6, a Hokuyo URG-04LX) becomes
  RANGE_M, the no-return value of such a laser. The log's own relations still apply.
- range-noise: every FLASER reading below the log's largest (its no-return value) gains Gaussian
  noise of SIGMA_M (default 0.03, a laser four to six times noisier than the logs' SICKs; SEED, 1),
  kept at 0.01 m or more. The log's own relations still apply.
- narrow: every FLASER reading more than FOV_DEG/2 (default 120/2) from straight ahead becomes the
  log's no-return value (its largest reading): a laser that sees less to the sides (a narrower
  scanner, or one half hidden by the robot's own body). The log's own relations still apply.
- odometry-scale: the odometry as a miscalibrated robot would report it: every step it logs
  (ODOM lines and FLASER's odometry, in the order of the log) driven DISTANCE_SCALE times as far
  (default 1.05, a wheel radius 5 % too large) and turned TURN_SCALE times as much (default 1.03,
  a wheelbase 3 % too short), integrated again from the first pose. FLASER's laser pose keeps its
  offset from the odometry. The log's own relations still apply.
"""
import bisect
import gzip
import math
import random
import sys

KEEP_M, KEEP_RAD = 0.8, 0.3


def lines(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt") as log:
        yield from log


def flaser(fields):
    """(beam count, the fields after the ranges) of a FLASER line's fields."""
    n = int(fields[1])
    return n, fields[2 + n:]


def read_reference(path):
    poses = {}
    for line in open(path):
        f = line.split()
        if len(f) == 4:
            poses[round(float(f[0]), 6)] = tuple(map(float, f[1:]))
    return poses


def relative(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return c * dx + s * dy, -s * dx + c * dy, math.remainder(b[2] - a[2], 2 * math.pi)


def sparse(log, reference_path, out_log, out_relations):
    reference = read_reference(reference_path)
    kept, last = [], None
    with open(out_log, "w") as out:
        for line in lines(log):
            f = line.split()
            if f and f[0] == "FLASER":
                _, rest = flaser(f)
                t = round(float(rest[6]), 6)
                odometry = tuple(map(float, rest[3:6]))
                if t not in reference:
                    continue
                if last is not None:
                    step = relative(last, odometry)
                    if math.hypot(step[0], step[1]) < KEEP_M and abs(step[2]) < KEEP_RAD:
                        continue
                last = odometry
                kept.append(t)
            out.write(line)
    pairs = []
    for i, t in enumerate(kept):
        for dt in (1.0, 10.0):
            j = bisect.bisect_left(kept, t + dt)
            if i < j < len(kept):
                pairs.append((t, kept[j]))
    rng = random.Random(1)
    for _ in range(1500):
        i, j = sorted(rng.sample(range(len(kept)), 2))
        pairs.append((kept[i], kept[j]))
    with open(out_relations, "w") as out:
        for a, b in pairs:
            x, y, yaw = relative(reference[a], reference[b])
            out.write("%.6f %.6f %.6f %.6f 0 0 0 %.6f\n" % (a, b, x, y, yaw))
    print("%s: %d scans kept, %d relations" % (out_log, len(kept), len(pairs)), file=sys.stderr)


def short_range(log, out_log, range_m):
    with open(out_log, "w") as out:
        for line in lines(log):
            f = line.split()
            if f and f[0] == "FLASER":
                n, rest = flaser(f)
                ranges = ["%.3f" % min(float(r), range_m) for r in f[2:2 + n]]
                line = " ".join(f[:2] + ranges + rest) + "\n"
            out.write(line)


def largest_reading(log):
    """The log's no-return value: its largest FLASER reading."""
    no_return = 0.0
    for line in lines(log):
        f = line.split()
        if f and f[0] == "FLASER":
            n, _ = flaser(f)
            no_return = max([no_return] + [float(r) for r in f[2:2 + n]])
    return no_return


def range_noise(log, out_log, sigma_m, seed):
    no_return = largest_reading(log)
    rng = random.Random(seed)
    with open(out_log, "w") as out:
        for line in lines(log):
            f = line.split()
            if f and f[0] == "FLASER":
                n, rest = flaser(f)
                ranges = [float(r) for r in f[2:2 + n]]
                noisy = [r if r >= no_return else max(0.01, r + rng.gauss(0.0, sigma_m)) for r in ranges]
                line = " ".join(f[:2] + ["%.3f" % r for r in noisy] + rest) + "\n"
            out.write(line)


def narrow(log, out_log, fov_deg):
    no_return = largest_reading(log)
    with open(out_log, "w") as out:
        for line in lines(log):
            f = line.split()
            if f and f[0] == "FLASER":
                n, rest = flaser(f)
                # A FLASER scan spans 180°, beam 0 on the right.
                kept = [abs((k + 0.5) / n - 0.5) * 180.0 <= fov_deg / 2 for k in range(n)]
                ranges = [r if keep else "%.3f" % no_return for r, keep in zip(f[2:2 + n], kept)]
                line = " ".join(f[:2] + ranges + rest) + "\n"
            out.write(line)


def compose(a, d):
    c, s = math.cos(a[2]), math.sin(a[2])
    return a[0] + c * d[0] - s * d[1], a[1] + s * d[0] + c * d[1], a[2] + d[2]


class ScaledOdometry:
    """The log's odometry poses, one after another, re-integrated with scaled steps."""

    def __init__(self, distance_scale, turn_scale):
        self.distance_scale, self.turn_scale = distance_scale, turn_scale
        self.last = self.scaled = None

    def __call__(self, pose):
        if self.last is None:
            self.last = self.scaled = pose
            return pose
        dx, dy, dyaw = relative(self.last, pose)
        step = (self.distance_scale * dx, self.distance_scale * dy, self.turn_scale * dyaw)
        self.last, self.scaled = pose, compose(self.scaled, step)
        return self.scaled


def odometry_scale(log, out_log, distance_scale, turn_scale):
    scaled = ScaledOdometry(distance_scale, turn_scale)
    pose_text = lambda p: ["%.6f" % p[0], "%.6f" % p[1], "%.6f" % math.remainder(p[2], 2 * math.pi)]
    with open(out_log, "w") as out:
        for line in lines(log):
            f = line.split()
            if f and f[0] == "ODOM" and len(f) >= 4:
                line = " ".join([f[0]] + pose_text(scaled(tuple(map(float, f[1:4])))) + f[4:]) + "\n"
            elif f and f[0] == "FLASER":
                n, rest = flaser(f)
                laser, odometry = tuple(map(float, rest[0:3])), tuple(map(float, rest[3:6]))
                new_odometry = scaled(odometry)
                new_laser = compose(new_odometry, relative(odometry, laser))
                line = " ".join(f[:2 + n] + pose_text(new_laser) + pose_text(new_odometry) +
                                rest[6:]) + "\n"
            out.write(line)


def main():
    if len(sys.argv) >= 6 and sys.argv[1] == "sparse":
        sparse(*sys.argv[2:6])
    elif len(sys.argv) in (4, 5) and sys.argv[1] == "short-range":
        short_range(sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) == 5 else 5.6)
    elif len(sys.argv) in (4, 5, 6) and sys.argv[1] == "range-noise":
        range_noise(sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) >= 5 else 0.03,
                    int(sys.argv[5]) if len(sys.argv) == 6 else 1)
    elif len(sys.argv) in (4, 5) and sys.argv[1] == "narrow":
        narrow(sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) == 5 else 120.0)
    elif len(sys.argv) in (4, 5, 6) and sys.argv[1] == "odometry-scale":
        odometry_scale(sys.argv[2], sys.argv[3], float(sys.argv[4]) if len(sys.argv) >= 5 else 1.05,
                       float(sys.argv[5]) if len(sys.argv) == 6 else 1.03)
    else:
        sys.exit(__doc__.strip())


if __name__ == "__main__":
    main()
