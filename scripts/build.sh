#!/usr/bin/env bash
# Configures and builds scanloc (Release by default) in build/ or $SCANLOC_BUILD_DIR.
# Extra arguments go to CMake's configure step, e.g. -DSCANLOC_BUILD_BENCHMARKS=ON.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SCANLOC_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE="${SCANLOC_BUILD_TYPE:-Release}" "$@" >/dev/null
cmake --build "$build_dir" -j"$(nproc)"
