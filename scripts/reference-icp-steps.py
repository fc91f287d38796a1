#!/usr/bin/env python3
"""Where a log's own poses and its scans disagree: each scan fitted on an earlier one by ICP.

    scripts/reference-icp-steps.py LOG.clf[.gz] [--gap N] [--above DEG]

Reads the FLASER lines of a CARMEN log (a Radish `NAME.exact.clf.gz` carries the reference poses of
`truth.txt`), starts each scan at its logged posture and fits it by point-to-line ICP on the scan N
before (default 1), placed at its logged posture. The heading the fit moves the scan by is where
the scans' own geometry disagrees with the logged step. Prints the scans it moves by more than DEG
(default 1.2°) and the rms and median over all fits. Shares nothing with scanloc but the log: an
independent witness for "the session and the reference disagree here" (docs/BENCHMARKS.md).
Pure Python; a few seconds per hundred scans.
"""
import argparse
import gzip
import math
import statistics

CELL_M = 0.3        # the line lookup grid, and the farthest a point pairs with a line
MAX_RESIDUAL_M = 0.1
NEIGHBOUR_M = 0.3   # beams farther apart than this are across a depth jump: no line between them


def read_scans(path):
    """(pose, points) of each FLASER line. CARMEN's bearings: 180° from −90°, in steps of π/n
    (π/(n − 1) for an odd n)."""
    opener = gzip.open if path.endswith(".gz") else open
    scans = []
    with opener(path, "rt") as log:
        for number, line in enumerate(log, start=1):
            fields = line.split()
            if not fields or fields[0] != "FLASER":
                continue
            try:
                n = int(fields[1])
                ranges = [float(r) for r in fields[2:2 + n]]
                pose = tuple(float(v) for v in fields[2 + n:5 + n])
                if len(ranges) != n or len(pose) != 3:
                    raise ValueError("too few fields")
            except (IndexError, ValueError) as error:
                raise SystemExit(f"reference-icp-steps: {path}:{number}: expected FLASER n, n "
                                 f"ranges and x y theta ({error})")
            step = math.pi / (n if n % 2 == 0 else n - 1)
            bearings = [-math.pi / 2 + k * step for k in range(n)]
            points = [(k, r * math.cos(bearings[k]), r * math.sin(bearings[k]))
                      for k, r in enumerate(ranges) if 0.05 < r < 30.0]
            scans.append((pose, points))
    return scans


def to_world(pose, points):
    x, y, theta = pose
    c, s = math.cos(theta), math.sin(theta)
    return [(k, x + c * px - s * py, y + s * px + c * py) for k, px, py in points]


def lines_of(pose, points):
    """Each point with a normal from its neighbouring beams, and a grid to look them up."""
    world = to_world(pose, points)
    by_beam = {k: (x, y) for k, x, y in world}
    lines, grid = [], {}
    for k, x, y in world:
        near = [by_beam[j] for j in (k - 1, k + 1)
                if j in by_beam and math.hypot(by_beam[j][0] - x, by_beam[j][1] - y) < NEIGHBOUR_M]
        if not near:
            continue
        a, b = (near[0], near[1]) if len(near) == 2 else ((x, y), near[0])
        tx, ty = b[0] - a[0], b[1] - a[1]
        length = math.hypot(tx, ty)
        if length < 1e-6:
            continue
        lines.append((x, y, -ty / length, tx / length))
        grid.setdefault((math.floor(x / CELL_M), math.floor(y / CELL_M)), []).append(len(lines) - 1)
    return lines, grid


def nearest_line(lines, grid, x, y):
    gx, gy = math.floor(x / CELL_M), math.floor(y / CELL_M)
    best, best_d2 = None, CELL_M * CELL_M
    for a in (-1, 0, 1):
        for b in (-1, 0, 1):
            for j in grid.get((gx + a, gy + b), ()):
                d2 = (lines[j][0] - x) ** 2 + (lines[j][1] - y) ** 2
                if d2 < best_d2:
                    best, best_d2 = lines[j], d2
    return best


def solve3(h, g):
    """h d = −g by Gaussian elimination with partial pivoting; None when singular."""
    a = [h[i][:] + [-g[i]] for i in range(3)]
    for i in range(3):
        p = max(range(i, 3), key=lambda r: abs(a[r][i]))
        a[i], a[p] = a[p], a[i]
        if abs(a[i][i]) < 1e-12:
            return None
        for r in range(3):
            if r != i:
                f = a[r][i] / a[i][i]
                a[r] = [a[r][c] - f * a[i][c] for c in range(4)]
    return [a[i][3] / a[i][i] for i in range(3)]


def fit(reference, scan, iterations=20):
    """The scan's posture fitted on the reference scan's lines: (posture, pairs), or None."""
    lines, grid = lines_of(*reference)
    pose, points = list(scan[0]), scan[1]
    pairs = 0
    for _ in range(iterations):
        c, s = math.cos(pose[2]), math.sin(pose[2])
        h, g, pairs = [[0.0] * 3 for _ in range(3)], [0.0] * 3, 0
        for _, px, py in points:
            x, y = pose[0] + c * px - s * py, pose[1] + s * px + c * py
            line = nearest_line(lines, grid, x, y)
            if line is None:
                continue
            r = line[2] * (x - line[0]) + line[3] * (y - line[1])
            if abs(r) > MAX_RESIDUAL_M:
                continue
            j = (line[2], line[3], line[2] * (-s * px - c * py) + line[3] * (c * px - s * py))
            for u in range(3):
                g[u] += j[u] * r
                for v in range(3):
                    h[u][v] += j[u] * j[v]
            pairs += 1
        step = solve3(h, g) if pairs >= 20 else None
        if step is None:
            return None
        pose = [pose[0] + step[0], pose[1] + step[1], pose[2] + step[2]]
        if abs(step[2]) < 1e-6 and math.hypot(step[0], step[1]) < 1e-5:
            break
    return pose, pairs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log")
    parser.add_argument("--gap", type=int, default=1, help="fit each scan on the one N before")
    parser.add_argument("--above", type=float, default=1.2, help="print fits turning more, deg")
    args = parser.parse_args()
    try:
        scans = read_scans(args.log)
    except OSError as error:
        raise SystemExit(f"reference-icp-steps: cannot read {args.log}: {error}")
    turns = []
    for i in range(args.gap, len(scans)):
        fitted = fit(scans[i - args.gap], scans[i])
        if fitted is None:
            continue
        turn = math.degrees(math.remainder(fitted[0][2] - scans[i][0][2], 2 * math.pi))
        turns.append(turn)
        if abs(turn) > args.above:
            print(f"scan {i} on scan {i - args.gap}: turned {turn:+.2f}° off the logged step "
                  f"({fitted[1]} pairs)")
    if not turns:
        raise SystemExit(f"reference-icp-steps: no scan of {args.log} could be fitted")
    rms = math.sqrt(sum(t * t for t in turns) / len(turns))
    print(f"{len(turns)} fits: rms {rms:.3f}°, median |turn| "
          f"{statistics.median(abs(t) for t in turns):.3f}°")


if __name__ == "__main__":
    main()
