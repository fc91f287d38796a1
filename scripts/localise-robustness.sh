#!/usr/bin/env bash
# How much `scanloc localise` depends on the map it is given: the localise benchmark's three starts
# (400 scans from 1/7, 3/7 and 5/7 of the log, no initial posture) on every ACES and Intel map the
# robustness harness's sessions wrote (scripts/robustness-sessions.sh: the default configuration and
# nine perturbations that should not matter), each scored against the session that wrote its map
# (scripts/localise_agreement.py). A start agrees when its median distance over the scans after the
# 30th is below 0.1 m and its 95th percentile below 0.3 m: the thresholds of the localise tests.
# The table also counts the scans each start stated "confirmed" more than 1 m from the session.
#   scripts/localise-robustness.sh HARNESS_OUT [OUT_DIR [--zeroed-odometry] [LOCALISE_ARGS...]]
# With --zeroed-odometry the starts are localised on copies of the logs whose pose fields are all
# zero (scripts/zero-odometry.py: a log without odometry); the maps stay the sessions'. HARNESS_OUT is a robustness harness's output (its p0/aces, p0/intel, ... runs); OUT_DIR defaults
# to build/localise-robustness. JOBS runs at a time (default: the number of processors). 60 runs,
# about 3 minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
harness=${1:?usage: scripts/localise-robustness.sh HARNESS_OUT [OUT_DIR [LOCALISE_ARGS...]]}
out=${2:-build/localise-robustness}
shift $(($# < 2 ? $# : 2))
zeroed=false
if [ "${1:-}" = --zeroed-odometry ]; then
  zeroed=true
  shift
fi
source scripts/public-logs.sh localise-robustness
mkdir -p "$out"
logs_dir=$datasets log_suffix=.clf.gz
if "$zeroed"; then
  logs_dir=$out/zeroed-logs log_suffix=.clf
  mkdir -p "$logs_dir"
  for log in aces intel; do
    python3 scripts/zero-odometry.py "$datasets/$log.clf.gz" > "$logs_dir/$log.clf"
  done
fi
: > "$out/jobs"
: > "$out/localise-args"  # LOCALISE_ARGS, NUL-terminated, read by every job
if [ $# -gt 0 ]; then printf '%s\0' "$@" > "$out/localise-args"; fi
for map in "$harness"/p*/aces "$harness"/p*/intel; do
  [ -f "$map/summary.json" ] || continue
  log=$(basename "$map")
  scans=$(python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['iterations'])" \
    "$map/summary.json")
  for k in 1 3 5; do
    printf '%s\0%s\0%s\0' "$map" "$log" "$((scans * k / 7))" >> "$out/jobs"
  done
done
[ -s "$out/jobs" ] || { echo "localise-robustness: no ACES or Intel runs in $harness" >&2; exit 1; }
export scanloc out logs_dir log_suffix
xargs -0 -n 3 -P "${JOBS:-$(nproc)}" bash -c '
  map=$0 log=$1 start=$2
  mapfile -d "" args < "$out/localise-args"
  name=$(basename "$(dirname "$map")")-$log-$start
  "$scanloc" localise --point-map "$map/map.pcd" --log "$logs_dir/$log$log_suffix" \
    --skip-scans "$start" --max-scans 400 --out "$out/$name" --force --quiet ${args[@]+"${args[@]}"} \
    > "$out/$name.txt" 2>&1 || true
  python3 scripts/localise_agreement.py "$map" "$out/$name" > "$out/$name.json"
'  < "$out/jobs"
python3 - "$out" <<'PY'
import glob, json, os, sys
out = sys.argv[1]
print("| run | first confirmed: scan | median [m] | p95 [m] | max [m] | scans confirmed > 1 m off "
      "| agrees |")
print("|---|---|---|---|---|---|---|")
fmt = lambda v, f="%.3f": "—" if v is None else (f % v if v != float("inf") else "∞")
failed, wrong = [], []
runs = sorted(glob.glob(f"{out}/*.json"))
for path in runs:
    name = os.path.basename(path)[:-5]
    r = json.load(open(path))
    agrees = r["median_m"] < 0.1 and r["p95_m"] < 0.3
    if not agrees:
        failed.append(name)
    if r["confirmed_far_scans"]:
        wrong.append(name)
    print(f"| {name} | {fmt(r['first_confirmed_scan'], '%d')} | {fmt(r['median_m'])} "
          f"| {fmt(r['p95_m'])} | {fmt(r['max_m'])} | {r['confirmed_far_scans']} "
          f"| {'yes' if agrees else '**no**'} |")
print(f"\n{len(runs) - len(failed)} of {len(runs)} starts agree with the session that wrote the map"
      + (f"; not: {', '.join(failed)}" if failed else ""))
print(f"{len(wrong)} of {len(runs)} starts confirmed a place more than 1 m off"
      + (f": {', '.join(wrong)}" if wrong else ""))
PY
