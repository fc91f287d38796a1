#!/usr/bin/env bash
# Checks that scanloc installs as a CMake package others can use: builds it as a shared library in
# build-install/ (or $SCANLOC_INSTALL_BUILD_DIR), installs it to a temporary prefix, then configures,
# builds and runs examples/likelihood_test against that prefix alone (the classroom's scan at its
# true posture must match: MP/NVP above 0.8; the desk and the person are not in the map), and runs
# the installed executable.
#   SCANLOC_INSTALL_FROM=build scripts/check-install.sh   installs a shared build already made
#                                                         (CI: the one the tests ran on)
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
if [ -n "${SCANLOC_INSTALL_FROM:-}" ]; then
  build=$SCANLOC_INSTALL_FROM
  grep -q '^BUILD_SHARED_LIBS:BOOL=ON' "$build/CMakeCache.txt" ||
    { echo "check-install: $build is not a shared build (BUILD_SHARED_LIBS)" >&2; exit 1; }
else
  build=${SCANLOC_INSTALL_BUILD_DIR:-build-install}
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
    -DSCANLOC_BUILD_TESTS=OFF >/dev/null
fi
cmake --build "$build" --target scanloc scanloc_app -j"$(nproc)"
cmake --install "$build" --prefix "$prefix" >/dev/null
test -f "$prefix/include/scanloc/likelihood/likelihood_test.hpp"
# The installed executable runs with the installed library, the build tree out of reach.
"$prefix/bin/scanloc" --help >/dev/null ||
  { echo "check-install: the installed scanloc does not run" >&2; exit 1; }
cmake -S examples/likelihood_test -B "$work/example" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/example"
out=$("$work/example/likelihood_test_example" datasets/classroom/classroom.lines \
  datasets/classroom/scan.scan 1.126 3.112 0.0463)
echo "check-install: $out"
ratio=$(echo "$out" | awk '{for (i = 1; i < NF; ++i) if ($i == "MP/NVP") print $(i + 1)}')
awk -v r="$ratio" 'BEGIN { exit !(r > 0.8) }' || { echo "check-install: MP/NVP $ratio <= 0.8" >&2; exit 1; }
echo "check-install: OK (installed to a temporary prefix, example built and run against it)"
