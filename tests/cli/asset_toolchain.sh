#!/bin/sh
# An asset through the toolchain, as a user runs it:
#   inspect ASSET -> pack -> inspect --validate --extract (.glb and .gltf)
#   -> simplify --lods 0.5,0.25 (.glb)
#   -> hierarchy, fan, strips, simplify --pm (from the asset and from its
#      container) -> inspect --validate, replay --validate (vhier, dag,
#      stream and vtrees on the hierarchy, fan, sets on the strips: every
#      recovered LoD's corners have their wedges) -> inspect --extract --lod
#      0.5 and 1.0 of the hierarchy's and the strips' progressive meshes
#   -> simplify --pm with default options (every collapse) -> inspect
#      --extract --lod 0, 0.25, 0.5 and 1.0 (.glb; 0.25 also as .gltf)
#   -> pack --draco of that PM -> inspect --validate, --extract --lod 0.5
# Every output keeps the asset: lodbake's own scene report of each equals
# the input's (every count for the copies; for the PM's full level all but
# its vertex layout; for the levels all but triangle, vertex, point and
# seam counts: every primitive stays, with its material and attributes),
# Khronos's validator finds no error the input does not already have, and
# gltf-transform's inspect lists the same scenes, meshes (with their
# primitives and attributes), materials, textures and animations. Corner
# by corner (tests/npm/same_triangles.mjs: every triangle with every
# attribute value of its corners, exactly): the PM's full level is the
# input (and so are the hierarchy's and the strips' PMs' full levels), its
# levels at 0.5 and 0.25 are simplify --lods' levels (the same
# collapse order), whether written as .gltf or extracted from the Draco
# container (a Draco BASE is lossy in positions, but a level's corners take
# their points from the asset's SCNE, so no tolerance is needed). An asset
# that is not glTF (an OBJ with materials) is its own reference for
# lodbake's report; for the validator (no error at all), the inventory and
# the triangles the reference is the .glb its container gives back.
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

# The "scene" object of an inspect report, without what a level changes;
# for a PM's full level, without its primitives' vertex layout (a
# non-indexed input, Fox's, comes back indexed: corners with equal values
# share a vertex).
scene_of() {  # FILE JSON-REPORT MODE(copy|full|level)
  node -e '
    const r = JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"));
    const s = r.scene;
    if (!s) { console.error("no scene in the report"); process.exit(1); }
    if (process.argv[2] === "full") {
      for (const m of s.meshes) for (const p of m.primitives) { delete p.vertices; delete p.indexed; }
    }
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
scene_of "$work/input.json" full > "$work/input.full"
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
build() {  # NAME REPLAY-MODES TOOL OPTION...: TOOL ASSET OPTION... NAME.lbk
  name=$1 modes=$2 tool=$3
  shift 3
  "$tools/$tool" "$asset" "$@" "$work/$name.lbk" -q > /dev/null || fail "$name"
  "$tools/$tool" "$work/asset.lbk" "$@" "$work/${name}_2.lbk" -q > /dev/null \
    || fail "$name from the container"
  cmp -s "$work/$name.lbk" "$work/${name}_2.lbk" || fail "$name from the container differs"
  "$tools/lodbake-inspect" "$work/$name.lbk" --validate -q > /dev/null \
    || fail "inspect --validate $name.lbk"
  for mode in $(echo "$modes" | tr , ' '); do
    case $mode in
      none) continue ;;
      # Not camera-driven; the paper's tests take minutes on SheenCloth's
      # 58k LoDs, one short test takes seconds.
      sets) path="--percent 0.2 --spacing linear" ;;
      *) path="--path orbit" ;;
    esac
    # shellcheck disable=SC2086
    "$tools/lodbake-replay" "$work/$name.lbk" --mode "$mode" $path --validate -q > /dev/null \
      || fail "replay $name.lbk --mode $mode"
  done
}
# The hierarchy's default sections (VHIE + RFIN, DAGE, VTRE) serve four modes.
build hierarchy vhier,dag,stream,vtrees lodbake-hierarchy -o
build fan fan lodbake-fan -o
build strips sets lodbake-strips -o
build strips_only none lodbake-strips --strips-only -o
build pm none lodbake-simplify --ratio 0.5 --pm
build pm_full none lodbake-simplify --pm

