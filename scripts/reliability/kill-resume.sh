#!/usr/bin/env bash
# A session killed with SIGKILL part way, then resumed with --resume, ends with exactly the files
# of an uninterrupted run: trajectory.tum and map.pcd byte for byte, iterations.jsonl and
# summary.json equal but for their timings. Prints where the kill landed and the CPU time of the
# whole run, of the killed part and of the resume.
#   scripts/reliability/kill-resume.sh [SCANLOC] [LOG] [FRACTION] [-- SESSION OPTIONS...]
# LOG defaults to the ACES log of the public datasets (SCANLOC_DATASETS); the kill comes once
# FRACTION (default 0.4) of the uninterrupted run's records are written.
set -euo pipefail
cd "$(dirname "$0")/../.."
scanloc=$(realpath "${1:-build/apps/scanloc}")
datasets=${SCANLOC_DATASETS:-$(cd .. && pwd)/shared/datasets}
log=${2:-$datasets/aces.clf.gz}
fraction=${3:-0.4}
shift $(($# < 3 ? $# : 3))
[ "${1:-}" = "--" ] && shift
[ -x "$scanloc" ] || { echo "kill-resume: no scanloc at $scanloc (build it first)"; exit 2; }
[ -f "$log" ] || { echo "kill-resume: no log at $log (set SCANLOC_DATASETS)"; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# User + system seconds of a command, by bash's own `time` (no /usr/bin/time on a fresh machine).
TIMEFORMAT='%U %S'
cpu() { awk '{print $1 + $2}' "$1"; }
{ time "$scanloc" session --log "$log" --out "$work/whole" --quiet "$@" >/dev/null \
  2>"$work/whole.err"; } 2>"$work/whole.time" || { cat "$work/whole.err"; exit 1; }
total=$(wc -l <"$work/whole/iterations.jsonl")
kill_at=$(awk -v t="$total" -v f="$fraction" 'BEGIN {printf "%d", t * f}')

# The run to kill, in its own process group; killed once kill_at records are on disk.
start=$(date +%s.%N)
"$scanloc" session --log "$log" --out "$work/killed" --quiet "$@" >/dev/null 2>&1 &
pid=$!
while kill -0 "$pid" 2>/dev/null; do
  lines=$({ cat "$work/killed/iterations.jsonl" 2>/dev/null || true; } | wc -l)
  [ "$lines" -ge "$kill_at" ] && break
  sleep 0.05
done
kill -KILL "$pid" 2>/dev/null || { echo "kill-resume: the run ended before the kill"; exit 1; }
wait "$pid" 2>/dev/null || true
killed_wall=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN {printf "%.1f", e - s}')
records=$(wc -l <"$work/killed/iterations.jsonl")
for file in summary.json trajectory.tum map.pcd; do
  [ ! -e "$work/killed/$file" ] || { echo "kill-resume: the killed run wrote $file"; exit 1; }
done

{ time "$scanloc" session --log "$log" --out "$work/killed" --quiet --resume "$@" >/dev/null \
  2>"$work/resume.err"; } 2>"$work/resume.time" || { cat "$work/resume.err"; exit 1; }

status=0
for file in trajectory.tum map.pcd map.pgm map.yaml run.json; do
  cmp -s "$work/whole/$file" "$work/killed/$file" || { echo "FAILED: $file differs"; status=1; }
done
for file in trajectory-online.tum graph.g2o; do
  [ ! -e "$work/whole/$file" ] || cmp -s "$work/whole/$file" "$work/killed/$file" ||
    { echo "FAILED: $file differs"; status=1; }
done
python3 - "$work/whole" "$work/killed" <<'EOF' || status=1
import json, sys

def strip(value):  # timings are the only part two runs of the same work do not share
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if k not in ("timings_ms", "time_s")}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value

whole, killed = sys.argv[1], sys.argv[2]
records = [[strip(json.loads(l)) for l in open(d + "/iterations.jsonl")] for d in (whole, killed)]
if records[0] != records[1]:
    print("FAILED: iterations.jsonl differs beyond its timings")
    sys.exit(1)
volatile = {"wall_time_s", "scans_per_s", "times_real_time", "peak_resident_mb", "cpu_time_s",
            "times_real_time_on_cpu", "resumed_after_records", "map_signature_wall_s",
            "final_match_wall_s"}
summaries = [{k: v for k, v in json.load(open(d + "/summary.json")).items() if k not in volatile}
             for d in (whole, killed)]
if summaries[0] != summaries[1]:
    print("FAILED: summary.json differs beyond its timings")
    sys.exit(1)
EOF
echo "log: $log ($total iterations)"
echo "killed after ${killed_wall} s of wall time with $records complete records"
echo "CPU (user + system): uninterrupted $(cpu "$work/whole.time") s, resume $(cpu "$work/resume.time") s"
[ "$status" -eq 0 ] && echo "kill-resume: OK, the resumed run's files equal the uninterrupted run's"
exit "$status"
