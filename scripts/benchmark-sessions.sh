#!/usr/bin/env bash
# Runs the default session on each public log (Intel, ACES, Fr079), one after the other, scores
# it on the relations (Kümmerle et al. 2009) and prints the table of docs/BENCHMARKS.md: absolute
# translational and rotational error, throughput on wall and on CPU time (user + system, the
# session's loop), the cost per scan over the first and the last tenth of the log, peak memory and
# final map size, the path's length and the peak memory's growth per km of it (the full session's
# peak minus that of a session over the log's first 100 scans, over the path between them).
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
  "$scanloc" session --log "$datasets/$log.clf.gz" --out "$out/$log-start" --force --quiet \
    --max-scans 100 "$@" > "$out/$log-start.session.txt"
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def per_scan_ms(log):
    # Mean wall ms per scan (timings_ms.total) over the first and the last tenth of the scans.
    totals = [json.loads(line)["timings_ms"]["total"] for line in open(f"{out}/{log}/iterations.jsonl")]
    tenth = max(1, len(totals) // 10)
    return sum(totals[:tenth]) / tenth, sum(totals[-tenth:]) / tenth
def path_km(folder):
    # Length of the trajectory's path (TUM: t x y z ...), km.
    rows = [line.split() for line in open(f"{folder}/trajectory.tum") if line.strip() and line[0] != "#"]
    xy = [(float(r[1]), float(r[2])) for r in rows]
    return sum(((b[0] - a[0]) ** 2 + (b[1] - a[1]) ** 2) ** 0.5 for a, b in zip(xy, xy[1:])) / 1e3
print("| log | translation [m] | max [m] | rotation [deg] | max [deg] | localised / validated / scans "
      "| wall [s] | × real time | CPU [s] | × real time on CPU | ms per scan, first → last tenth "
      "| peak memory [MB] | map points | path [km] | memory growth [MB/km] |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for log in ["intel", "aces", "fr079"]:
    s = json.load(open(f"{out}/{log}/summary.json"))
    e = json.load(open(f"{out}/{log}.evaluation.json"))
    t, r = e["translation_m"], e["rotation_deg"]
    first, last = per_scan_ms(log)
    start = json.load(open(f"{out}/{log}-start/summary.json"))
    km, start_km = path_km(f"{out}/{log}"), path_km(f"{out}/{log}-start")
    growth = (s["peak_resident_mb"] - start["peak_resident_mb"]) / max(1e-9, km - start_km)
    print(f"| {log} | {t['mean']:.4f} ± {t['std']:.4f} | {t['max']:.3f} | {r['mean']:.3f} ± {r['std']:.3f} "
          f"| {r['max']:.2f} | {s['localised']} / {s['validated']} / {s['iterations']} "
          f"| {s['wall_time_s']:.1f} | {s['times_real_time']:.0f} | {s['cpu_time_s']:.1f} "
          f"| {s['times_real_time_on_cpu']:.0f} | {first:.2f} → {last:.2f} "
          f"| {s['peak_resident_mb']:.1f} | {s['map_points']} | {km:.2f} | {growth:.1f} |")
PY
