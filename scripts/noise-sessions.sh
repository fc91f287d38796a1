#!/usr/bin/env bash
# The public logs as a noisier laser would have seen them: every reading below the log's no-return
# value gains Gaussian noise of NOISE_M metres (default 0.01, on top of the logs' own; a SICK's
# spec is about that, a Hokuyo URG's 1–3 cm), drawn afresh for each of SEEDS seeds (default 4;
# scripts/log-variants.py range-noise). The thirteen default runs of each seed are scored as
# scripts/robustness-sessions.sh scores its perturbations, against issue 15's targets: a session
# whose result holds only for the noise its logs happen to carry shows here.
#   scripts/noise-sessions.sh [OUT_DIR [SESSION_ARGS...]]   (default: build/noise; logs in
#   $SCANLOC_DATASETS). The noisy logs are written once into OUT_DIR/logs (about 50 MB a
#   seed). SESSION_ARGS go to every session. JOBS sessions run at a time (default: the number of
#   processors). 52 sessions, about 4 minutes on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/noise}
shift || true
extra=("$@")
noise_m=${NOISE_M:-0.01}
seeds=${SEEDS:-4}
source scripts/public-logs.sh noise-sessions
source scripts/score-session.sh
logs="$out/logs"
mkdir -p "$logs"
rm -f "$out/jobs" "$out/failed"
: > "$out/session-args"
if [ ${#extra[@]} -gt 0 ]; then printf '%s\0' "${extra[@]}" > "$out/session-args"; fi
job() { printf '%s\0' "$@" >> "$out/jobs"; }
# A noisy copy of LOG as OUT (written once; the σ and the seed are in its name).
noisy() {
  [ -s "$2" ] || python3 scripts/log-variants.py range-noise "$1" "$2.part" "$noise_m" "$3"
  [ -s "$2" ] || mv "$2.part" "$2"
}
for ((i = 0; i < seeds; ++i)); do
  seed=$((i + 1))
  mkdir -p "$out/p$i"
  echo "range noise ${noise_m} m, seed $seed" > "$out/p$i/perturbation"
  for log in intel aces fr079; do
    noisy "$datasets/$log.clf.gz" "$logs/$log.n$noise_m.s$seed.clf" "$seed"
    job "$i" "$log" "$logs/$log.n$noise_m.s$seed.clf" "$datasets/$log.relations"
  done
  for log in seattle orebro fhw edmonton acapulco; do
    for kind in noisy exact; do
      noisy "$datasets/radish/$log.$kind.clf.gz" "$logs/$log.$kind.n$noise_m.s$seed.clf" "$seed"
      job "$i" "$log-$kind" "$logs/$log.$kind.n$noise_m.s$seed.clf" \
        "$datasets/radish/$log.relations"
    done
  done
done

run_harness noise-sessions "$seeds"