# The full PM's levels, and the same PM with a Draco BASE.
level() {  # CONTAINER LOD OUT
  "$tools/lodbake-inspect" "$work/$1" --extract "$work/$3" --lod "$2" -q > /dev/null \
    || fail "extract $3 from $1 at --lod $2"
}
level pm_full.lbk 0 pm_0.glb
level pm_full.lbk 0.25 pm_25.glb
level pm_full.lbk 0.25 gltf/pm_25.gltf
level pm_full.lbk 0.5 pm_50.glb
level pm_full.lbk 1.0 pm_100.glb
# The hierarchy's own progressive mesh (beside DAGE and VTRE) has its wedges.
level hierarchy.lbk 0.5 hier_50.glb
level hierarchy.lbk 1.0 hier_100.glb
# So has the strips' progressive mesh under the SETS graph (WEDG).
level strips.lbk 0.5 strips_50.glb
level strips.lbk 1.0 strips_100.glb
# A build without the Draco codec (make test-nodraco) refuses --draco with
# exit 5: the Draco container's level is then left out.
draco=draco_50.glb
rc=0
"$tools/lodbake-pack" --draco "$work/pm_full.lbk" -o "$work/draco.lbk" -q > /dev/null \
  2> "$work/draco.err" || rc=$?
case $rc in
  0)
    "$tools/lodbake-inspect" "$work/draco.lbk" --validate -q > /dev/null \
      || fail "inspect --validate draco.lbk"
    level draco.lbk 0.5 draco_50.glb
    ;;
  5) draco="" ;;
  *) cat "$work/draco.err" >&2; fail "pack --draco pm_full.lbk" ;;
esac

scene_of "$work/container.json" copy > "$work/container.copy"
cmp -s "$work/input.copy" "$work/container.copy" || fail "the container's scene differs from the input's"
copies="back.glb gltf/back.gltf"
levels="lod_0.glb lod_1.glb pm_0.glb pm_25.glb gltf/pm_25.gltf pm_50.glb $draco pm_100.glb hier_50.glb hier_100.glb strips_50.glb strips_100.glb"
for out in $copies $levels; do
  "$tools/lodbake-inspect" "$work/$out" --json -q > "$work/out.json" || fail "inspect $out"
  case $out in
    pm_100.glb | hier_100.glb | strips_100.glb) mode=full ;;
    back.glb | gltf/back.gltf) mode=copy ;;
    *) mode=level ;;
  esac
  scene_of "$work/out.json" $mode > "$work/out.$mode"
  cmp -s "$work/input.$mode" "$work/out.$mode" || {
    diff "$work/input.$mode" "$work/out.$mode" >&2 || true
    fail "$out: its scene differs from the input's"
  }
done

# Each node check takes every file in one run (a node start and the
# reference's own inspection or validation are most of their time), from
# the work folder so that the lists are plain names.
absolute() { echo "$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"; }
reference=$(absolute "$reference") npm=$(absolute "$npm")
case $baseline in
  "") ;;
  *) baseline="--baseline $(absolute "$asset")" ;;
esac
cd "$work"
# shellcheck disable=SC2086
node "$scripts/validate.mjs" --modules "$npm" $baseline $allow $copies $levels > v.txt \
  || { cat v.txt >&2; fail "the validator found errors"; }
grep -v '^ ' v.txt
# shellcheck disable=SC2086
node "$scripts/same_inventory.mjs" --modules "$npm" "$reference" $copies --lod $levels \
  || fail "gltf-transform's inspect lists something else"
# shellcheck disable=SC2086
node "$scripts/same_triangles.mjs" --modules "$npm" "$reference" pm_100.glb hier_100.glb strips_100.glb \
  -- lod_0.glb pm_50.glb $draco -- lod_1.glb pm_25.glb gltf/pm_25.gltf \
  || fail "the PM's full level is not the input, or a level is not simplify's"
echo "ok: $asset"
