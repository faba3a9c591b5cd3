#!/usr/bin/env bash
# lodbake-bake on the sample recipe over the shared data (docs/benchmarks.md
# "Batch baking"): wall and CPU seconds with --jobs 1 and --jobs 2 (no cache;
# goal: 1.8x on two cores), then a cold run filling a fresh cache and a warm
# rerun into the same folder (goal: under 2 s), whose outputs must equal the
# cold run's (checked: a warm run that bakes anything or writes other bytes
# fails the benchmark). Times depend on the machine's load; sizes do not.
#
#   tests/bench/bake_sample.sh BIN_DIR SHARED_DATA [RECIPE]
set -euo pipefail
bin=$1 data=$(cd "$2" && pwd) recipe=${3:-$(dirname "$0")/../../samples/shared_data.toml}
scratch=$(mktemp -d /tmp/bake_sample.XXXXXX)
trap 'rm -rf "$scratch"' EXIT

timed() {  # LABEL ARGS... : prints "| LABEL | wall | user+sys |"
  local label=$1
  shift
  local TIMEFORMAT="%R %U %S"
  { time "$bin/lodbake-bake" "$recipe" --set "data=$data" --quiet "$@" > /dev/null; } \
    2> "$scratch/time"
  read -r wall user sys < <(tail -n 1 "$scratch/time")
  awk -v l="$label" -v w="$wall" -v u="$user" -v y="$sys" \
    'BEGIN { printf "| %s | %.2f | %.2f |\n", l, w, u + y }' | tee -a "$scratch/rows"
}

echo "| run | wall s | CPU s |"
echo "|---|---:|---:|"
timed "--jobs 1, no cache" --jobs 1 --no-cache --keep-going --out "$scratch/j1"
timed "--jobs 2, no cache" --jobs 2 --no-cache --keep-going --out "$scratch/j2"
diff -r "$scratch/j1" "$scratch/j2" > /dev/null || { echo "--jobs 1 and 2 differ" >&2; exit 1; }
timed "cold, filling the cache" --cache "$scratch/cache" --keep-going --out "$scratch/warm"
cp -r "$scratch/warm" "$scratch/cold"
timed "warm rerun, same folder" --cache "$scratch/cache" --keep-going --out "$scratch/warm"
"$bin/lodbake-bake" "$recipe" --set "data=$data" --quiet --cache "$scratch/cache" --json \
  --out "$scratch/warm" > "$scratch/warm.json"
if grep -q '"status": "baked"' "$scratch/warm.json"; then
  echo "a warm rerun baked a step" >&2
  exit 1
fi
diff -r "$scratch/cold" "$scratch/warm" > /dev/null || { echo "warm outputs differ" >&2; exit 1; }
awk -F'|' 'NR == 1 { one = $3 } NR == 2 { printf "speed-up with --jobs 2: %.2fx\n", one / $3 }' \
  "$scratch/rows"

# Snakemake: one job per input and step (each a `lodbake-bake --asset
# --step` process), two at once, no cache, in its own working folder.
if ! command -v snakemake > /dev/null; then
  echo "snakemake missing: the workflow row is skipped"
  exit 0
fi
recipe_abs=$(cd "$(dirname "$recipe")" && pwd)/$(basename "$recipe")
workflow=$(cd "$(dirname "$0")/../../workflow" && pwd)/Snakefile
bake_abs=$(cd "$bin" && pwd)/lodbake-bake
mkdir -p "$scratch/snake"
snake_status=0
TIMEFORMAT="%R %U %S"
{ time (cd "$scratch/snake" && snakemake -s "$workflow" --cores 2 --quiet --keep-going \
  --config recipe="$recipe_abs" out="$scratch/snake/out" bake="$bake_abs" set="data=$data" \
  > "$scratch/snake.log" 2>&1); } 2> "$scratch/time" || snake_status=$?
[ "$snake_status" = 0 ] || { cat "$scratch/snake.log" >&2; echo "the workflow failed" >&2; exit 1; }
read -r wall user sys < <(tail -n 1 "$scratch/time")
diff -r "$scratch/j2" "$scratch/snake/out" > /dev/null || { echo "Snakemake's files differ" >&2; exit 1; }
awk -F'|' -v w="$wall" -v u="$user" -v y="$sys" 'NR == 2 {
  printf "| Snakemake --cores 2, no cache | %.2f | %.2f |\n", w, u + y
  printf "Snakemake against lodbake-bake --jobs 2: %.2fx the wall time\n", w / $3 }' "$scratch/rows"
