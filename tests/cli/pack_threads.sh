#!/bin/sh
# lodbake-pack writes the same bytes for --threads 1, 2, 7 and 0 (every
# core): merging the bunny's progressive mesh, hierarchy, fan and strips
# containers with Draco, whose sections after BASE are coded side by side,
# and packing the mesh itself, whose check runs in parts. CODEC is draco, or
# nodraco for a build without the Draco codec (the merge is then compact
# only).
#
#   pack_threads.sh TOOLS DATA WORK CODEC
set -eu
tools=$1 data=$2 work=$3 codec=$4
draco=""
[ "$codec" = nodraco ] || draco=--draco
rm -rf "$work" && mkdir -p "$work"
fail() { echo "pack_threads: $*" >&2; exit 1; }
mesh=$data/meshes/stanford_bun_zipper.ply
"$tools/lodbake-simplify" "$mesh" --pm "$work/pm.lbk" --no-metrics --quiet > /dev/null ||
  fail "simplify failed"
for tool in hierarchy fan strips; do
  "$tools/lodbake-$tool" "$mesh" -o "$work/$tool.lbk" --quiet > /dev/null || fail "$tool failed"
done
for n in 1 2 7 0; do
  "$tools/lodbake-pack" "$work/pm.lbk" "$work/hierarchy.lbk" "$work/fan.lbk" "$work/strips.lbk" \
    $draco --threads $n --quiet -o "$work/merged$n.lbk" > /dev/null 2> "$work/err.txt" ||
    fail "--threads $n: merging failed: $(cat "$work/err.txt")"
  "$tools/lodbake-pack" "$mesh" --threads $n --quiet -o "$work/mesh$n.lbk" > /dev/null \
    2> "$work/err.txt" || fail "--threads $n: packing the mesh failed: $(cat "$work/err.txt")"
done
[ -s "$work/merged1.lbk" ] || fail "empty output"
for n in 2 7 0; do
  for f in merged mesh; do
    cmp "$work/${f}1.lbk" "$work/$f$n.lbk" > /dev/null ||
      fail "--threads $n: $f$n.lbk differs from --threads 1's"
  done
done
echo "pack_threads: --threads 1, 2, 7 and 0 wrote the same bytes"
