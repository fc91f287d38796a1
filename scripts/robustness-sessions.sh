#!/usr/bin/env bash
# How much a session's accuracy depends on chance, on all eight public logs: Intel, ACES, Fr079
# and the five Radish logs with noisy and with perfect odometry (13 runs), each with the default
# configuration and with perturbations that should not matter (a threshold or a tolerance moved by
# 2–10 %, in both directions). Every run is scored on its relations (Kümmerle et al. 2009), the
# Radish runs also on their local relations (scans ≤ 15 s apart) and by their scan-to-scan errors
# against the reference poses; scripts/robustness-summary.py prints the table and issue 15's
# targets counted over every run, so that a regression shows however it falls.
#   scripts/robustness-sessions.sh [OUT_DIR [SESSION_ARGS...]]
# OUT_DIR defaults to build/robustness; the logs are in $SCANLOC_DATASETS. SESSION_ARGS go to every
# session (e.g. --set session.motion_prior=true, to judge a variant on every run). JOBS sessions
# run at a time (default: the number of processors). 130 sessions, about 6 minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/robustness}
shift || true
extra=("$@")
source scripts/public-logs.sh robustness-sessions
# The perturbations, one a line ("default": none), shared with the localise tests
# (tests/localise_datasets_test.cpp).
mapfile -t perturbations < scripts/perturbations.txt
mkdir -p "$out"
rm -f "$out/jobs" "$out/failed"
# Every job is four NUL-terminated fields (INDEX NAME LOG RELATIONS), so that a path may hold
# spaces; the session arguments are NUL-terminated in a file, read by every job.
: > "$out/session-args"
if [ ${#extra[@]} -gt 0 ]; then printf '%s\0' "${extra[@]}" > "$out/session-args"; fi
job() { printf '%s\0' "$@" >> "$out/jobs"; }
for i in "${!perturbations[@]}"; do
  mkdir -p "$out/p$i"
  echo "${perturbations[$i]:-default}" > "$out/p$i/perturbation"
  for log in intel aces fr079; do
    job "$i" "$log" "$datasets/$log.clf.gz" "$datasets/$log.relations"
  done
  for log in seattle orebro fhw edmonton acapulco; do
    for kind in noisy exact; do
      job "$i" "$log-$kind" "$datasets/radish/$log.$kind.clf.gz" "$datasets/radish/$log.relations"
    done
  done
done

# One session and its scores: run_one INDEX NAME LOG RELATIONS. The perturbation is read from
# OUT_DIR/pINDEX/perturbation ("default": none).
run_one() {
  local i=$1 name=$2 log=$3 relations=$4 dir="$out/p$1" p args
  mapfile -d '' -t args < "$out/session-args"
  p=$(< "$dir/perturbation")
  [ "$p" != default ] && args+=(--set "$p")
  echo "robustness-sessions: $name $p" >&2
  # Nothing of an earlier run in OUT_DIR may be scored in place of this one.
  rm -rf "${dir:?}/$name" "$dir/$name".*
  if ! "$scanloc" session --log "$log" --out "$dir/$name" --force --quiet "${args[@]}" \
    > "$dir/$name.session.txt" 2>&1; then
    echo "p$i $name" >> "$out/failed"
    return 0
  fi
  "$scanloc" evaluate --trajectory "$dir/$name/trajectory.tum" --relations "$relations" --json \
    > "$dir/$name.evaluation.json" || echo "p$i $name" >> "$out/failed"
  local local_relations=${relations%.relations}.local.relations
  if [ -f "$local_relations" ]; then
    "$scanloc" evaluate --trajectory "$dir/$name/trajectory.tum" --relations "$local_relations" \
      --json > "$dir/$name.local.evaluation.json" || echo "p$i $name" >> "$out/failed"
  fi
}
export -f run_one
export out scanloc
xargs -0 -n 4 -P "${JOBS:-$(nproc)}" bash -c 'run_one "$@"' run_one < "$out/jobs"
SCANLOC_DATASETS="$datasets" python3 scripts/robustness-summary.py "$out" "${#perturbations[@]}"
