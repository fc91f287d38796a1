#!/usr/bin/env bash
# The three benchmark logs as other robots might have logged them (scripts/log-variants.py): kept
# sparse, one scan every 0.8 m or 0.3 rad as the Radish logs are but with the log's real odometry,
# and seen by a short-range laser (readings beyond 5.6 m are no return). The default session on
# each, scored on all relations and on the local ones (scans ≤ 15 s apart), beside the odometry
# alone; a regression on data no default was tuned on shows here.
#   scripts/variant-sessions.sh [OUT_DIR [SESSION_ARGS...]]   (default: build/variants; logs in
#   $SCANLOC_DATASETS). The variant logs are written once into OUT_DIR/logs. SESSION_ARGS go to
#   every session but the odometry-only one.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build/variants}
shift || true
extra=("$@")
source scripts/public-logs.sh variant-sessions
mkdir -p "$out/logs"
# The gate never opens: no step is 1 km long, no turn exceeds π.
odometry_only=(--set session.localise_translation_m=1000 --set session.localise_rotation_rad=3.141592653589793)
for log in intel aces fr079; do
  logs="$out/logs"
  if [ ! -s "$logs/$log.sparse.relations" ]; then
    python3 scripts/log-variants.py sparse "$datasets/$log.clf.gz" \
      "$datasets/$log.corrected-poses.txt" "$logs/$log.sparse.clf" "$logs/$log.sparse.relations"
  fi
  [ -s "$logs/$log.short-range.clf" ] ||
    python3 scripts/log-variants.py short-range "$datasets/$log.clf.gz" "$logs/$log.short-range.clf"
  cp "$datasets/$log.relations" "$logs/$log.short-range.relations"
  for variant in sparse short-range; do
    awk '$2 - $1 <= 15' "$logs/$log.$variant.relations" > "$logs/$log.$variant.local.relations"
    for kind in odometry session; do
      name="$log-$variant-$kind"
      echo "variant-sessions: $name" >&2
      args=("${extra[@]}")
      [ "$kind" = odometry ] && args=("${odometry_only[@]}")
      /usr/bin/time -f "%U %S" -o "$out/$name.cpu" \
        "$scanloc" session --log "$logs/$log.$variant.clf" --out "$out/$name" --force --quiet \
        "${args[@]}" > "$out/$name.session.txt" || true
      for relations in relations local.relations; do
        "$scanloc" evaluate --trajectory "$out/$name/trajectory.tum" \
          --relations "$logs/$log.$variant.$relations" --json > "$out/$name.$relations.json" || true
      done
    done
  done
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def ev(name, relations):
    try:
        return json.load(open(f"{out}/{name}.{relations}.json"))["translation_m"]
    except Exception:
        return None
def mm(e):
    return "failed" if e is None else f"{e['mean']:.3f} / {e['max']:.2f}"
def local_max(e):
    return "failed" if e is None else f"{e['max']:.2f}"
print("| log | variant | scans | odometry alone: mean / max [m] | session: mean / max | session: local max | confirmed | CPU [s] |")
print("|---|---|---|---|---|---|---|---|")
for log in ["intel", "aces", "fr079"]:
    for variant in ["sparse", "short-range"]:
        name = f"{log}-{variant}-session"
        try:
            s = json.load(open(f"{out}/{name}/summary.json"))
            cpu = sum(map(float, open(f"{out}/{name}.cpu").read().split()[-2:]))
            counts = f"{s['validated']} of {s['localised']}"
            scans, cpu = str(s["iterations"]), f"{cpu:.2f}"
        except Exception:
            counts, scans, cpu = "failed", "", ""
        cells = [scans, mm(ev(f"{log}-{variant}-odometry", "relations")),
                 mm(ev(name, "relations")), local_max(ev(name, "local.relations")), counts, cpu]
        print(f"| {log} | {variant} | " + " | ".join(cells) + " |")
PY
