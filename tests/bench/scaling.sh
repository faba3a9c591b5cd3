#!/usr/bin/env bash
# The scaling table (docs/benchmarks.md, "Scaling"): the full dragon
# Loop-subdivided 0 to 3 times (0.9M, 3.5M, 14M, 56M triangles) with
# OpenMesh-commandlineSubdivider (Debian's libopenmesh-apps), each level made
# once from the one below into WORK_DIR and kept there. On each mesh:
# lodbake-simplify --pm --ratio 0.1 --no-metrics (simplify + PM; the metrics
# are a separate step of their own) and lodbake-hierarchy, with --threads 1
# and 2: wall seconds, peak resident set (GNU time's %M) and bytes
# of that peak per input triangle; the outputs of 1 and 2 threads must be the
# same bytes (the benchmark fails otherwise). meshoptimizer 0.18
# (bench_simplify --peers meshopt, one thread, to the same 10%) is the speed
# reference. Times depend on the machine's load; peaks hardly do.
# The out-of-core run (lodbake-simplify --memory-limit, at a quarter of the
# in-core --pm peak just measured) against the in-core one, both writing the
# mesh with --no-metrics and the first thread count: wall and peak rows, and
# a second table of their Hausdorff and mean distance to the input
# (BENCH_DIR/mesh_distance; left out above 20M triangles, whose metrics take
# more memory than the runs).
#
#   tests/bench/scaling.sh [--levels 0,1,2,3] [--threads 1,2] TOOLS_DIR BENCH_DIR DRAGON_PLY WORK_DIR
#
# TOOLS_DIR holds lodbake-simplify and lodbake-hierarchy, BENCH_DIR
# bench_simplify and mesh_distance.
set -euo pipefail
levels=0,1,2,3
thread_counts=1,2
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --levels) levels=$2 ;;
    --threads) thread_counts=$2 ;;
    *)
      echo "scaling.sh: unknown option '$1'" >&2
      exit 1
      ;;
  esac
  shift 2
