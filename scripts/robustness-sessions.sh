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
source scripts/score-session.sh
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
  rm -f "$out/p$i/session-args"
  if [ "${perturbations[$i]:-default}" != default ]; then
    printf '%s\0' --set "${perturbations[$i]}" > "$out/p$i/session-args"
  fi
  for log in intel aces fr079; do
    job "$i" "$log" "$datasets/$log.clf.gz" "$datasets/$log.relations"
  done
  for log in seattle orebro fhw edmonton acapulco; do
    for kind in noisy exact; do
      job "$i" "$log-$kind" "$datasets/radish/$log.$kind.clf.gz" "$datasets/radish/$log.relations"
    done
  done
done

run_harness robustness-sessions "${#perturbations[@]}"
