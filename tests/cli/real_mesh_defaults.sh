#!/bin/sh
# real_mesh_defaults.sh BIN MESH TMP: runs every tool that needs a 2-manifold
# on one real mesh with its default options (lodbake-simplify --pm,
# lodbake-hierarchy, lodbake-fan, lodbake-strips, lodbake-strips
# --strips-only). Each must succeed and say at most one line on stderr: the
# default repair takes any triangle mesh. Prints one row per run.
set -u
bin=$1
mesh=$2
tmp=$3
rm -rf "$tmp"
mkdir -p "$tmp"
failed=0
run() {
  label=$1
  shift
  "$@" > "$tmp/out" 2> "$tmp/err"
  rc=$?
  lines=$(wc -l < "$tmp/err")
  echo "$label: exit $rc, $lines stderr lines"
  if [ "$rc" -ne 0 ] || [ "$lines" -gt 1 ]; then
    cat "$tmp/err"
    failed=1
  fi
  rm -f "$tmp/o.lbk"
}
run "lodbake-simplify --pm" "$bin/lodbake-simplify" "$mesh" --pm "$tmp/o.lbk"
run "lodbake-hierarchy" "$bin/lodbake-hierarchy" "$mesh" -o "$tmp/o.lbk"
run "lodbake-fan" "$bin/lodbake-fan" "$mesh" -o "$tmp/o.lbk"
run "lodbake-strips" "$bin/lodbake-strips" "$mesh" -o "$tmp/o.lbk"
run "lodbake-strips --strips-only" "$bin/lodbake-strips" --strips-only "$mesh" -o "$tmp/o.lbk"
exit $failed
