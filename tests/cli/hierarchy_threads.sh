#!/bin/sh
# lodbake-hierarchy writes the same bytes (container with every section,
# JSON report without its timings) for --threads 1, 2, 7 and 0 (every
# core), on the bunny, whose candidate listing and sorting run in parts.
#
#   hierarchy_threads.sh TOOLS DATA WORK
set -eu
tools=$1 data=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
fail() { echo "hierarchy_threads: $*" >&2; exit 1; }
for n in 1 2 7 0; do
  # The same file names in a folder per run: the report names them.
  mkdir "$work/t$n"
  (cd "$work/t$n" && "$tools/lodbake-hierarchy" "$data/meshes/stanford_bun_zipper.ply" \
    --threads $n --quiet --json -o out.lbk > out.json 2> err.txt) ||
    fail "--threads $n failed: $(cat "$work/t$n/err.txt")"
  [ ! -s "$work/t$n/err.txt" ] || fail "--threads $n wrote to stderr: $(cat "$work/t$n/err.txt")"
  # The report's times differ from run to run (a key per line, the build
  # steps' seconds on lines of their own).
  grep -v -E '"seconds"|"(hierarchy|refinement|progressive_mesh|dag|vertex_trees)": [0-9]' \
    "$work/t$n/out.json" > "$work/t$n/report"
done
[ -s "$work/t1/out.lbk" ] || fail "empty output"
grep -q '"DAGE"' "$work/t1/report" && grep -q '"VTRE"' "$work/t1/report" ||
  fail "the report names no DAGE or VTRE section"
for n in 2 7 0; do
  for f in out.lbk report; do
    cmp "$work/t1/$f" "$work/t$n/$f" > /dev/null ||
      fail "--threads $n: its $f differs from --threads 1's"
  done
done
echo "hierarchy_threads: --threads 1, 2, 7 and 0 wrote the same bytes"
