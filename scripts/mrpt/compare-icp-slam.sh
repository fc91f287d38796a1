#!/usr/bin/env bash
# scanloc's default session beside MRPT's icp-slam (Debian's mrpt-apps, its shipped classic
# configuration) on every public log: the three Kümmerle logs and the five Radish logs with their
# noisy odometry. Both run one after the other on each log, in this one run, each timed as a whole
# process (user + system CPU seconds, peak resident memory) and scored on the same relations by
# `scanloc evaluate`. Prints the table of docs/BENCHMARKS.md (issue 19).
#   scripts/mrpt/compare-icp-slam.sh [OUT_DIR]   (default: build/icp-slam; logs in $SCANLOC_DATASETS)
# Needs: apt-get install mrpt-apps mrpt-common (not part of CI).
# Only icp-slam's input and output settings are changed: the rawlog, the output folder, no 3-D
# window, no 3-D scene and no periodic map dumps (LOG_FREQUENCY=0), so that it does no drawing work.
# The logs are converted by scripts/mrpt/carmen-to-robotlaser.py (read it: MRPT's converter needs
# the scan geometry spelled out and its timestamps in picoseconds).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-build/icp-slam}
source scripts/public-logs.sh compare-icp-slam
classic=/usr/share/mrpt/config_files/icp-slam/icp-slam_demo_classic.ini
for tool in icp-slam carmen2rawlog /usr/bin/time; do
  command -v "$tool" > /dev/null || { echo "compare-icp-slam: $tool is missing (apt-get install mrpt-apps mrpt-common time)" >&2; exit 2; }
done
[ -f "$classic" ] || { echo "compare-icp-slam: $classic is missing (apt-get install mrpt-common)" >&2; exit 2; }
mkdir -p "$out"
out=$(cd "$out" && pwd)

icp_slam_ini() {  # CLASSIC RAWLOG LOG_DIR > INI: the classic configuration, input and output only
  python3 - "$@" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
for key, value in [("rawlog_file", sys.argv[2]), ("logOutput_dir", sys.argv[3]),
                   ("SHOW_PROGRESS_3D_REAL_TIME", "0"), ("SAVE_3D_SCENE", "0"), ("LOG_FREQUENCY", "0")]:
    text, n = re.subn(r"(?m)^(\s*" + key + r"\s*=)[^\n]*", lambda m: m.group(1) + value, text)
    if n != 1:
        sys.exit(f"compare-icp-slam: {sys.argv[1]}: expected one '{key} =', found {n}")
print(text, end="")
PY
}

run_log() {  # NAME LOG RELATIONS
  local name=$1 log=$2 relations=$3 dir="$out/$1"
  echo "compare-icp-slam: $name" >&2
  mkdir -p "$dir"
  /usr/bin/time -f "%U %S %M" -o "$dir/scanloc.time" \
    "$scanloc" session --log "$log" --out "$dir/scanloc" --force --quiet > "$dir/scanloc.txt"
  "$scanloc" evaluate --trajectory "$dir/scanloc/trajectory.tum" --relations "$relations" --json \
    > "$dir/scanloc.evaluation.json"
  python3 scripts/mrpt/carmen-to-robotlaser.py "$log" "$dir/robotlaser.log"
  carmen2rawlog -q -w -i "$dir/robotlaser.log" -o "$dir/log.rawlog" > "$dir/carmen2rawlog.txt" 2>&1
  icp_slam_ini "$classic" "$dir/log.rawlog" "$dir/icp-slam" > "$dir/icp-slam.ini"
  /usr/bin/time -f "%U %S %M" -o "$dir/icp-slam.time" icp-slam "$dir/icp-slam.ini" > "$dir/icp-slam.txt" 2>&1
  python3 scripts/mrpt/path-to-tum.py "$dir/robotlaser.log.stamps" "$dir/icp-slam/log_estimated_path.txt" \
    "$dir/icp-slam.tum"
  # icp-slam's path is the robot's, as scanloc's trajectory is: both are scored through the laser's
  # mounting (the relations are the scans'), the one scanloc's run recorded.
  local mounting
  mounting=$(python3 -c "import json, sys; m = json.load(open(sys.argv[1]))['config']['mounting']; \
print(m['x_m'], m['y_m'], m['yaw_rad'])" "$dir/scanloc/summary.json")
  # shellcheck disable=SC2086
  "$scanloc" evaluate --trajectory "$dir/icp-slam.tum" --relations "$relations" \
    --mounting $mounting --json > "$dir/icp-slam.evaluation.json"
}

for log in intel aces fr079; do run_log "$log" "$datasets/$log.clf.gz" "$datasets/$log.relations"; done
for log in seattle orebro fhw edmonton acapulco; do
  run_log "$log" "$datasets/radish/$log.noisy.clf.gz" "$datasets/radish/$log.relations"
done

python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def cost(name, tool):
    user, system, peak_kb = open(f"{out}/{name}/{tool}.time").read().split()[-3:]
    return float(user) + float(system), float(peak_kb) / 1024
def error(name, tool):
    t = json.load(open(f"{out}/{name}/{tool}.evaluation.json"))["translation_m"]
    return f"{t['mean']:.3f} / {t['max']:.2f}"
print("| log | span [s] | scanloc CPU [s] | icp-slam CPU [s] | CPU ratio | scanloc peak [MB] "
      "| icp-slam peak [MB] | scanloc error mean / max [m] | icp-slam error mean / max [m] |")
print("|---|---|---|---|---|---|---|---|---|")
for name in ["intel", "aces", "fr079", "seattle", "orebro", "fhw", "edmonton", "acapulco"]:
    stamps = [float(s) for s in open(f"{out}/{name}/robotlaser.log.stamps")]
    (s_cpu, s_mb), (m_cpu, m_mb) = cost(name, "scanloc"), cost(name, "icp-slam")
    print(f"| {name} | {stamps[-1] - stamps[0]:.0f} | {s_cpu:.2f} | {m_cpu:.2f} | {s_cpu / m_cpu:.1f} "
          f"| {s_mb:.0f} | {m_mb:.0f} | {error(name, 'scanloc')} | {error(name, 'icp-slam')} |")
PY
