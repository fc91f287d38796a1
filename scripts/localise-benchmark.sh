#!/usr/bin/env bash
# The localise issue's benchmark: on ACES and Intel, a default mapping session builds the map; then
# `scanloc localise` runs with no initial posture on 400-scan stretches cut from three places of
# each log (at 1/7, 3/7 and 5/7 of its scans, chosen by position, not by result), and on a log
# spliced from two 200-scan stretches (a robot carried elsewhere). Prints the table of
# docs/BENCHMARKS.md: the agreement with the session's postures after the first 30 scans, scans and
# log seconds to the first confirmed posture, the global searches' cost, and CPU time.
#   scripts/localise-benchmark.sh [OUT_DIR [--zeroed-odometry] [LOCALISE_ARGS...]]
# (default: build/localise). With --zeroed-odometry the stretches and splices are localised on copies
# of the logs whose pose fields are all zero (scripts/zero-odometry.py: a log without odometry),
# and Fr079 joins ACES and Intel; the maps stay the sessions' on the logs as published.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/localise}
shift || true
zeroed=false
if [ "${1:-}" = --zeroed-odometry ]; then
  zeroed=true
  shift
fi
source scripts/public-logs.sh localise-benchmark
mkdir -p "$out"
cpu() {  # user + system seconds of a command, into $out/$1.cpu
  local name=$1
  shift
  /usr/bin/time -f "%U %S" -o "$out/$name.cpu" "$@"
}
logs="aces intel"
"$zeroed" && logs="aces intel fr079"
for log in $logs; do
  [ -f "$out/$log-map/summary.json" ] ||
    "$scanloc" session --log "$datasets/$log.clf.gz" --out "$out/$log-map" --force --quiet \
      > /dev/null
  source_log="$datasets/$log.clf.gz"
  if "$zeroed"; then
    source_log="$out/$log.zeroed.clf"
    python3 scripts/zero-odometry.py "$datasets/$log.clf.gz" > "$source_log"
  fi
  scans=$(python3 -c "import json; print(json.load(open('$out/$log-map/summary.json'))['iterations'])")
  for k in 1 3 5; do
    start=$((scans * k / 7))
    echo "localise-benchmark: $log from scan $start" >&2
    cpu "$log-$start" "$scanloc" localise --point-map "$out/$log-map/map.pcd" \
      --log "$source_log" --skip-scans "$start" --max-scans 400 \
      --out "$out/$log-$start" --force --quiet "$@" > "$out/$log-$start.txt" 2>&1 || true
    python3 scripts/localise_agreement.py "$out/$log-map" "$out/$log-$start" \
      > "$out/$log-$start.json"
  done
  first=$((scans / 7)) second=$((scans * 4 / 7))
  python3 scripts/splice-carmen.py "$source_log" "$first" "$second" 200 \
    > "$out/$log-splice.clf"
  echo "localise-benchmark: $log spliced $first+200 / $second+200" >&2
  cpu "$log-splice" "$scanloc" localise --point-map "$out/$log-map/map.pcd" \
    --log "$out/$log-splice.clf" --out "$out/$log-splice" --force --quiet "$@" \
    > "$out/$log-splice.txt" 2>&1 || true
  python3 scripts/localise_agreement.py "$out/$log-map" "$out/$log-splice" --splice-at 200 \
    > "$out/$log-splice.json"
done
python3 - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
print("| run | first confirmed: scan (s) | median [m] | p95 [m] | max [m] | global searches "
      "| search [s] mean / max | lost | re-confirmed after splice [scans] | CPU [s] |")
print("|---|---|---|---|---|---|---|---|---|---|")
fmt = lambda v, f="%.3f": "—" if v is None else (f % v if v != float("inf") else "∞")
for path in sorted(glob.glob(f"{out}/*.json")):
    name = os.path.basename(path)[:-5]
    r = json.load(open(path))
    user, system = (float(v) for v in open(f"{out}/{name}.cpu").read().split()[-2:])
    print(f"| {name} | {fmt(r['first_confirmed_scan'], '%d')} ({fmt(r['seconds_to_confirm'], '%.1f')}) "
          f"| {fmt(r['median_m'])} | {fmt(r['p95_m'])} | {fmt(r['max_m'])} | {r['global_searches']} "
          f"| {fmt(r['search_wall_s_mean'], '%.2f')} / {fmt(r['search_wall_s_max'], '%.2f')} "
          f"| {r['lost']} | {fmt(r['scans_to_reconfirm_after_splice'], '%d')} | {user + system:.1f} |")
PY
