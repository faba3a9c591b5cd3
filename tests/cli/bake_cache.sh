#!/bin/sh
# lodbake-bake's content cache: a cold bake fills it, a warm rerun bakes
# nothing (every step "cached") and writes the same bytes; a changed option
# reruns exactly the steps it reaches (simplify and the package merging it),
# a touched buffer of an asset reruns that asset's steps alone, --force
# bakes everything again, and --no-cache neither reads nor fills it.
#
#   bake_cache.sh TOOLS DATA WORK
set -eu
tools=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work/in"
fail() { echo "bake_cache: $*" >&2; exit 1; }
cp -r "$data/assets/Fox" "$work/in/"
cp "$data/meshes/igl_decimated-knight.off" "$work/in/"

recipe() {  # RATIO
  cat > "$work/recipe.toml" <<TOML
[inputs]
globs = ["in/*.off", "in/*/*.gltf"]
[steps.pack]
[steps.simplify]
ratio = $1
[steps.hierarchy]
[steps.package]
from = ["simplify", "hierarchy"]
TOML
}
# "STATUS STEP" per step of the JSON report, in order (each step object
# lists its status before its name).
bake() {  # OUT [OPTIONS...]
  out=$1
  shift
  "$tools/lodbake-bake" "$work/recipe.toml" --out "$work/$out" --cache "$work/cache" --json \
    --quiet "$@" > "$work/$out.json"
  awk -F'"' '/"status":/ { status = $4 } /"step":/ { print status, $4 }' "$work/$out.json" \
    > "$work/$out.steps"
}
expect() {  # RUN WANTED
  printf '%s\n' "$2" | cmp -s - "$work/$1.steps" || {
    cat "$work/$1.steps" >&2
    fail "$1: not the steps expected"
  }
}

recipe 0.5
bake cold
expect cold "baked pack
baked simplify
baked hierarchy
baked package
baked pack
baked simplify
baked hierarchy
baked package"
bake warm
expect warm "cached pack
cached simplify
cached hierarchy
cached package
cached pack
cached simplify
cached hierarchy
cached package"
diff -r "$work/cold" "$work/warm" > /dev/null || fail "a warm run wrote other bytes"

recipe 0.25
bake ratio
expect ratio "cached pack
baked simplify
cached hierarchy
baked package
cached pack
baked simplify
cached hierarchy
baked package"
cmp -s "$work/cold/Fox.gltf/simplify.lbk" "$work/ratio/Fox.gltf/simplify.lbk" &&
  fail "another ratio gave the same progressive mesh"

printf 'x' >> "$work/in/Fox/Fox.bin"
bake touched
expect touched "baked pack
baked simplify
baked hierarchy
baked package
cached pack
cached simplify
cached hierarchy
cached package"

bake forced --force
expect forced "baked pack
baked simplify
baked hierarchy
baked package
baked pack
baked simplify
baked hierarchy
baked package"
diff -r "$work/touched" "$work/forced" > /dev/null || fail "--force wrote other bytes"

entries=$(find "$work/cache" -name step.json | wc -l)
"$tools/lodbake-bake" "$work/recipe.toml" --out "$work/none" --no-cache --quiet
[ "$(find "$work/cache" -name step.json | wc -l)" = "$entries" ] || fail "--no-cache filled it"
diff -r "$work/forced" "$work/none" > /dev/null || fail "--no-cache wrote other bytes"
echo "bake_cache: warm runs bake nothing, changes rerun exactly their steps"
