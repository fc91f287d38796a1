#!/usr/bin/env bash
# Issue 20, defect 2: a 273-byte PCD whose header announces 1.05 billion points of four floats
# made `scanloc test --point-map` allocate 16.8 GB inside PCL's reader before failing. The header
# is now checked against the file's size first: under a 2 GB address space (ulimit -v 2000000) the
# command must end with exit 1 and an error naming the file and the POINTS line, not bad_alloc or
# a signal.
#   scripts/reliability/huge-pcd.sh [SCANLOC]   (default ./build/apps/scanloc)
set -euo pipefail
cd "$(dirname "$0")/../.."
scanloc=$(realpath "${1:-./build/apps/scanloc}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
{
  printf '# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z spacing\n'
  printf 'SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH 1050000000\nHEIGHT 1\n'
  printf 'VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 1050000000\nDATA binary\n'
  head -c 16 /dev/zero
} > "$work/huge.pcd"
echo "huge-pcd: $(stat -c %s "$work/huge.pcd")-byte PCD announcing 1050000000 points"
set +e
(ulimit -v 2000000; "$scanloc" test --point-map "$work/huge.pcd" \
  --scan datasets/classroom/scan.scan --candidates datasets/classroom/candidates.txt) \
  > "$work/out.txt" 2> "$work/err.txt"
status=$?
set -e
echo "huge-pcd: exit $status: $(cat "$work/err.txt")"
if [[ $status -ne 1 ]] || ! grep -q "huge.pcd:10: 1050000000 points" "$work/err.txt" ||
   grep -q "bad_alloc" "$work/err.txt"; then
  echo "huge-pcd: FAILED (expected exit 1 and an error naming huge.pcd:10)"
  exit 1
fi
echo "huge-pcd: passed"
