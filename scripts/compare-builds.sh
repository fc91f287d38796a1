#!/usr/bin/env bash
# Two builds side by side on the 13 public logs (3 Kümmerle, 5 Radish × noisy and perfect
# odometry), default settings: whether every output is byte for byte the same (the records with
# their timings blanked), then, with --rounds N, the CPU seconds (user + system) of both on the
# Kümmerle logs in ABBA order, one process at a time, so that a change's cost is judged by a
# ratio measured in one sitting, never against figures from another day or host.
#   scripts/compare-builds.sh OLD NEW OUT [--rounds N] [SESSION_ARGS...]
# OLD and NEW are build trees (apps/scanloc and src/libscanloc.so) or folders holding a copy of
# both (`cp build/apps/scanloc build/src/libscanloc.so DIR` before changing the code): each
# binary runs with its own library first on LD_LIBRARY_PATH.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 3 ]; then
  echo "usage: scripts/compare-builds.sh OLD NEW OUT [--rounds N] [SESSION_ARGS...]" >&2
  exit 2
fi
old=$1 new=$2 out=$3
shift 3
rounds=0
if [ "${1:-}" = --rounds ]; then
  rounds=${2:?--rounds needs a count}
  shift 2
fi
extra=("$@")
datasets=${SCANLOC_DATASETS:-../shared/datasets}
[ -d "$datasets" ] || { echo "compare-builds: no datasets at $datasets (set SCANLOC_DATASETS)" >&2; exit 2; }

binary_of() { [ -x "$1/apps/scanloc" ] && echo "$1/apps/scanloc" || echo "$1/scanloc"; }
library_of() { [ -f "$1/src/libscanloc.so" ] && echo "$1/src" || echo "$1"; }
for build in "$old" "$new"; do
  [ -x "$(binary_of "$build")" ] || { echo "compare-builds: no scanloc binary in $build" >&2; exit 2; }
done
run() {  # run BUILD LOG DIR: one session, its CPU seconds into DIR.cpu
  local build=$1 log=$2 dir=$3
  LD_LIBRARY_PATH="$(library_of "$build")${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
    /usr/bin/time -f "%U %S" -o "$dir.cpu" \
    "$(binary_of "$build")" session --log "$log" --out "$dir" --force --quiet "${extra[@]}" \
    > "$dir.txt" 2>&1
}
# The records without what differs from run to run: the measured times.
records() { sed -E 's/"timings_ms":\{[^}]*\}//; s/"time_s":[0-9.e+-]+//g' "$1/iterations.jsonl"; }

mkdir -p "$out"
logs=()
for log in intel aces fr079; do logs+=("$log:$datasets/$log.clf.gz"); done
for log in seattle orebro fhw edmonton acapulco; do
  for kind in noisy exact; do logs+=("$log-$kind:$datasets/radish/$log.$kind.clf.gz"); done
done
differing=0
for entry in "${logs[@]}"; do
  name=${entry%%:*} log=${entry#*:}
  run "$old" "$log" "$out/old-$name"
  run "$new" "$log" "$out/new-$name"
  verdict=same
  for file in trajectory.tum trajectory-online.tum map.pcd map.pgm graph.g2o summary.json; do
    [ -f "$out/old-$name/$file" ] || [ -f "$out/new-$name/$file" ] || continue
    [ "$file" = summary.json ] && continue  # holds the run's times and paths
    cmp -s "$out/old-$name/$file" "$out/new-$name/$file" || verdict="differs: $file"
  done
  cmp -s <(records "$out/old-$name") <(records "$out/new-$name") || verdict="$verdict, records"
  [ "$verdict" = same ] || differing=$((differing + 1))
  echo "| $name | $verdict |"
done
echo "compare-builds: $differing of ${#logs[@]} logs differ"

[ "$rounds" -gt 0 ] || exit 0
echo
echo "| log | old CPU s (ABBA order) | new CPU s | mean change |"
echo "|---|---|---|---|"
for log in intel aces fr079; do
  olds=() news=()
  for round in $(seq "$rounds"); do
    for which in old new new old; do
      build=$old
      [ "$which" = new ] && build=$new
      run "$build" "$datasets/$log.clf.gz" "$out/abba-$log-$which"
      seconds=$(awk '{printf "%.2f", $1 + $2}' "$out/abba-$log-$which.cpu")
      if [ "$which" = old ]; then olds+=("$seconds"); else news+=("$seconds"); fi
    done
  done
  python3 - "$log" "${olds[*]}" "${news[*]}" <<'PY'
import sys
log, olds, news = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
mean = lambda xs: sum(map(float, xs)) / len(xs)
change = 100.0 * (mean(news) / mean(olds) - 1.0)
print(f"| {log} | {' / '.join(olds)} | {' / '.join(news)} | {change:+.1f} % |")
PY
done
