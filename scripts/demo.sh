#!/usr/bin/env bash
# The main job on the default data that ships in datasets/: installs, builds, localises the
# classroom's recorded sequence against its line map while the point map grows from its scans,
# and writes the operator's report (HTML with figures) of the run.
#   scripts/demo.sh [RUN_DIR]     (default: build/demo-classroom)
set -euo pipefail
cd "$(dirname "$0")/.."
run=${1:-build/demo-classroom}
bash scripts/install-deps.sh
bash scripts/build.sh
# The first posture is the one the operator gives (§3.2.2): Table 1's true posture p0. --force:
# a second demo writes over the first one's run folder.
./build/apps/scanloc session --log datasets/classroom/classroom.seq.jsonl \
  --line-map datasets/classroom/classroom.lines --initial-pose 1.126 3.112 0.0463 \
  --out "$run" --force --quiet
./build/apps/scanloc report "$run"
echo "demo: open $(cd "$run" && pwd)/report.html in a browser;" \
  "the occupancy grid is $(cd "$run" && pwd)/map.pgm (map.yaml for ROS map_server)"
