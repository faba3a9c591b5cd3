#!/bin/sh
# lodbake-simplify --memory-limit on the bunny with a limit (4M) that cuts it
# into several blocks: the one-shot run writes the same bytes for --threads
# 1 and 3, leaves no work files, and running the stages one by one (split,
# each block, merge; as the Snakemake workflow does) writes the same bytes
# again. A failing stage leaves no output.
#
#   out_of_core_stages.sh TOOLS DATA WORK
set -eu
tools=$1 data=$2 work=$3
simplify=$tools/lodbake-simplify
mesh=$data/meshes/stanford_bun_zipper.ply
rm -rf "$work" && mkdir -p "$work/t1" "$work/t3"
fail() { echo "out_of_core_stages: $*" >&2; exit 1; }
for n in 1 3; do
  "$simplify" "$mesh" -o "$work/t$n/out.ply" --ratio 0.1 --memory-limit 4M --threads $n \
    --json --quiet > "$work/t$n/report.json" 2> "$work/t$n/err.txt" ||
    fail "one-shot --threads $n failed: $(cat "$work/t$n/err.txt")"
  [ "$(ls -A "$work/t$n")" = "$(printf 'err.txt\nout.ply\nreport.json')" ] ||
    fail "one-shot --threads $n left files behind: $(ls -A "$work/t$n")"
done
blocks=$(sed -n 's/^ *"blocks": \([0-9]*\),$/\1/p' "$work/t1/report.json")
[ "${blocks:-0}" -ge 4 ] || fail "expected several blocks, got '${blocks:-none}'"
cmp "$work/t1/out.ply" "$work/t3/out.ply" > /dev/null || fail "--threads 1 and 3 differ"

# A failing run (here a target larger than the limit allows)
# leaves neither output nor work files.
mkdir "$work/failed"
"$simplify" "$mesh" -o "$work/failed/out.ply" --ratio 0.5 --memory-limit 4M --quiet \
  2> /dev/null && fail "a target above the limit succeeded"
[ -z "$(ls -A "$work/failed")" ] || fail "a failed run left $(ls -A "$work/failed")"

staged=$work/staged
"$simplify" "$mesh" --stage split --work "$staged" --ratio 0.1 --memory-limit 4M --quiet \
  > /dev/null || fail "split failed"
"$simplify" --stage merge --work "$staged" -o "$work/early.ply" --quiet 2> "$work/early.err" &&
  fail "merge before the blocks succeeded"
grep -q "block 0 is not simplified yet" "$work/early.err" || fail "merge: $(cat "$work/early.err")"
[ ! -e "$work/early.ply" ] || fail "a failed merge left its output"
b=0
while [ $b -lt "$blocks" ]; do
  "$simplify" --stage block --block $b --work "$staged" --threads 2 --quiet > /dev/null ||
    fail "block $b failed"
  b=$((b + 1))
done
"$simplify" --stage merge --work "$staged" -o "$work/staged.ply" --quiet > /dev/null ||
  fail "merge failed"
cmp "$work/t1/out.ply" "$work/staged.ply" > /dev/null ||
  fail "the staged run's output differs from the one-shot run's"
echo "out_of_core_stages: $blocks blocks; one-shot (--threads 1 and 3) and staged runs wrote the same bytes"
