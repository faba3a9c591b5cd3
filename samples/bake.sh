#!/usr/bin/env bash
# The end-to-end bake `make run` runs on the embedded sample: check the mesh,
# pack it (float32 and quantized), validate both containers, extract the base
# mesh as GLB and check that again, simplify it to a mesh, an LOD chain and a
# progressive mesh whose full refinement is checked again, repack that
# (compact VSPL, Draco BASE), build the balanced hierarchy with its split DAG
# and vertex trees, the fan-merge hierarchy, strips and the SETS graph and
# validate them, print a summary of the sizes, and end by replaying the scan
# camera path on the hierarchy, the split DAG (all three traversals) and the
# fan hierarchy, the LoD-recovery tests on the SETS graph, and the streaming
# of the hierarchy and of its vertex trees from a server to a client in one
# process, every frame validated, each printing its summary (and the first
# four their charts).
#   LODBAKE_BIN=build/tools samples/bake.sh OUT_DIR
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
bin=${LODBAKE_BIN:-build/tools}
out=${1:-build/sample}
mesh="$here/elephant.off"
mkdir -p "$out"

step() { printf '\n== %s\n' "$*"; }

step "1. check the input mesh (lodbake-inspect --strict)"
"$bin/lodbake-inspect" --strict "$mesh"

step "2. pack it into a container (lodbake-pack)"
"$bin/lodbake-pack" "$mesh" -o "$out/elephant.lbk"
"$bin/lodbake-pack" "$mesh" --quantize 16 -o "$out/elephant-q16.lbk"

step "3. inspect and validate the containers (lodbake-inspect --validate)"
"$bin/lodbake-inspect" --validate "$out/elephant.lbk"
"$bin/lodbake-inspect" --validate --quiet "$out/elephant-q16.lbk" > /dev/null

step "4. extract the base mesh and check it again"
"$bin/lodbake-inspect" -q "$out/elephant.lbk" --extract "$out/elephant.glb" > /dev/null
"$bin/lodbake-inspect" -q --strict "$out/elephant.glb" > /dev/null

step "5. simplify it, recording the progressive mesh (lodbake-simplify)"
"$bin/lodbake-simplify" "$mesh" --ratio 0.1 -o "$out/elephant-10.obj" --pm "$out/elephant-pm.lbk"
"$bin/lodbake-simplify" -q "$mesh" --lods 0.5,0.25,0.1 -o "$out/elephant-lod%d.glb"
"$bin/lodbake-inspect" --validate --quiet "$out/elephant-pm.lbk" > /dev/null
"$bin/lodbake-inspect" -q "$out/elephant-pm.lbk" --extract "$out/elephant-pm-full.obj" --lod 1.0 > /dev/null
"$bin/lodbake-inspect" --strict -q "$out/elephant-pm-full.obj" | grep -E '^(triangles|genus|problems)'

step "6. balanced vertex hierarchy, split DAG and vertex trees (lodbake-hierarchy)"
"$bin/lodbake-hierarchy" "$mesh" -o "$out/elephant-hierarchy.lbk"
"$bin/lodbake-inspect" --validate "$out/elephant-hierarchy.lbk" |
  grep -E '^(VHIE|RFIN|VSPL|DAGE|VTRE|validation)'

step "7. build the fan-merge hierarchy (lodbake-fan, compared with the balanced vertex hierarchy) and validate it"
"$bin/lodbake-fan" "$mesh" -o "$out/elephant-fan.lbk" --compare
"$bin/lodbake-inspect" --validate "$out/elephant-fan.lbk" | grep -E '^(FANH|validation)'

step "8. triangle strips and the SETS strip graph (lodbake-strips)"
"$bin/lodbake-strips" "$mesh" -o "$out/elephant-sets.lbk"
"$bin/lodbake-inspect" --validate "$out/elephant-sets.lbk" | grep -E '^(SETS|validation)'
"$bin/lodbake-strips" -q --strips-only "$mesh" -o "$out/elephant-strips.lbk" > /dev/null
"$bin/lodbake-inspect" -q --validate "$out/elephant-strips.lbk" --extract "$out/elephant-strips.obj" > /dev/null
"$bin/lodbake-inspect" --strict -q "$out/elephant-strips.obj" | grep -E '^(triangles|problems)'

step "9. repack the progressive mesh: compact VSPL, Draco BASE (lodbake-pack)"
"$bin/lodbake-pack" "$out/elephant-pm.lbk" --draco -o "$out/elephant-pm-packed.lbk"
"$bin/lodbake-inspect" --validate --quiet "$out/elephant-pm-packed.lbk" > /dev/null

size() { stat -c %s "$1"; }
step "summary"
printf '%-28s %10s bytes\n' "input elephant.off" "$(size "$mesh")"
printf '%-28s %10s bytes\n' "elephant.lbk (float32)" "$(size "$out/elephant.lbk")"
printf '%-28s %10s bytes\n' "elephant-q16.lbk (16 bits)" "$(size "$out/elephant-q16.lbk")"
printf '%-28s %10s bytes\n' "elephant.glb (extracted)" "$(size "$out/elephant.glb")"
printf '%-28s %10s bytes\n' "elephant-pm.lbk (full PM)" "$(size "$out/elephant-pm.lbk")"
printf '%-28s %10s bytes\n' "elephant-pm-packed.lbk" "$(size "$out/elephant-pm-packed.lbk")"
printf '%-28s %10s bytes\n' "elephant-10.obj (10%)" "$(size "$out/elephant-10.obj")"
printf '%-28s %10s bytes\n' "elephant-hierarchy.lbk" "$(size "$out/elephant-hierarchy.lbk")"
printf '%-28s %10s bytes\n' "elephant-fan.lbk (FANH)" "$(size "$out/elephant-fan.lbk")"
printf '%-28s %10s bytes\n' "elephant-sets.lbk (SETS)" "$(size "$out/elephant-sets.lbk")"
step "10. replay the baked structures (lodbake-replay, every frame validated, charts drawn with gnuplot)"
"$bin/lodbake-replay" "$out/elephant-hierarchy.lbk" --mode vhier --path scan --validate \
  --csv "$out/elephant-replay-scan.csv" --plot "$out/plots-vhier"
"$bin/lodbake-replay" "$out/elephant-hierarchy.lbk" --mode dag --traversal all --path scan --validate \
  --csv "$out/elephant-replay-dag-scan.csv" --plot "$out/plots-dag"
"$bin/lodbake-replay" "$out/elephant-fan.lbk" --mode fan --path scan --validate --plot "$out/plots-fan"
"$bin/lodbake-replay" "$out/elephant-sets.lbk" --mode sets --percent 1,3 --validate \
  --plot "$out/plots-sets"
"$bin/lodbake-replay" "$out/elephant-hierarchy.lbk" --mode stream --path scan --validate
"$bin/lodbake-replay" "$out/elephant-hierarchy.lbk" --mode vtrees --path scan --validate
echo
echo "all steps passed; outputs in $out, charts in $out/plots-{vhier,dag,fan,sets}"
