#!/bin/sh
# An asset's progressive mesh with its wedges through lodbake-pack's codecs:
#   simplify --pm -> pack (compact, WEDG included) and pack --draco
#   -> inspect --validate -> inspect --extract --lod 0.5
# The level extracted from the compact container is byte for byte the one
# from the raw container (the compact codecs are lossless); the levels from
# the compact and the draco containers pass Khronos's validator with no
# error the input does not already have.
#
#   wedg_compact_toolchain.sh TOOLS NPM_DIR ASSET WORK
set -eu
tools=$1 npm=$2 asset=$3 work=$4
scripts=$(cd "$(dirname "$0")/../npm" && pwd)
rm -rf "$work" && mkdir -p "$work"

fail() { echo "FAIL: $*" >&2; exit 1; }

"$tools/lodbake-simplify" -q "$asset" --pm "$work/p.lbk" > /dev/null || fail "simplify --pm"
"$tools/lodbake-pack" -q "$work/p.lbk" -o "$work/c.lbk" > /dev/null || fail "pack"
# A build without the Draco codec (make test-nodraco) refuses --draco with
# exit 5: the draco container is then left out.
packed="c d"
rc=0
"$tools/lodbake-pack" -q --draco "$work/p.lbk" -o "$work/d.lbk" > /dev/null 2> "$work/d.err" || rc=$?
case $rc in
  0) ;;
  5) packed="c" ;;
  *) cat "$work/d.err" >&2; fail "pack --draco" ;;
esac
for c in $packed; do
  "$tools/lodbake-inspect" "$work/$c.lbk" > "$work/$c.txt" || fail "inspect $c.lbk"
  grep -q "WEDG  compact" "$work/$c.txt" || fail "$c.lbk does not store WEDG compact"
  "$tools/lodbake-inspect" "$work/$c.lbk" --validate -q > /dev/null || fail "inspect --validate $c.lbk"
done
for c in p $packed; do
  "$tools/lodbake-inspect" "$work/$c.lbk" --extract "$work/$c.glb" --lod 0.5 -q > /dev/null \
    || fail "extract --lod 0.5 from $c.lbk"
done
cmp -s "$work/p.glb" "$work/c.glb" || fail "the compact container's level differs from the raw one's"
if [ ! -d "$npm/node_modules/gltf-validator" ] || ! command -v node > /dev/null; then
  echo "skipped the validator: node or the npm test tools are missing (make npm-deps)" >&2
  exit 77
fi
for c in $packed; do
  node "$scripts/validate.mjs" --modules "$npm" --baseline "$asset" "$work/$c.glb" > "$work/v.txt" \
    || { cat "$work/v.txt" >&2; fail "$c.glb: the validator found errors"; }
  head -1 "$work/v.txt"
done
echo "ok: $asset"
