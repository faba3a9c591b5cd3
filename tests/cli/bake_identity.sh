#!/bin/sh
# lodbake-bake against the tools: a recipe over two small meshes and a glTF
# asset (written here), every step's files compared byte for byte with what
# the tool its step stands for writes with the same options (pack,
# simplify --pm, simplify --lods (and --error per level of a chain by
# errors), hierarchy --sections, fan, strips, pack --draco of
# the containers), an override changing one input's options, the JSON report
# listing every step as baked, one job per input and step (--asset --step, as
# a workflow engine runs them) giving the same bytes, and the exit codes of a
# bake where some or all inputs fail.
#
#   bake_identity.sh TOOLS DATA WORK [draco|nodraco]
# (nodraco: a build without the Draco codec; the package step stays compact)
set -eu
tools=$1 data=$2 work=$3 codec=${4:-draco}
draco=true draco_option="--draco --qp 12"
if [ "$codec" = nodraco ]; then
  draco=false draco_option=
fi
rm -rf "$work" && mkdir -p "$work/tools"
fail() { echo "bake_identity: $*" >&2; exit 1; }
same() { cmp "$1" "$2" > /dev/null || fail "$2 differs from $1"; }

cat > "$work/recipe.toml" <<TOML
version = 1
[vars]
data = "$data"
[inputs]
globs = ["{data}/meshes/igl_decimated-knight.off", "{data}/meshes/cgal_tetrahedron.off",
         "{data}/assets/Fox/*.gltf"]
[output]
path = "{dir}/{name}/{step}.lbk"
lods = "{dir}/{name}/lod{level}.{format}"
[steps.pack]
quantize = 14
[steps.simplify]
ratio = 0.25
placement = "half"
[steps.lods]
ratios = [0.5, 0.2]
[steps.hierarchy]
[steps.fan]
degree_weight = 1.5
[steps.strips]
[steps.package]
from = ["simplify", "hierarchy"]
draco = $draco
qp = 12
[[override]]
glob = "*/igl_decimated-knight.off"
[override.steps.strips]
strips_only = true
[override.steps.hierarchy]
sections = ["vhie"]
[override.steps.simplify]
triangles = 300
[[override]]
glob = "*/Fox.gltf"
[override.steps.lods]
errors = [0.002, 0.02]
TOML
"$tools/lodbake-bake" "$work/recipe.toml" --out "$work/out" --no-cache --json --quiet \
  > "$work/report.json"
grep -q '"schema": "lodbake.bake/1"' "$work/report.json" || fail "no report"
[ "$(grep -c '"status": "baked"' "$work/report.json")" = 21 ] || fail "not 21 steps baked"

check() {  # INPUT DIR NAME HIERARCHY_SECTIONS STRIPS_OPTION|- BY_ERROR SIMPLIFY_OPTIONS...
  input=$1 out=$work/out/$2/$3 sections=$4 t=$work/tools/$3 strips=$5 by_error=$6
  [ "$strips" = - ] && strips=
  shift 6
  "$tools/lodbake-pack" "$input" -o "$t.pack.lbk" --quantize 14 > /dev/null
  same "$t.pack.lbk" "$out/pack.lbk"
  "$tools/lodbake-simplify" "$input" --pm "$t.pm.lbk" --ratio 0.25 "$@" > /dev/null
  same "$t.pm.lbk" "$out/simplify.lbk"
  if [ "$by_error" = yes ]; then
    # A chain by errors: one run of the tool per error.
    "$tools/lodbake-simplify" "$input" --error 0.002 -o "$t.lod0.glb" --no-metrics > /dev/null
    "$tools/lodbake-simplify" "$input" --error 0.02 -o "$t.lod1.glb" --no-metrics > /dev/null
    cmp -s "$t.lod0.glb" "$t.lod1.glb" && fail "the two errors gave one level"
  else
    "$tools/lodbake-simplify" "$input" --lods 0.5,0.2 -o "$t.lod%d.glb" --no-metrics > /dev/null
  fi
  same "$t.lod0.glb" "$out/lod0.glb"
  same "$t.lod1.glb" "$out/lod1.glb"
  "$tools/lodbake-hierarchy" "$input" -o "$t.h.lbk" --sections "$sections" > /dev/null
  same "$t.h.lbk" "$out/hierarchy.lbk"
  "$tools/lodbake-fan" "$input" -o "$t.fan.lbk" --degree-weight 1.5 > /dev/null
  same "$t.fan.lbk" "$out/fan.lbk"
  "$tools/lodbake-strips" "$input" $strips -o "$t.strips.lbk" > /dev/null
  same "$t.strips.lbk" "$out/strips.lbk"
  "$tools/lodbake-pack" "$t.pm.lbk" "$t.h.lbk" $draco_option -o "$t.pkg.lbk" > /dev/null
  same "$t.pkg.lbk" "$out/package.lbk"
}
check "$data/meshes/igl_decimated-knight.off" meshes igl_decimated-knight.off vhie --strips-only \
  no --triangles 300
