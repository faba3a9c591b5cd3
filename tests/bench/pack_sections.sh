#!/usr/bin/env bash
# Per-section sizes of every container kind before and after lodbake-pack
# (issue 7, docs/benchmarks.md "Every section kind"): for each mesh, the
# containers lodbake-hierarchy (all of vhie,dage,vtre), lodbake-fan,
# lodbake-strips and lodbake-strips --strips-only write with their defaults,
# each packed with lodbake-pack (compact) and lodbake-pack --draco; prints a
# markdown table per mesh of each section's bytes as the tool wrote it and
# after each pack, with bits per vertex of the input mesh, and for each
# coded section the median encode and decode seconds that
# bench_section_codecs measures on the packed file (BENCH_RUNS runs, default
# 5). Sizes are deterministic (same input, same bytes); times are not.
#
#   tests/bench/pack_sections.sh BIN_DIR MESH...     (BIN_DIR: build/tools)
#
# bench_section_codecs is taken from BIN_DIR/../tests/bench (or
# $BENCH_SECTION_CODECS); without it the time columns are empty.
set -euo pipefail

if [ $# -lt 2 ]; then
  echo "usage: $0 BIN_DIR MESH..." >&2
  exit 1
fi
bin=$1
shift
codec_bench=${BENCH_SECTION_CODECS:-$bin/../tests/bench/bench_section_codecs}
runs=${BENCH_RUNS:-5}
scratch=$(mktemp -d /tmp/pack_sections.XXXXXX)
trap 'rm -rf "$scratch"' EXIT

# Runs a tool quietly; on failure shows what it said and stops.
run() {
  if ! "$@" > "$scratch/log" 2>&1; then
    echo "pack_sections: failed: $*" >&2
    cat "$scratch/log" >&2
    exit 4
  fi
}

# lodbake-pack's listing as "TAG BEFORE AFTER CODEC_AFTER" lines, then
# "FILE BYTES VERTICES" from its "wrote" line.
pack_sizes() {
  awk '/^  [A-Z][A-Z][A-Z][A-Z] / && $4 == "->" && $7 == "->" { print $1, $6, $8, $5 }
       /^wrote / { for (i = 1; i <= NF; ++i) {
                     if ($(i + 1) == "bytes") bytes = $i
                     if ($(i + 1) == "vertices,") vertices = $i }
                   print "FILE", 0, bytes, vertices }' "$1"
}

for mesh in "$@"; do
  name=$(basename "$mesh")
  echo "pack_sections: $name" >&2
  run "$bin/lodbake-hierarchy" -q "$mesh" -o "$scratch/hierarchy.lbk"
  run "$bin/lodbake-fan" -q "$mesh" -o "$scratch/fan.lbk"
  run "$bin/lodbake-strips" -q "$mesh" -o "$scratch/strips.lbk"
  run "$bin/lodbake-strips" -q --strips-only "$mesh" -o "$scratch/strp.lbk"
  rows=""
  vertices=""
  for kind in hierarchy fan strips strp; do
    in="$scratch/$kind.lbk"
    run "$bin/lodbake-pack" "$in" -o "$scratch/$kind.raw.lbk"
    pack_sizes "$scratch/log" > "$scratch/$kind.raw"
    run "$bin/lodbake-pack" "$in" --draco -o "$scratch/$kind.draco.lbk"
    pack_sizes "$scratch/log" > "$scratch/$kind.draco"
    # "TAG ENCODE_S DECODE_S" per coded section of each packed file.
    for variant in raw draco; do
      : > "$scratch/$kind.$variant.times"
      if [ -x "$codec_bench" ]; then
        "$codec_bench" --runs "$runs" "$scratch/$kind.$variant.lbk" > "$scratch/log" 2>&1 ||
          { cat "$scratch/log" >&2; exit 4; }
        awk '$3 != "raw" { print $2, $6, $7 }' "$scratch/log" > "$scratch/$kind.$variant.times"
      fi
    done
    written_total=$(stat -c %s "$in")
    case $kind in
      hierarchy) tool="lodbake-hierarchy" ;;
      fan) tool="lodbake-fan" ;;
      strips) tool="lodbake-strips" ;;
      strp) tool="lodbake-strips --strips-only" ;;
    esac
    # Join the two listings by tag, in the packed order.
    rows+=$(awk -v tool="$tool" -v written_total="$written_total" '
      # By name, not by counting first lines: a times file may be empty.
      { file = FILENAME == ARGV[1] ? 1 : FILENAME == ARGV[2] ? 2 : FILENAME == ARGV[3] ? 3 : 4 }
      file == 1 { order[++n] = $1; before[$1] = $2; raw[$1] = $3; raw_codec[$1] = $4
                  if ($1 == "FILE") { vertices = $4; before[$1] = written_total } }
      file == 2 { draco[$1] = $3; draco_codec[$1] = $4 }
      file == 3 { raw_enc[$1] = $2; raw_dec[$1] = $3 }
      file == 4 { draco_enc[$1] = $2; draco_dec[$1] = $3 }
      function secs(x) { return x == "" ? "" : sprintf("%.4f", x) }
      END {
        for (i = 1; i <= n; ++i) {
          t = order[i]
          label = t == "FILE" ? "whole file" : t
          rc = t == "FILE" || raw_codec[t] == "raw" ? "" : " " raw_codec[t]
          dc = t == "FILE" || draco_codec[t] == "raw" ? "" : " " draco_codec[t]
          printf "| %s | %s | %d | %.2f | %d%s | %.2f | %s | %s | %d%s | %.2f | %s | %s |\n",
                 tool, label, before[t], 8 * before[t] / vertices, raw[t], rc,
                 8 * raw[t] / vertices, secs(raw_enc[t]), secs(raw_dec[t]), draco[t], dc,
                 8 * draco[t] / vertices, secs(draco_enc[t]), secs(draco_dec[t])
        }
        printf "VERTICES %d\n", vertices
      }' "$scratch/$kind.raw" "$scratch/$kind.draco" "$scratch/$kind.raw.times" \
         "$scratch/$kind.draco.times")$'\n'
  done
  vertices=$(printf '%s' "$rows" | awk '$1 == "VERTICES" { print $2; exit }')
  echo
  echo "$name: $vertices vertices"
  echo
  echo "| written by | section | bytes written | bits/vertex | lodbake-pack | bits/vertex | encode s | decode s | lodbake-pack --draco | bits/vertex | encode s | decode s |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  printf '%s' "$rows" | grep -v '^VERTICES '
done