done
if [[ $# -ne 4 ]]; then
  echo "usage: scaling.sh [--levels 0,1,2,3] [--threads 1,2] TOOLS_DIR BENCH_DIR DRAGON_PLY" \
    "WORK_DIR" >&2
  exit 1
fi
tools=$1 bench=$2 dragon=$3 work=$4
for program in /usr/bin/time OpenMesh-commandlineSubdivider; do
  command -v "$program" > /dev/null || {
    echo "scaling.sh: $program is missing (make bench-deps installs it)" >&2
    exit 1
  }
done
mkdir -p "$work"

# mesh LEVEL: the path of the dragon subdivided LEVEL times, made if missing.
mesh() {
  local level=$1
  if [[ $level -eq 0 ]]; then
    echo "$dragon"
    return
  fi
  local out=$work/dragon_loop$level.ply
  if [[ ! -s $out ]]; then
    local below
    below=$(mesh $((level - 1)))
    echo "scaling.sh: subdividing $(basename "$below") once (Loop) into $out" >&2
    OpenMesh-commandlineSubdivider -l 1 "$below" "$out.tmp.ply" > /dev/null 2>&1
    mv "$out.tmp.ply" "$out"
  fi
  echo "$out"
}

# The face count from a PLY header (ASCII or binary).
triangles() {
  head -c 4096 "$1" | tr -d '\r' | awk '/^element face/ { print $3; exit }'
}

# timed TRIANGLES LABEL THREADS COMMAND...: one table row from GNU time.
timed() {
  local tris=$1 label=$2 threads=$3
  shift 3
  /usr/bin/time -f "%e %U %S %M" -o "$work/time" "$@" > /dev/null
  read -r wall user sys kib < "$work/time"
  awk -v m="$name" -v t="$tris" -v l="$label" -v n="$threads" -v w="$wall" -v c="$user" \
    -v y="$sys" -v k="$kib" 'BEGIN { printf "| %s | %.2fM | %s | %s | %.2f | %.2f | %.0f | %.1f |\n",
                             m, t / 1e6, l, n, w, c + y, k / 1024, k * 1024 / t }'
}

# lodbake-hierarchy takes --threads once it has parallel steps; until then
# it runs once, its thread count shown as "-".
hierarchy_threads=false
"$tools/lodbake-hierarchy" --help 2>&1 | grep -q -- --threads && hierarchy_threads=true

echo "| mesh | triangles | step | threads | wall s | CPU s | peak MiB | bytes/triangle |"
echo "|---|---:|---|---:|---:|---:|---:|---:|"
distances=""
IFS=, read -r -a level_list <<< "$levels"
IFS=, read -r -a thread_list <<< "$thread_counts"
for level in "${level_list[@]}"; do
  file=$(mesh "$level")
  name=$(basename "$file")
  tris=$(triangles "$file")
  first=""
  for n in "${thread_list[@]}"; do
    out=$work/$name.t$n
    timed "$tris" "simplify --pm --ratio 0.1 --no-metrics" "$n" \
      "$tools/lodbake-simplify" "$file" --pm "$out.pm.lbk" --ratio 0.1 --no-metrics \
      --threads "$n" --quiet
    [[ -n $first ]] || read -r _ _ _ incore_kib < "$work/time"
    if $hierarchy_threads; then
      timed "$tris" "hierarchy" "$n" \
        "$tools/lodbake-hierarchy" "$file" -o "$out.hier.lbk" --threads "$n" --quiet
    elif [[ -z $first ]]; then
      timed "$tris" "hierarchy" "-" "$tools/lodbake-hierarchy" "$file" -o "$out.hier.lbk" --quiet
    fi
    timed "$tris" "fan" "$n" "$tools/lodbake-fan" "$file" -o "$out.fan.lbk" --threads "$n" --quiet
    timed "$tris" "strips" "$n" \
      "$tools/lodbake-strips" "$file" -o "$out.strips.lbk" --threads "$n" --quiet
    if [[ -z $first ]]; then
      first=$out
      continue
    fi
    for kind in pm hier fan strips; do
      [[ -e $out.$kind.lbk ]] || continue
      cmp -s "$first.$kind.lbk" "$out.$kind.lbk" || {
        echo "scaling.sh: $name: the $kind outputs of --threads ${thread_list[0]} and $n differ" >&2
        exit 1
      }
    done
    rm -f "$out".*.lbk
  done
  rm -f "$first".*.lbk
  n=${thread_list[0]}
  limit=$((incore_kib / 4))K
  timed "$tris" "simplify -o --ratio 0.1 --no-metrics, in core" "$n" \
    "$tools/lodbake-simplify" "$file" -o "$work/$name.incore.ply" --ratio 0.1 --no-metrics \
    --threads "$n" --quiet
  timed "$tris" "simplify -o --ratio 0.1 --memory-limit $limit" "$n" \
    "$tools/lodbake-simplify" "$file" -o "$work/$name.ooc.ply" --ratio 0.1 --memory-limit "$limit" \
    --threads "$n" --quiet
  if [[ $tris -le 20000000 ]]; then
    distances+=$("$bench/mesh_distance" "$file" "$work/$name.incore.ply" "$work/$name.ooc.ply" |
      awk -v m="$name" -v l="$limit" '{ printf "| %s | %s | %.3g | %.3g |\n", m,
        (NR == 1 ? "in core" : "--memory-limit " l), $3, $5 }')$'\n'
  fi
  rm -f "$work/$name.incore.ply" "$work/$name.ooc.ply"
  # meshoptimizer's wall and CPU seconds (bench_simplify's "seconds" and
  # "cpu s", from its TriangleMesh to the result), with as few metric
  # samples as it takes.
  "$bench/bench_simplify" --runs 1 --ratios 0.1 --peers meshopt --samples 1000 --markdown \
    "$file" 2> /dev/null | awk -F'|' -v m="$name" -v t="$tris" '$4 ~ /meshopt/ {
      printf "| %s | %.2fM | meshoptimizer 0.18, 10%% | 1 | %.2f | %.2f | - | - |\n",
             m, t / 1e6, $5, $6 }'
done
# The whole bake of the full dragon (tests/bench/dragon_bake.toml: simplify
# + PM, hierarchy + DAG + vertex trees, fan, strips + SETS, one
# Draco-packed container) with --jobs N: the bake's steps share one import
# and run side by side on its N threads. Its files must be the same bytes
# for every N.
first=""
for n in "${thread_list[@]}"; do
  name=$(basename "$dragon")
  rm -rf "$work/bake.t$n"
  timed "$(triangles "$dragon")" "lodbake-bake dragon_bake.toml (whole bake)" "$n" \
    "$tools/lodbake-bake" "$(dirname "$0")/dragon_bake.toml" --set "mesh=$dragon" \
    --out "$work/bake.t$n" --jobs "$n" --no-cache --quiet
  if [[ -z $first ]]; then
    first=$work/bake.t$n
    continue
  fi
  diff -r -q "$first" "$work/bake.t$n" > /dev/null || {
    echo "scaling.sh: the bakes with --jobs ${thread_list[0]} and $n differ" >&2
    exit 1
  }
  rm -rf "$work/bake.t$n"
done
rm -rf "$first"

if [[ -n $distances ]]; then
  echo
  echo "| mesh | run | Hausdorff / diagonal | mean / diagonal |"
  echo "|---|---|---:|---:|"
  printf '%s' "$distances"
fi
