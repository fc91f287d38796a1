#!/usr/bin/env bash
# How a session's peak memory and CPU grow with the path driven: each Kümmerle log (Intel, ACES,
# Fr079) cut after a quarter, a half, three quarters and all of its scans (--max-scans), with
# loop closure off and on. Prints, per run, the path (from trajectory.tum), peak resident memory,
# CPU (user + system) and the loop closures, then per log and setting the memory growth in MB per
# km (least squares over the four cuts) and the CPU per scan over the first and the last quarter.
#   scripts/memory-growth.sh [OUT_DIR [SESSION_ARGS...]]   (default: build/memory-growth; logs in
#   $SCANLOC_DATASETS). SESSION_ARGS go to every run.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/memory-growth}
shift || true
extra=("$@")
source scripts/public-logs.sh memory-growth
mkdir -p "$out"
# The whole log first: its summary gives the number of scans the cuts are fractions of.
for log in intel aces fr079; do
  for closure in false true; do
    for quarter in 4 1 2 3; do
      name="$log-lc-$closure-q$quarter"
      echo "memory-growth: $name" >&2
      cut=0
      [ "$quarter" = 4 ] || cut=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['iterations'] * $quarter // 4)" "$out/$log-lc-$closure-q4/summary.json")
      /usr/bin/time -f "%U %S" -o "$out/$name.cpu" \
        "$scanloc" session --log "$datasets/$log.clf.gz" --out "$out/$name" --force --quiet \
        --max-scans "$cut" --set loop_closure.enabled=$closure "${extra[@]}" \
        > "$out/$name.session.txt"
    done
  done
done
python3 - "$out" <<'PY'
import json, math, sys
out = sys.argv[1]
def path_km(run):
    xy = [tuple(map(float, l.split()[1:3])) for l in open(f"{run}/trajectory.tum") if l[0] != "#"]
    return sum(math.dist(a, b) for a, b in zip(xy, xy[1:])) / 1000.0
def slope(xs, ys):
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
print("| log | loop closure | scans | path [km] | peak memory [MB] | CPU [s] | closures accepted / tried |")
print("|---|---|---|---|---|---|---|")
growth = []
for log in ["intel", "aces", "fr079"]:
    for closure in ["false", "true"]:
        km, mb, cpu, scans = [], [], [], []
        for q in range(1, 5):
            run = f"{out}/{log}-lc-{closure}-q{q}"
            s = json.load(open(f"{run}/summary.json"))
            lc = s.get("loop_closure") or {}
            km.append(path_km(run)); mb.append(s["peak_resident_mb"]); scans.append(s["iterations"])
            cpu.append(sum(map(float, open(f"{run}.cpu").read().split())))
            closures = f"{lc['closures_accepted']} / {lc['closures_tried']}" if lc else "–"
            print(f"| {log} | {'on' if closure == 'true' else 'off'} | {scans[-1]} | {km[-1]:.3f} "
                  f"| {mb[-1]:.1f} | {cpu[-1]:.1f} | {closures} |")
        first = 1000.0 * cpu[0] / scans[0]
        last = 1000.0 * (cpu[3] - cpu[2]) / (scans[3] - scans[2])
        growth.append((log, closure, slope(km, mb), first, last))
print()
print("| log | loop closure | memory growth [MB/km] | CPU per scan, first quarter [ms] | last quarter [ms] |")
print("|---|---|---|---|---|")
for log, closure, mb_per_km, first, last in growth:
    print(f"| {log} | {'on' if closure == 'true' else 'off'} | {mb_per_km:.1f} | {first:.2f} | {last:.2f} |")
PY
