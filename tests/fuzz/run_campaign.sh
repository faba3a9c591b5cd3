#!/bin/bash
# Runs every libFuzzer target of a `make fuzz` build for SECONDS each, two at
# a time, each from a scratch copy of its seed corpus (the seeds in the tree
# stay as they are). Crashes, leaks, timeouts and out-of-memory inputs land
# in BUILD/fuzz-campaign/artifacts/; the script lists them and exits 1 when
# there is any, so a finding can be added to tests/fuzz/corpus/NAME/ as a
# regression seed once it is fixed.
#
#   tests/fuzz/run_campaign.sh BUILD SECONDS [NAME ...]
set -u
build=${1:?usage: run_campaign.sh BUILD SECONDS [NAME ...]}
seconds=${2:?usage: run_campaign.sh BUILD SECONDS [NAME ...]}
shift 2
source_dir=$(cd "$(dirname "$0")" && pwd)
work=$build/fuzz-campaign
rm -rf "$work" && mkdir -p "$work/artifacts" "$work/logs"
names=("$@")
if [ ${#names[@]} -eq 0 ]; then
  for seeds in "$source_dir"/corpus/*/; do names+=("$(basename "$seeds")"); done
fi
run_one() {
  local name=$1 binary=$build/tests/fuzz/fuzz_$1 dict=()
  if [ ! -x "$binary" ]; then
    echo "fuzz_$name: not built (make fuzz)"
    touch "$work/failed_$name"
    return
  fi
  [ -f "$source_dir/$name.dict" ] && dict=(-dict="$source_dir/$name.dict")
  cp -r "$source_dir/corpus/$name" "$work/corpus_$name"
  "$binary" "$work/corpus_$name" "${dict[@]}" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=4096 -artifact_prefix="$work/artifacts/$name-" >"$work/logs/$name.log" 2>&1
  local rc=$?
  if [ $rc -eq 0 ]; then
    echo "fuzz_$name: clean"
  else
    echo "fuzz_$name: FOUND (exit $rc, $work/logs/$name.log)"
    touch "$work/failed_$name"
  fi
}
export -f run_one
export build work source_dir seconds
printf '%s\n' "${names[@]}" | xargs -P 2 -I{} bash -c 'run_one {}'
if ! ls "$work"/failed_* >/dev/null 2>&1; then exit 0; fi
if [ -n "$(ls "$work/artifacts")" ]; then
  echo "inputs that failed:"
  ls -1 "$work/artifacts" | sed "s|^|  $work/artifacts/|"
fi
exit 1
