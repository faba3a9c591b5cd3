#!/bin/sh
# lodbake-simplify writes the same bytes (mesh, PM container, JSON report
# without its timing) for --threads 1, 2, 7 and 0 (every core), on the
# bunny, whose every parallel step runs in parts.
#
#   simplify_threads.sh TOOLS DATA WORK
set -eu
tools=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "simplify_threads: $*" >&2; exit 1; }
for n in 1 2 7 0; do
  # The same file names in a folder per run: the report names them.
  mkdir "$work/t$n"
  (cd "$work/t$n" && "$tools/lodbake-simplify" "$data/meshes/stanford_bun_zipper.ply" \
    --ratio 0.05 --height-guard --threads $n --no-metrics --quiet --json -o out.obj \
    --pm out.lbk > out.json 2> err.txt) || fail "--threads $n failed: $(cat "$work/t$n/err.txt")"
  [ ! -s "$work/t$n/err.txt" ] || fail "--threads $n wrote to stderr: $(cat "$work/t$n/err.txt")"
  # The report's times differ from run to run.
  grep -v 'seconds"' "$work/t$n/out.json" > "$work/t$n/report"
done
[ -s "$work/t1/out.lbk" ] && [ -s "$work/t1/out.obj" ] || fail "empty output"
grep -q '"collapses"' "$work/t1/report" || fail "the report has no collapse count"
for n in 2 7 0; do
  for f in out.obj out.lbk report; do
    cmp "$work/t1/$f" "$work/t$n/$f" > /dev/null ||
      fail "--threads $n: its $f differs from --threads 1's"
  done
done
echo "simplify_threads: --threads 1, 2, 7 and 0 wrote the same bytes"
