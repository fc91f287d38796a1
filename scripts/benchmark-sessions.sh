#!/usr/bin/env bash
# Runs the default session on each public log (Intel, ACES, Fr079), one after the other, scores
# it on the relations (Kümmerle et al. 2009) and prints the table of docs/BENCHMARKS.md: absolute
# translational and rotational error, throughput on wall and on CPU time (user + system, the
# session's loop), the cost per scan over the first and the last tenth of the log, peak memory and
# final map size.
#   scripts/benchmark-sessions.sh [OUT_DIR [SESSION_ARGS...]]  (default: build/sessions; logs in
#   $SCANLOC_DATASETS); SESSION_ARGS (e.g. --set recovery.lost_after_unconfirmed=2) go to every
#   session, to measure a configuration beside the defaults.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/sessions}
shift || true
source scripts/public-logs.sh benchmark-sessions
mkdir -p "$out"
for log in intel aces fr079; do
  echo "benchmark-sessions: $log" >&2
  "$scanloc" session --log "$datasets/$log.clf.gz" --out "$out/$log" --force --quiet "$@" \
    > "$out/$log.session.txt"
  "$scanloc" evaluate --trajectory "$out/$log/trajectory.tum" --relations "$datasets/$log.relations" \
    --json > "$out/$log.evaluation.json"
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def per_scan_ms(log):
    # Mean wall ms per scan (timings_ms.total) over the first and the last tenth of the scans.
    totals = [json.loads(line)["timings_ms"]["total"] for line in open(f"{out}/{log}/iterations.jsonl")]
    tenth = max(1, len(totals) // 10)
    return sum(totals[:tenth]) / tenth, sum(totals[-tenth:]) / tenth
print("| log | translation [m] | max [m] | rotation [deg] | max [deg] | localised / validated / scans "
      "| wall [s] | × real time | CPU [s] | × real time on CPU | ms per scan, first → last tenth "
      "| peak memory [MB] | map points |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for log in ["intel", "aces", "fr079"]:
    s = json.load(open(f"{out}/{log}/summary.json"))
    e = json.load(open(f"{out}/{log}.evaluation.json"))
    t, r = e["translation_m"], e["rotation_deg"]
    first, last = per_scan_ms(log)
    print(f"| {log} | {t['mean']:.4f} ± {t['std']:.4f} | {t['max']:.3f} | {r['mean']:.3f} ± {r['std']:.3f} "
          f"| {r['max']:.2f} | {s['localised']} / {s['validated']} / {s['iterations']} "
          f"| {s['wall_time_s']:.1f} | {s['times_real_time']:.0f} | {s['cpu_time_s']:.1f} "
          f"| {s['times_real_time_on_cpu']:.0f} | {first:.2f} → {last:.2f} "
          f"| {s['peak_resident_mb']:.1f} | {s['map_points']} |")
PY
