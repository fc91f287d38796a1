#!/usr/bin/env bash
# How much a session's accuracy depends on chance: runs each public log (Intel, ACES, Fr079) with
# the default configuration and with perturbations that should not matter (a threshold or a
# tolerance moved by 2–10%, in both directions), scores every run on the relations (Kümmerle et al. 2009) and prints
# one row per run. A robust session gives nearly the same error in every row of a log.
#   scripts/robustness-sessions.sh [OUT_DIR]   (default: build/robustness; logs in $SCANLOC_DATASETS)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/robustness}
source scripts/public-logs.sh robustness-sessions
perturbations=(
  ""
  "session.localise_translation_m=0.051"
  "refinement.ceres.translation_tolerance_m=0.0011"
  "session.insert_translation_m=0.105"
  "session.localise_translation_m=0.049"
  "session.insert_translation_m=0.095"
  "refinement.ceres.translation_tolerance_m=0.0009"
  "session.localise_rotation_rad=0.037"
)
mkdir -p "$out"
for log in intel aces fr079; do
  for i in "${!perturbations[@]}"; do
    p=${perturbations[$i]}
    echo "robustness-sessions: $log ${p:-default}" >&2
    args=()
    [ -n "$p" ] && args=(--set "$p")
    "$scanloc" session --log "$datasets/$log.clf.gz" --out "$out/$log-$i" --force --quiet "${args[@]}" \
      > "$out/$log-$i.session.txt"
    "$scanloc" evaluate --trajectory "$out/$log-$i/trajectory.tum" \
      --relations "$datasets/$log.relations" --json > "$out/$log-$i.evaluation.json"
    echo "${p:-default}" > "$out/$log-$i.perturbation"
  done
done
python3 - "$out" "${#perturbations[@]}" <<'PY'
import json, sys
out, count = sys.argv[1], int(sys.argv[2])
print("| log | configuration | translation [m] | max [m] | rotation [deg] | validated / localised |")
print("|---|---|---|---|---|---|")
summary = []
for log in ["intel", "aces", "fr079"]:
    above = []
    for i in range(count):
        s = json.load(open(f"{out}/{log}-{i}/summary.json"))
        e = json.load(open(f"{out}/{log}-{i}.evaluation.json"))
        p = open(f"{out}/{log}-{i}.perturbation").read().strip()
        t, r = e["translation_m"], e["rotation_deg"]
        print(f"| {log} | {p} | {t['mean']:.4f} ± {t['std']:.4f} | {t['max']:.3f} "
              f"| {r['mean']:.3f} ± {r['std']:.3f} | {s['validated']} / {s['localised']} |")
        if t["max"] > 1.0:
            above.append(t["max"])
    summary.append(f"{log}: {len(above)} of {count} runs with a relation error above 1 m")
print()
print("; ".join(summary))
PY
