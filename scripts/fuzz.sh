#!/usr/bin/env bash
# Runs every libFuzzer target of a DAEP_FUZZ build, one after the other.
# usage: scripts/fuzz.sh BUILD_DIR LIBFUZZER_FLAG... [-- TARGET...]
#   e.g. scripts/fuzz.sh build-san -max_total_time=60
#        scripts/fuzz.sh build-san -runs=1000000 -- rawlog eth_ucy
# New inputs go to BUILD_DIR/fuzz/corpus/<target> (the tree's tests/fuzz/corpus/<target> is
# read, never written); crashes, hangs (-timeout) and out-of-memory inputs to
# BUILD_DIR/fuzz/artifacts/<target>/. Exits non-zero on the first finding.
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1
shift
flags=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  flags+=("$1")
  shift
done
[ $# -gt 0 ] && shift
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(experiment_ini benchmark_config world_file gazebo_import eth_ucy rawlog)
fi

for t in "${targets[@]}"; do
  exe="$build/tests/fuzz/fuzz_$t"
  if [ ! -x "$exe" ]; then
    echo "fuzz.sh: $exe missing: build with DAEP_FUZZ=ON (make sanitize-build)" >&2
    exit 1
  fi
  work="$build/fuzz/corpus/$t"
  artifacts="$build/fuzz/artifacts/$t"
  mkdir -p "$work" "$artifacts"
  echo "== fuzz_$t ${flags[*]}"
  start=$SECONDS
  # -timeout: an input that takes longer is a hang; -rss_limit_mb: more memory is an OOM.
  "$exe" "$work" tests/fuzz/corpus/"$t" -timeout=25 -rss_limit_mb=2048 \
      -artifact_prefix="$artifacts/" -print_final_stats=1 "${flags[@]}" \
      > "$build/fuzz/$t.log" 2>&1 || {
    tail -n 60 "$build/fuzz/$t.log"
    echo "fuzz_$t: FAILED after $((SECONDS - start)) s; inputs in $artifacts/" >&2
    exit 1
  }
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$build/fuzz/$t.log" |
      tr '\n' ' '
  echo "($((SECONDS - start)) s)"
done
