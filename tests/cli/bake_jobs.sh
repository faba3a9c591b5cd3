#!/bin/sh
# lodbake-bake --jobs: a recipe over four inputs (two meshes, a glTF asset
# and an OBJ with materials) baked with --jobs 1 and --jobs 2 gives the same
# files byte for byte and the same JSON report but for its timings; plain
# progress lines (stderr is not a terminal) name every input once, and
# --quiet prints nothing on stderr.
#
#   bake_jobs.sh TOOLS DATA WORK
set -eu
tools=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "bake_jobs: $*" >&2; exit 1; }

cat > "$work/recipe.toml" <<TOML
[inputs]
globs = ["$data/meshes/igl_decimated-knight.off", "$data/meshes/cgal_tetrahedron.off",
         "$data/assets/Duck/Duck.glb", "$data/meshes/c3d_spot.obj"]
[output]
path = "{name}/{step}.lbk"
[steps.pack]
[steps.simplify]
ratio = 0.5
[steps.lods]
ratios = [0.5, 0.25]
[steps.hierarchy]
[steps.fan]
[steps.package]
TOML
for jobs in 1 2; do
  "$tools/lodbake-bake" "$work/recipe.toml" --out "$work/j$jobs" --jobs $jobs --no-cache --json \
    > "$work/j$jobs.json" 2> "$work/j$jobs.err"
  # The report without its timings, and the output folder named alike.
  grep -v '"seconds"' "$work/j$jobs.json" | sed "s|$work/j$jobs|OUT|g" > "$work/j$jobs.report"
done
[ "$(find "$work/j1" -type f | wc -l)" -ge 24 ] || fail "fewer files than steps"
diff -r "$work/j1" "$work/j2" > /dev/null || fail "--jobs 1 and --jobs 2 wrote different files"
cmp "$work/j1.report" "$work/j2.report" > /dev/null || fail "the reports differ beyond timings"
for err in "$work/j1.err" "$work/j2.err"; do
  [ "$(grep -c '^lodbake-bake: \[[1-4]/4\] .*: ok in ' "$err")" = 4 ] || fail "progress: $err"
done
"$tools/lodbake-bake" "$work/recipe.toml" --out "$work/q" --jobs 2 --no-cache --quiet \
  > /dev/null 2> "$work/q.err"
[ ! -s "$work/q.err" ] || fail "--quiet printed on stderr"
diff -r "$work/j1" "$work/q" > /dev/null || fail "a third run wrote different files"
echo "bake_jobs: --jobs 1 and --jobs 2 give the same bytes"
