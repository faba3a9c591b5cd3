#!/bin/sh
# A textured OBJ mesh through the toolchain as an asset (asset_toolchain.sh),
# twice: with one material whose map_Kd is IMAGE, and with its faces split
# into two materials (a textured one and a plain one, so that builders meet
# a material border). Then the mesh as the file has it, texture coordinates
# without materials: a mesh for lodbake-pack (BASE, no SCNE), an asset for
# lodbake-simplify -o OUT.glb (TEXCOORD_0 kept, valid glTF).
#
#   obj_asset_toolchain.sh TOOLS NPM_DIR MESH.obj IMAGE.png WORK
set -eu
tools=$1 npm=$2 mesh=$3 image=$4 work=$5
here=$(cd "$(dirname "$0")" && pwd)
scripts=$here/../npm
rm -rf "$work" && mkdir -p "$work"
if [ ! -d "$npm/node_modules/gltf-validator" ] || ! command -v node > /dev/null; then
  echo "skipped: node or the npm test tools are missing (make npm-deps)" >&2
  exit 77
fi
fail() { echo "FAIL: $*" >&2; exit 1; }
name=$(basename "$mesh" .obj)

# One material, its image in a subfolder of the library's folder.
mkdir -p "$work/one/tex"
cp "$image" "$work/one/tex/albedo.png"
printf 'newmtl painted\nKd 1 1 1\nNs 50\nmap_Kd tex/albedo.png\n' > "$work/one/$name.mtl"
{ echo "mtllib $name.mtl"; echo "usemtl painted"; cat "$mesh"; } > "$work/one/$name.obj"

# Two materials: the first half of the faces textured, the rest plain red.
mkdir -p "$work/two/tex"
cp "$image" "$work/two/tex/albedo.png"
printf 'newmtl painted\nKd 1 1 1\nmap_Kd tex/albedo.png\nnewmtl red\nKd 0.8 0.1 0.1\nNs 20\n' \
  > "$work/two/$name.mtl"
faces=$(grep -c '^f ' "$mesh")
awk -v half=$((faces / 2)) -v lib="$name.mtl" '
  NR == 1 { print "mtllib " lib }
  /^f / { if (n == 0) print "usemtl painted"; if (n == half) print "usemtl red"; ++n }
  { print }' "$mesh" > "$work/two/$name.obj"

for variant in one two; do
  sh "$here/asset_toolchain.sh" "$tools" "$npm" "$work/$variant/$name.obj" \
    "$work/$variant/run" || fail "$variant: the asset toolchain"
done

# Texture coordinates alone: pack keeps it a mesh, simplify -o .glb an asset.
"$tools/lodbake-pack" "$mesh" -o "$work/plain.lbk" -q > /dev/null || fail "pack $mesh"
"$tools/lodbake-inspect" "$work/plain.lbk" > "$work/plain.txt" || fail "inspect plain.lbk"
grep -q '^  BASE' "$work/plain.txt" || fail "plain.lbk has no BASE"
! grep -q '^  SCNE' "$work/plain.txt" || fail "plain.lbk holds a scene: the OBJ has no materials"
"$tools/lodbake-simplify" "$mesh" --ratio 0.5 -o "$work/plain.glb" --json -q > "$work/plain.json" \
  || fail "simplify $mesh -o plain.glb"
grep -q '"asset": true' "$work/plain.json" || fail "simplify -o plain.glb did not take an asset"
"$tools/lodbake-inspect" "$work/plain.glb" > "$work/plain_glb.txt" || fail "inspect plain.glb"
grep -q 'TEXCOORD_0' "$work/plain_glb.txt" || fail "plain.glb lost its texture coordinates"
node "$scripts/validate.mjs" --modules "$npm" "$work/plain.glb" > "$work/v.txt" \
  || { cat "$work/v.txt" >&2; fail "plain.glb: the validator found errors"; }
echo "ok: $mesh as a textured asset, with two materials, and as a mesh with texture coordinates"
