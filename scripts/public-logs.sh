# Sourced by the scripts that run sessions on the public logs: from the repository's top,
# sets `datasets` (the logs: $SCANLOC_DATASETS, default ../shared/datasets) and `scanloc` (the
# executable, built if missing), and stops with a clear message when the logs are absent.
#   usage (after `set -euo pipefail` and `cd` to the top): source scripts/public-logs.sh NAME
datasets=${SCANLOC_DATASETS:-../shared/datasets}
scanloc=./build/apps/scanloc
[ -x "$scanloc" ] || bash scripts/build.sh
[ -d "$datasets" ] || { echo "$1: no logs at $datasets (set SCANLOC_DATASETS)" >&2; exit 1; }
