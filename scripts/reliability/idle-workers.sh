#!/usr/bin/env bash
# Issue 20, defect 1: idle workers of the pool must sleep, not spin. The old pool spun through
# 20,000 sched_yield calls between loops; under contention a low-priority run then spent minutes
# after its work before its workers could be joined, and without contention it burnt a core.
#
# The symptom (wall time under `nice -n 19` beside busy loops) is the scheduler's to decide: the
# same one-thread `scanloc refine` took 17 s and 245 s in two runs beside the same loops here, so
# a check on it fails at random. This one measures the cause, which does not depend on the
# scheduler: the CPU (user + system) that a second thread adds to a whole session of the
# classroom, where the pool runs a few loops per scan. A sleeping worker adds little (0.98–1.09× measured); the old spin,
# put back, made it 2.7×. Fails when two threads burn 1.5× one thread's CPU (+ 0.1 s), medians
# of three runs each; also when the second thread was never woken (the check would measure
# nothing), and when two threads change the trajectory or the map.
#   scripts/reliability/idle-workers.sh [SCANLOC]   (default ./build/apps/scanloc)
set -euo pipefail
cd "$(dirname "$0")/../.."
scanloc=${1:-./build/apps/scanloc}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Prints "cpu_s voluntary_switches" of one classroom session with THREADS into DIR.
session() {  # THREADS DIR
  python3 - "$scanloc" "$1" "$2" <<'EOF'
import resource, subprocess, sys
scanloc, threads, out = sys.argv[1:]
command = [scanloc, "--threads", threads, "session",
           "--log", "datasets/classroom/classroom.seq.jsonl",
           "--line-map", "datasets/classroom/classroom.lines",
           "--initial-pose", "1.126", "3.112", "0.0463", "--out", out, "--quiet"]
subprocess.run(["timeout", "120"] + command, check=True,
               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
usage = resource.getrusage(resource.RUSAGE_CHILDREN)
print(f"{usage.ru_utime + usage.ru_stime:.3f} {usage.ru_nvcsw}")
EOF
}
median() { sort -g | sed -n 2p; }

for run in 1 2 3; do  # alternated, so that a slow spell of the machine falls on both
  session 1 "$work/one$run" >>"$work/one"
  session 2 "$work/two$run" >>"$work/two"
done
for run in 1 2 3; do
  for file in trajectory.tum map.pcd; do
    cmp -s "$work/one1/$file" "$work/two$run/$file" ||
      { echo "idle-workers: FAILED: two threads changed $file"; exit 1; }
  done
done
scans=$(wc -l <"$work/one1/iterations.jsonl")
one_cpu=$(cut -d' ' -f1 "$work/one" | median)
two_cpu=$(cut -d' ' -f1 "$work/two" | median)
one_sleeps=$(cut -d' ' -f2 "$work/one" | median)
two_sleeps=$(cut -d' ' -f2 "$work/two" | median)
echo "idle-workers: classroom session of $scans scans, CPU s (median of 3): one thread $one_cpu," \
  "two threads $two_cpu; voluntary context switches $one_sleeps and $two_sleeps"
if ((two_sleeps < one_sleeps + scans / 2)); then
  echo "idle-workers: FAILED: the second thread slept fewer than once per two scans; the pool" \
    "seems unused and this check measures nothing"
  exit 1
fi
if (($(echo "$two_cpu > 1.5 * $one_cpu + 0.1" | bc))); then
  echo "idle-workers: FAILED: the second thread burns CPU while idle"
  exit 1
fi
echo "idle-workers: passed"
