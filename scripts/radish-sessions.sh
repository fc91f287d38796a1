#!/usr/bin/env bash
# The five sparse Radish logs of other buildings (../shared/datasets/radish, see its README), each
# with noisy synthetic odometry and with perfect odometry: the default session on every one, scored
# on all relations and on the local ones (scans ≤ 15 s apart), beside the odometry alone (every
# scan takes the prediction: the localisation gate never opens). Prints the table of issue 15, then
# each session's cost beside its error (CPU, wall, throughput on CPU, peak memory: issue 19).
#   scripts/radish-sessions.sh [OUT_DIR [SESSION_ARGS...]]   (default: build/radish; logs in
#   $SCANLOC_DATASETS/radish). SESSION_ARGS go to every session but the odometry-only one, e.g.
#   --set recovery.lost_after_unconfirmed=2, to measure a configuration on all five logs.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/radish}
shift || true
extra=("$@")
source scripts/public-logs.sh radish-sessions
radish="$datasets/radish"
mkdir -p "$out"
# The gate never opens: no step is 1 km long, no turn exceeds π.
odometry_only=(--set session.localise_translation_m=1000 --set session.localise_rotation_rad=3.141592653589793)
for log in seattle orebro fhw edmonton acapulco; do
  for kind in odometry noisy exact; do
    echo "radish-sessions: $log $kind" >&2
    input="$radish/$log.${kind/odometry/noisy}.clf.gz"
    args=("${extra[@]}")
    [ "$kind" = odometry ] && args=("${odometry_only[@]}")
    /usr/bin/time -f "%U %S" -o "$out/$log-$kind.cpu" \
      "$scanloc" session --log "$input" --out "$out/$log-$kind" --force --quiet "${args[@]}" \
      > "$out/$log-$kind.session.txt" || true
    for relations in relations local.relations; do
      "$scanloc" evaluate --trajectory "$out/$log-$kind/trajectory.tum" \
        --relations "$radish/$log.$relations" --json > "$out/$log-$kind.$relations.json" || true
    done
  done
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def ev(log, kind, relations):
    try:
        return json.load(open(f"{out}/{log}-{kind}.{relations}.json"))["translation_m"]
    except Exception:
        return None
def mm(e):
    return "failed" if e is None else f"{e['mean']:.3f} / {e['max']:.1f}"
print("| log | odometry given: mean / max [m] | noisy: mean / max | noisy: local max "
      "| perfect odometry: mean / max | perfect: local max |")
print("|---|---|---|---|---|---|")
def local_max(e):
    return "failed" if e is None else f"{e['max']:.2f}"
for log in ["seattle", "orebro", "fhw", "edmonton", "acapulco"]:
    cells = [mm(ev(log, "odometry", "relations")), mm(ev(log, "noisy", "relations")),
             local_max(ev(log, "noisy", "local.relations")), mm(ev(log, "exact", "relations")),
             local_max(ev(log, "exact", "local.relations"))]
    print(f"| {log} | " + " | ".join(cells) + " |")
# What each session cost beside its error: the whole process's CPU (user + system, from
# /usr/bin/time), the session's wall time and peak memory (summary.json), and the log's span over
# that CPU time (issue 19's throughput).
print()
print("| log | odometry | mean [m] | CPU [s] | wall [s] | × real time on CPU | peak memory [MB] |")
print("|---|---|---|---|---|---|---|")
for log in ["seattle", "orebro", "fhw", "edmonton", "acapulco"]:
    for kind in ["noisy", "exact"]:
        try:
            s = json.load(open(f"{out}/{log}-{kind}/summary.json"))
            user, system = map(float, open(f"{out}/{log}-{kind}.cpu").read().split()[-2:])
        except Exception:
            print(f"| {log} | {kind} | failed | | | | |")
            continue
        cpu = user + system
        span = s["times_real_time_on_cpu"] * s["cpu_time_s"]
        e = ev(log, kind, "relations")
        mean = "failed" if e is None else f"{e['mean']:.3f}"
        print(f"| {log} | {kind} | {mean} | {cpu:.2f} | {s['wall_time_s']:.2f} "
              f"| {span / cpu:.0f} | {s['peak_resident_mb']:.1f} |")
PY
