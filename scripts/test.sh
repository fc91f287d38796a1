#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test. The public-log tests find the logs in
# $SCANLOC_DATASETS (default ../shared/datasets) and skip with a message when they are absent.
#   scripts/test.sh              Release build in build/
#   scripts/test.sh --sanitize   AddressSanitizer + UBSan build in build-sanitize/
# Further arguments go to ctest, e.g. `scripts/test.sh --sanitize -L unit` for the unit tests only.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
if [ "${1:-}" = "--sanitize" ]; then
  shift
  # -O1 with line tables: stacks with file and line at half the compile time of -O2 -g (the
  # library; the app and tests build at -O0, cmake/ScanlocTarget.cmake).
  export SCANLOC_BUILD_DIR=build-sanitize SCANLOC_BUILD_TYPE=RelWithDebInfo
  bash scripts/build.sh -DSCANLOC_SANITIZE=ON -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1"
else
  bash scripts/build.sh
fi
ctest --test-dir "${SCANLOC_BUILD_DIR:-build}" --output-on-failure -j"$(nproc)" "$@"
