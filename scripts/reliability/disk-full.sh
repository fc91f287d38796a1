#!/usr/bin/env bash
# Issue 20, defect 3: when the disk filled while map.pcd was written, PCL's memory-mapped writer
# died of SIGBUS and left map.pcd.tmp-PID-N behind. Runs a classroom session into a tmpfs too small
# for its outputs; the session must exit non-zero with an error naming the file and the reason
# ("No space left on device"), and leave no temporary file. Needs root for mount; skips (exit 0)
# with a message otherwise.
#   scripts/reliability/disk-full.sh [SCANLOC] [SIZE]   (default ./build/apps/scanloc, 580k)
# tmpfs counts whole 4 kB pages: with 580k (145 pages) iterations.jsonl (567 kB, 139 pages) and
# trajectory.tum (2 pages) fit and map.pcd (25 kB, 7 pages) does not, so the failure happens while
# map.pcd is written. A smaller SIZE makes iterations.jsonl fail instead.
set -euo pipefail
cd "$(dirname "$0")/../.."
scanloc=$(realpath "${1:-./build/apps/scanloc}")
size=${2:-580k}
mount_point=$(mktemp -d)
work=$(mktemp -d)
cleanup() { umount "$mount_point" 2>/dev/null || true; rmdir "$mount_point"; rm -rf "$work"; }
trap cleanup EXIT
if ! mount -t tmpfs -o size="$size" tmpfs "$mount_point" 2>/dev/null; then
  echo "disk-full: SKIPPED (cannot mount a tmpfs here; run as root)"
  exit 0
fi
set +e
"$scanloc" session --log datasets/classroom/classroom.seq.jsonl \
  --line-map datasets/classroom/classroom.lines --initial-pose 1.126 3.112 0.0463 \
  --out "$mount_point/run" --quiet > "$work/out.txt" 2> "$work/err.txt"
status=$?
set -e
echo "disk-full: exit $status on a $size tmpfs: $(tail -c 300 "$work/err.txt")"
ls -la "$mount_point/run" || true
leftovers=$(find "$mount_point" -name '*.tmp*' | wc -l)
failed=0
if [[ $status -eq 0 ]]; then echo "disk-full: the session claimed success"; failed=1; fi
if [[ $status -gt 128 ]]; then echo "disk-full: killed by signal $((status - 128))"; failed=1; fi
if ! grep -q "No space left on device" "$work/err.txt"; then
  echo "disk-full: no clear error (expected 'No space left on device')"; failed=1
fi
if [[ $leftovers -ne 0 ]]; then echo "disk-full: $leftovers temporary files left"; failed=1; fi
if [[ $failed -ne 0 ]]; then echo "disk-full: FAILED"; exit 1; fi
echo "disk-full: passed"