check "$data/meshes/cgal_tetrahedron.off" meshes cgal_tetrahedron.off vhie,dage,vtre - no
check "$data/assets/Fox/Fox.gltf" Fox Fox.gltf vhie,dage,vtre - yes

# One job per input and step, as a workflow engine runs them (package
# reading the files of the steps it merges): the same bytes as one bake.
for input in "$data/meshes/igl_decimated-knight.off" "$data/assets/Fox/Fox.gltf"; do
  for step in pack simplify lods hierarchy fan strips package; do
    "$tools/lodbake-bake" "$work/recipe.toml" --out "$work/jobs" --no-cache --quiet \
      --asset "$input" --step $step > /dev/null
  done
done
diff -r "$work/jobs/meshes/igl_decimated-knight.off" "$work/out/meshes/igl_decimated-knight.off" \
  > /dev/null || fail "--asset --step jobs differ from the bake (mesh)"
diff -r "$work/jobs/Fox" "$work/out/Fox" > /dev/null || fail "--asset --step jobs differ (asset)"
[ ! -e "$work/jobs/meshes/cgal_tetrahedron.off" ] || fail "--asset baked another input"
code=0
"$tools/lodbake-bake" "$work/recipe.toml" --out "$work/alone" --no-cache --quiet \
  --asset "$data/meshes/cgal_tetrahedron.off" --step package 2> "$work/alone.err" || code=$?
[ "$code" = 9 ] || fail "package without its steps' files: exit $code, not 9"
grep -q "simplify.lbk: cannot open.*(run step simplify first)" "$work/alone.err" ||
  fail "package without its steps' files: not said"

# Some inputs fail (a file that is not a mesh): 8 with --keep-going, the
# others baked; stopped at the first failure (--jobs 1, the largest input
# first) before any input baked: 9. No output of a failed step is left.
# Larger than the tetrahedron, so that it starts first (largest first).
{ printf 'not a mesh\n' && head -c 4096 /dev/zero | tr '\0' x; } > "$work/a_broken.off"
cp "$data/meshes/cgal_tetrahedron.off" "$work/b_tetrahedron.off"
cat > "$work/partly.toml" <<TOML
[inputs]
globs = ["*.off"]
[steps.pack]
TOML
code=0
"$tools/lodbake-bake" "$work/partly.toml" --out "$work/partly" --no-cache --keep-going --quiet ||
  code=$?
[ "$code" = 8 ] || fail "some failed: exit $code, not 8"
[ -f "$work/partly/b_tetrahedron.off/pack.lbk" ] || fail "the good input was not baked"
[ ! -e "$work/partly/a_broken.off/pack.lbk" ] || fail "a failed step left its output"
code=0
"$tools/lodbake-bake" "$work/partly.toml" --out "$work/stopped" --no-cache --jobs 1 --quiet \
  2> "$work/stopped.err" ||
  code=$?
[ "$code" = 9 ] || fail "stopped at the first input: exit $code, not 9"
grep -q "a_broken.off: pack: " "$work/stopped.err" || fail "the failure is not named"
[ ! -e "$work/stopped/b_tetrahedron.off" ] || fail "the run went on without --keep-going"
echo "bake_identity: every step's files equal the tools'"
