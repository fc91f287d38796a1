#!/usr/bin/env bash
# The main job on the default data that ships in datasets/: installs, builds, then runs the
# Likelihood Test of the classroom's four candidate postures (the chapter's Table 1).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/apps/scanloc test --map datasets/classroom/classroom.lines \
  --scan datasets/classroom/scan.scan --candidates datasets/classroom/candidates.txt
