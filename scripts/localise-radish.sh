#!/usr/bin/env bash
# `scanloc localise` on buildings the localise benchmark does not cover: for each of the five
# Radish logs with noisy odometry, a default session builds the map; then 100-scan stretches from
# 1/7, 3/7 and 5/7 of the log are localised with no initial posture and scored against the
# session's postures after their first 10 scans (scripts/localise_agreement.py --settle 10; the
# logs are sparse). Prints one line per stretch.
#   scripts/localise-radish.sh [OUT_DIR [LOCALISE_ARGS...]]  (default: build/localise-radish)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/localise-radish}
shift || true
source scripts/public-logs.sh localise-radish
echo "| stretch | first confirmed scan | median / p95 / max [m] | global searches |"
echo "|---|---|---|---|"
for log in seattle orebro fhw edmonton acapulco; do
  radish="$datasets/radish/$log.noisy.clf.gz"
  [ -f "$out/$log-map/summary.json" ] ||
    "$scanloc" session --log "$radish" --out "$out/$log-map" --force --quiet > /dev/null
  scans=$(python3 -c "import json; print(json.load(open('$out/$log-map/summary.json'))['iterations'])")
  for k in 1 3 5; do
    start=$((scans * k / 7))
    "$scanloc" localise --point-map "$out/$log-map/map.pcd" --log "$radish" --skip-scans "$start" \
      --max-scans 100 --out "$out/$log-$start" --force --quiet "$@" > "$out/$log-$start.txt" 2>&1 || true
    python3 scripts/localise_agreement.py "$out/$log-map" "$out/$log-$start" --settle 10 |
      python3 -c "
import json, sys
r = json.load(sys.stdin)
f = lambda v: '∞' if v is None or v == float('inf') else f'{v:.3f}'
print(f\"| $log-$start | {r['first_confirmed_scan']} | {f(r['median_m'])} / {f(r['p95_m'])} / {f(r['max_m'])} | {r['global_searches']} |\")"
  done
done
