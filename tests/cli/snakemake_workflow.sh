#!/bin/sh
# workflow/Snakefile against lodbake-bake: a recipe over a mesh, a glTF
# asset and an OBJ with materials, every step (package merging three, one
# skipped for one input by an override), run by Snakemake with --cores 2 into
# one folder and by lodbake-bake into another (recipe variables given
# through --config set=...): the same files, byte for byte.
# Then a rerun has nothing to do, a touched buffer of the glTF asset reruns
# that asset's steps alone, and a changed simplify ratio reruns only each
# input's simplify and the package that merges it.
# Exit 77 (skipped) when snakemake is not installed.
#
#   snakemake_workflow.sh TOOLS SOURCE DATA WORK
set -eu
tools=$1 src=$2 data=$3 work=$4
command -v snakemake > /dev/null || { echo "snakemake_workflow: snakemake missing: skipped"; exit 77; }
rm -rf "$work" && mkdir -p "$work"
fail() { echo "snakemake_workflow: $*" >&2; exit 1; }

cp "$src/tests/cli/bake/workflow.toml" "$work/recipe.toml"
# A copy of the inputs of {data}, whose buffer the test touches.
mkdir -p "$work/data/assets" "$work/data/meshes"
cp -r "$data/assets/Fox" "$work/data/assets/"
cp "$data/meshes/c3d_spot.obj" "$work/data/meshes/"
chmod -R u+w "$work/data"
data=$work/data

# Snakemake keeps its state in .snakemake/ of its working folder: the work folder.
cd "$work"
snake() {
  snakemake -s "$src/workflow/Snakefile" --cores 2 \
    --config recipe=recipe.toml out=snake bake="$tools/lodbake-bake" set="src=$src,data=$data" "$@"
}
snake > snake.log 2>&1 || { cat snake.log; fail "the workflow failed"; }
"$tools/lodbake-bake" recipe.toml --set "src=$src" --set "data=$data" --out bake --no-cache --quiet \
  > /dev/null \
  || fail "lodbake-bake failed"

# 3 inputs x 7 steps, lods giving two files, Fox without fan: 23 files.
(cd bake && find . -type f | sort) > bake.files
(cd snake && find . -type f | sort) > snake.files
[ "$(wc -l < bake.files)" = 23 ] || fail "lodbake-bake wrote $(wc -l < bake.files) files, not 23"
cmp bake.files snake.files > /dev/null || { diff bake.files snake.files; fail "not the same files"; }
while read -r file; do
  cmp "bake/$file" "snake/$file" || fail "$file differs"
done < bake.files

snake --dry-run > rerun.log 2>&1 || { cat rerun.log; fail "dry rerun failed"; }
grep -q "Nothing to be done" rerun.log || { cat rerun.log; fail "a rerun would bake again"; }

# A touched buffer of the asset: its steps alone (6, fan skipped).
touch data/assets/Fox/Fox.bin
snake --dry-run --quiet > touched.log 2>&1 || { cat touched.log; fail "dry run after a touch failed"; }
jobs=$(grep -E '^[a-z]+_[0-9]+ ' touched.log | sed 's/ .*//' | sort | tr '\n' ' ')
fox=$("$tools/lodbake-bake" recipe.toml --set "src=$src" --set "data=$data" --list \
  | grep -n '"input"' | grep -n Fox.gltf | cut -d: -f1)
index=$((fox - 1))
[ "$jobs" = "hierarchy_$index lods_$index pack_$index package_$index simplify_$index strips_$index " ] \
  || { cat touched.log; fail "a touched Fox.bin runs: $jobs"; }
snake > touched-run.log 2>&1 || { cat touched-run.log; fail "the rerun after a touch failed"; }

# A changed ratio: simplify of each input and the package merging it.
sed -i 's/^ratio = 0.5$/ratio = 0.4/' recipe.toml
snake --dry-run --quiet > changed.log 2>&1 || { cat changed.log; fail "dry run after a change failed"; }
jobs=$(grep -E '^(simplify|package|pack|lods|hierarchy|fan|strips)_[0-9]+ ' changed.log \
  | sed 's/_[0-9]* .*//' | sort | uniq -c | tr -s ' ' | tr '\n' ';')
[ "$jobs" = " 3 package; 3 simplify;" ] || { cat changed.log; fail "a changed ratio runs: $jobs"; }
echo "snakemake_workflow: Snakemake and lodbake-bake wrote the same 23 files"
