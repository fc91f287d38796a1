# Sourced by the scripts that run many scored sessions (robustness-sessions.sh,
# noise-sessions.sh): score_session OUT INDEX NAME LOG RELATIONS [SESSION_ARGS...] runs one
# session into OUT/pINDEX/NAME and scores it on RELATIONS, and on the local relations beside them
# (LOG.local.relations: scans <= 15 s apart) where they exist. A session or a score that fails is
# listed in OUT/failed. Needs `scanloc` (scripts/public-logs.sh).
score_session() {
  local out=$1 i=$2 name=$3 log=$4 relations=$5 dir="$1/p$2"
  shift 5
  # Nothing of an earlier run in OUT may be scored in place of this one.
  rm -rf "${dir:?}/$name" "$dir/$name".*
  if ! "$scanloc" session --log "$log" --out "$dir/$name" --force --quiet "$@" \
    > "$dir/$name.session.txt" 2>&1; then
    echo "p$i $name" >> "$out/failed"
    return 0
  fi
  "$scanloc" evaluate --trajectory "$dir/$name/trajectory.tum" --relations "$relations" --json \
    > "$dir/$name.evaluation.json" || echo "p$i $name" >> "$out/failed"
  local local_relations=${relations%.relations}.local.relations
  if [ -f "$local_relations" ]; then
    "$scanloc" evaluate --trajectory "$dir/$name/trajectory.tum" --relations "$local_relations" \
      --json > "$dir/$name.local.evaluation.json" || echo "p$i $name" >> "$out/failed"
  fi
}

# run_one INDEX NAME LOG RELATIONS: one session of a harness, with OUT's session arguments
# (OUT/session-args) and the perturbation's own (OUT/pINDEX/session-args, when there), both
# NUL-terminated; `out` (OUT) and `tag` (the harness's name, for the progress lines) exported.
run_one() {
  local args more=()
  mapfile -d '' -t args < "$out/session-args"
  [ -f "$out/p$1/session-args" ] && mapfile -d '' -t more < "$out/p$1/session-args"
  echo "$tag: $2, $(< "$out/p$1/perturbation")" >&2
  score_session "$out" "$@" "${args[@]}" "${more[@]}"
}

# run_harness TAG COUNT: every job of OUT/jobs (INDEX NAME LOG RELATIONS, NUL-terminated), JOBS
# at a time (default: the number of processors), then scripts/robustness-summary.py's table over
# COUNT perturbations. Needs `out` and `datasets`.
run_harness() {
  export -f run_one score_session
  export out scanloc tag=$1
  xargs -0 -n 4 -P "${JOBS:-$(nproc)}" bash -c 'run_one "$@"' run_one < "$out/jobs"
  SCANLOC_DATASETS="$datasets" python3 scripts/robustness-summary.py "$out" "$2"
}
