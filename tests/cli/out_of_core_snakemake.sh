#!/bin/sh
# workflow/out_of_core.smk on the bunny cut into several blocks: the split,
# one job per block and the merge write the same bytes as the one-shot
# `lodbake-simplify --memory-limit` run. Skipped (77) without snakemake.
#
#   out_of_core_snakemake.sh TOOLS DATA SRC WORK
set -eu
tools=$1 data=$2 src=$3 work=$4
command -v snakemake > /dev/null || { echo "out_of_core_snakemake: no snakemake" >&2; exit 77; }
fail() { echo "out_of_core_snakemake: $*" >&2; exit 1; }
mesh=$data/meshes/stanford_bun_zipper.ply
rm -rf "$work" && mkdir -p "$work"
"$tools/lodbake-simplify" "$mesh" -o "$work/one_shot.ply" --ratio 0.1 --memory-limit 4M --quiet \
  > /dev/null || fail "the one-shot run failed"
(cd "$work" && snakemake -s "$src/workflow/out_of_core.smk" --cores 2 --quiet \
  --config mesh="$mesh" out="$work/workflow.ply" limit=4M "target=--ratio 0.1" \
  simplify="$tools/lodbake-simplify" > snakemake.log 2>&1) || fail "snakemake failed: $(tail -20 "$work/snakemake.log")"
blocks=$(ls "$work/workflow.ply.work" | grep -c '^block_.*[.]out$')
[ "$blocks" -ge 4 ] || fail "expected several block jobs, got $blocks"
cmp "$work/one_shot.ply" "$work/workflow.ply" > /dev/null ||
  fail "the workflow's output differs from the one-shot run's"
echo "out_of_core_snakemake: $blocks block jobs wrote the one-shot run's bytes"
