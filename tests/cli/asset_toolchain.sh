#!/bin/sh
# An asset through the toolchain, as a user runs it:
#   inspect ASSET -> pack -> inspect --validate --extract (.glb and .gltf)
#   -> simplify --lods 0.5,0.25 (.glb)
#   -> hierarchy, fan, strips, simplify --pm (from the asset and from its
#      container) -> inspect --validate, replay --validate
# Every output keeps the asset: lodbake's own scene report of each equals
# the input's (every count for the copies; for the levels all but triangle,
# vertex, point and seam counts), Khronos's validator finds no error the
# input does not already have, and gltf-transform inspect lists the same
# scenes, meshes, materials, textures and animations. An asset that is not
# glTF (an OBJ with materials) is its own reference for lodbake's report;
# for the validator (no error at all) and the inventory the reference is the
# .glb its container gives back.
#
#   asset_toolchain.sh TOOLS NPM_DIR ASSET WORK [--allow-missing URI]
set -eu
tools=$1 npm=$2 asset=$3 work=$4
shift 4
allow="$*"
scripts=$(cd "$(dirname "$0")/../npm" && pwd)
rm -rf "$work" && mkdir -p "$work/gltf"
if [ ! -d "$npm/node_modules/gltf-validator" ] || ! command -v node > /dev/null; then
  echo "skipped: node or the npm test tools are missing (make npm-deps)" >&2
  exit 77
fi

fail() { echo "FAIL: $*" >&2; exit 1; }

# The "scene" object of an inspect report, without what a level changes.
scene_of() {  # FILE JSON-REPORT MODE(copy|level)
  node -e '
    const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
    const s = r.scene;
    if (!s) { console.error("no scene in the report"); process.exit(1); }
    if (process.argv[2] === "level") {
      delete s.triangles; delete s.instanced_triangles;
      for (const m of s.meshes) {
        for (const k of ["points", "triangles", "seam_points", "border_points"]) delete m[k];
        for (const p of m.primitives)
          for (const k of ["vertices", "triangles", "seam_points", "indexed", "mode"]) delete p[k];
      }
    }
    console.log(JSON.stringify(s));' "$1" "$2"
}

"$tools/lodbake-inspect" "$asset" --json -q > "$work/input.json" || fail "inspect $asset"
scene_of "$work/input.json" copy > "$work/input.copy"
scene_of "$work/input.json" level > "$work/input.level"

"$tools/lodbake-pack" "$asset" -o "$work/asset.lbk" -q > /dev/null || fail "pack"
"$tools/lodbake-inspect" "$work/asset.lbk" --validate --json -q > "$work/container.json" \
  || fail "inspect --validate the container"
"$tools/lodbake-inspect" "$work/asset.lbk" --extract "$work/back.glb" -q > /dev/null \
  || fail "extract .glb"
"$tools/lodbake-inspect" "$work/asset.lbk" --extract "$work/gltf/back.gltf" -q > /dev/null \
  || fail "extract .gltf"
"$tools/lodbake-simplify" "$asset" --lods 0.5,0.25 -o "$work/lod_%d.glb" -q > /dev/null \
  || fail "simplify --lods"
case $asset in
  *.gltf | *.glb) reference=$asset baseline="--baseline $asset" ;;
  *) reference=$work/back.glb baseline= ;;
esac

# Structures over the asset: each builder builds every mesh in its group,
# the same bytes from the asset and from its container, valid, replayed.
build() {  # NAME REPLAY-MODE TOOL OPTION...: TOOL ASSET OPTION... NAME.lbk
  name=$1 mode=$2 tool=$3
  shift 3
  "$tools/$tool" "$asset" "$@" "$work/$name.lbk" -q > /dev/null || fail "$name"
  "$tools/$tool" "$work/asset.lbk" "$@" "$work/${name}_2.lbk" -q > /dev/null \
    || fail "$name from the container"
  cmp -s "$work/$name.lbk" "$work/${name}_2.lbk" || fail "$name from the container differs"
  "$tools/lodbake-inspect" "$work/$name.lbk" --validate -q > /dev/null \
    || fail "inspect --validate $name.lbk"
  case $mode in
    none) ;;
    # Not camera-driven; the paper's tests take minutes on SheenCloth's
    # 58k LoDs, one short test takes seconds.
    sets) path="--percent 0.2 --spacing linear" ;;
    *) path="--path orbit" ;;
  esac
  if [ "$mode" != none ]; then
    # shellcheck disable=SC2086
    "$tools/lodbake-replay" "$work/$name.lbk" --mode "$mode" $path --validate -q > /dev/null \
      || fail "replay $name.lbk --mode $mode"
  fi
}
build hierarchy vhier lodbake-hierarchy -o
build fan fan lodbake-fan -o
build strips sets lodbake-strips -o
build strips_only none lodbake-strips --strips-only -o
build pm none lodbake-simplify --ratio 0.5 --pm

scene_of "$work/container.json" copy > "$work/container.copy"
cmp -s "$work/input.copy" "$work/container.copy" || fail "the container's scene differs from the input's"
for out in back.glb gltf/back.gltf lod_0.glb lod_1.glb; do
  "$tools/lodbake-inspect" "$work/$out" --json -q > "$work/out.json" || fail "inspect $out"
  case $out in
    lod_*) mode=level inventory=--lod ;;
    *) mode=copy inventory= ;;
  esac
  scene_of "$work/out.json" $mode > "$work/out.$mode"
  cmp -s "$work/input.$mode" "$work/out.$mode" || {
    diff "$work/input.$mode" "$work/out.$mode" >&2 || true
    fail "$out: its scene differs from the input's"
  }
  # shellcheck disable=SC2086
  node "$scripts/validate.mjs" --modules "$npm" $baseline $allow "$work/$out" > "$work/v.txt" \
    || { cat "$work/v.txt" >&2; fail "$out: the validator found errors"; }
  head -1 "$work/v.txt"
  # shellcheck disable=SC2086
  node "$scripts/same_inventory.mjs" --modules "$npm" $inventory "$reference" "$work/$out" \
    || fail "$out: gltf-transform inspect lists something else"
done
echo "ok: $asset"
