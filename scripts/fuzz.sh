#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang, ASan + UBSan) in build-fuzz/ and runs each for
# SECONDS on a temporary copy of its seed corpus fuzz/corpus/<target>/ (the committed corpus never
# grows). Prints each target's executions and coverage; exits non-zero when a target crashed,
# leaked, timed out or ran out of memory, naming the reproducer (kept in build-fuzz/artifacts/).
#   scripts/fuzz.sh SECONDS [TARGET...]     e.g. scripts/fuzz.sh 60 scan_file pcd
# SCANLOC_FUZZ_NO_BUILD=1 skips the build and runs the fuzzers already in build-fuzz/.
# Replay a reproducer: build-fuzz/fuzz/<target>_fuzzer FILE
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:?usage: scripts/fuzz.sh SECONDS [TARGET...]}
shift
build_dir=build-fuzz

if [ "${SCANLOC_FUZZ_NO_BUILD:-0}" != 1 ]; then
  # The library's own packages, then clang with libFuzzer and the sanitizer runtimes.
  bash scripts/install-deps.sh
  if ! command -v clang++ >/dev/null || ! dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null |
    grep -q "install ok installed"; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    echo "fuzz: installing clang and its libFuzzer runtime"
    $sudo apt-get update -q
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends clang \
      libclang-rt-14-dev
  fi

  # -O1 without NDEBUG: sanitizer reports with usable stacks (line tables: file and line), Eigen's
  # assertions on. Static: the harnesses' coverage is the library's.
  cmake -S . -B "$build_dir" -DSCANLOC_FUZZ=ON -DSCANLOC_BUILD_TESTS=OFF -DBUILD_SHARED_LIBS=OFF \
    -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only" >/dev/null
  nice -n 10 cmake --build "$build_dir" --target scanloc_fuzzers -j"$(nproc)"
fi

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for dir in fuzz/corpus/*/; do
    target=$(basename "$dir")
    # ros_bag is built only when the library reads bags (cmake/ScanlocRosBag.cmake).
    if [ ! -x "$build_dir/fuzz/${target}_fuzzer" ] && [ "$target" = ros_bag ]; then
      echo "fuzz: ros_bag skipped: the library was built without ROS bag support"
      continue
    fi
    targets+=("$target")
  done
fi
artifacts="$PWD/$build_dir/artifacts"
# UBSan reports with the stack that led there (the build makes them fatal).
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
# The corpus copies and the harnesses' input files, in memory where possible, removed at exit
# (a crashed harness cannot remove its input file itself).
work=$(mktemp -d -p /dev/shm 2>/dev/null || mktemp -d)
trap 'rm -rf "$work"' EXIT
export SCANLOC_FUZZ_TMPDIR="$work"
failed=()
printf '%-16s %10s %8s %8s %8s  %s\n' target executions exec/s cov ft result
for target in "${targets[@]}"; do
  fuzzer="$build_dir/fuzz/${target}_fuzzer"
  [ -x "$fuzzer" ] || { echo "fuzz: no fuzzer $fuzzer"; exit 2; }
  mkdir -p "$work/$target" "$artifacts/$target"
  cp -r "fuzz/corpus/$target/." "$work/$target/"
  dict=()
  [ -f "fuzz/dictionaries/$target.dict" ] && dict=(-dict="fuzz/dictionaries/$target.dict")
  log="$artifacts/$target/fuzz.log"
  status=0
  # One process at a time, niced: the machine is shared.
  nice -n 10 "$fuzzer" "$work/$target" "${dict[@]}" \
    -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1 \
    -artifact_prefix="$artifacts/$target/" >"$log" 2>&1 || status=$?
  # The last status line (#N DONE/pulse/NEW ... cov: C ft: F ... exec/s: E) and the final stats.
  stats=$(grep -E '^#[0-9]+' "$log" | tail -1 || true)
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$stats")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$stats")
  result=ok
  if [ "$status" -ne 0 ]; then
    crash=$(grep -o "Test unit written to .*" "$log" | tail -1 | sed 's/Test unit written to //')
    result="FAILED (exit $status) ${crash:-see $log}"
    failed+=("$target")
  fi
  printf '%-16s %10s %8s %8s %8s  %s\n' "$target" "${executions:-?}" "${rate:-?}" "${cov:-?}" \
    "${ft:-?}" "$result"
done
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: ${#failed[@]} target(s) failed: ${failed[*]}; logs in $artifacts/<target>/fuzz.log"
  for target in "${failed[@]}"; do
    echo "---- $target"
    grep -E -m1 -A12 "ERROR: |runtime error|contract broken|terminate called|deadly signal" \
      "$artifacts/$target/fuzz.log" || tail -20 "$artifacts/$target/fuzz.log"
  done
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, no crash"
