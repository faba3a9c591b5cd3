#!/bin/sh
# install_embed.sh BUILD SRC CXX MESH TMP
#
# The installed package as a user meets it (docs/install.md): `cmake
# --install BUILD --prefix TMP/prefix` puts every tool of BUILD/tools and its
# man page, the headers, the static libraries, the CMake package and
# lodbake.pc in place; samples/embed_replay is then configured and built
# against that prefix alone, by a separate cmake run (find_package(lodbake),
# CMAKE_PREFIX_PATH) and by the compiler with `pkg-config --cflags --libs
# lodbake`, and every installed header must compile from the prefix. Both
# builds replay the orbit path on MESH's balanced hierarchy
# (made by the build's lodbake-hierarchy) and must print, frame by frame, the
# triangle counts of `lodbake-replay --mode vhier --csv` on the same file.
set -u
build=$1
src=$2
cxx=$3
mesh=$4
tmp=$5
prefix=$tmp/prefix

fail() {
  echo "install_embed: $*" >&2
  exit 1
}

rm -rf "$tmp"
mkdir -p "$tmp"
cmake --install "$build" --prefix "$prefix" > "$tmp/install.log" 2>&1 ||
  { cat "$tmp/install.log"; fail "cmake --install failed"; }

# Every tool the build made is installed, runs from the prefix and has its page.
tools=0
for tool in "$build"/tools/lodbake-*; do
  [ -x "$tool" ] || continue
  name=$(basename "$tool")
  tools=$((tools + 1))
  [ -x "$prefix/bin/$name" ] || fail "bin/$name not installed"
  "$prefix/bin/$name" --version | grep -q "^$name [0-9]" || fail "installed $name --version fails"
  page=$prefix/share/man/man1/$name.1.gz
  [ -f "$page" ] || fail "share/man/man1/$name.1.gz not installed"
  gzip -dc "$page" > "$tmp/page" || fail "$name.1.gz is not gzip"
  grep -q "^\.TH $(echo "$name" | tr a-z A-Z) \"1\"" "$tmp/page" || fail "$name.1 has no .TH line"
  grep -qF -- '\-\-json' "$tmp/page" && grep -q "Exit codes" "$tmp/page" ||
    fail "$name.1 lacks the options and exit codes of --help"
done
[ "$tools" -ge 7 ] || fail "only $tools tools in $build/tools"
for file in include/lodbake/formats/sections/open_container.h \
  include/lodbake/lib/replay/vhier_replay.h lib/cmake/lodbake/lodbakeConfig.cmake \
  lib/cmake/lodbake/lodbakeTargets.cmake lib/liblodbake_formats.a lib/liblodbake_replay.a; do
  [ -f "$prefix/$file" ] || fail "$file not installed"
done
pc=$(find "$prefix" -name lodbake.pc)
[ -n "$pc" ] || fail "lodbake.pc not installed"

# The container and the reference numbers, from the build's own tools.
"$build/tools/lodbake-hierarchy" "$mesh" -o "$tmp/mesh.lbk" --sections vhie --quiet ||
  fail "lodbake-hierarchy failed on $mesh"
"$build/tools/lodbake-replay" "$tmp/mesh.lbk" --mode vhier --path orbit --csv "$tmp/replay.csv" \
  --quiet > /dev/null || fail "lodbake-replay failed"
# frame,triangles from frame,splits,collapses,passes,front,triangles,adapt_ms
head -1 "$tmp/replay.csv" | grep -q '^frame,splits,collapses,passes,front,triangles,' ||
  fail "lodbake-replay --csv columns changed: $(head -1 "$tmp/replay.csv")"
cut -d, -f1,6 "$tmp/replay.csv" > "$tmp/expected.csv"
[ "$(wc -l < "$tmp/expected.csv")" -gt 100 ] || fail "the orbit path replayed too few frames"

# The sample through the CMake package, in a separate configuration.
launcher=
command -v ccache > /dev/null && launcher=-DCMAKE_CXX_COMPILER_LAUNCHER=ccache
cmake -S "$src/samples/embed_replay" -B "$tmp/sample" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_PREFIX_PATH="$prefix" $launcher \
  > "$tmp/sample.log" 2>&1 || { cat "$tmp/sample.log"; fail "find_package(lodbake) failed"; }
cmake --build "$tmp/sample" > "$tmp/sample_build.log" 2>&1 ||
  { cat "$tmp/sample_build.log"; fail "samples/embed_replay does not build against the prefix"; }
"$tmp/sample/embed_replay" "$tmp/mesh.lbk" orbit > "$tmp/cmake_sample.csv" 2> "$tmp/cmake_sample.err" ||
  { cat "$tmp/cmake_sample.err"; fail "embed_replay (CMake build) failed"; }
cmp -s "$tmp/cmake_sample.csv" "$tmp/expected.csv" ||
  fail "embed_replay (CMake build) triangle counts differ from lodbake-replay --csv"

# The same program through pkg-config only.
flags=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --cflags --libs lodbake) ||
  fail "pkg-config cannot read lodbake.pc"
# shellcheck disable=SC2086 # flags are words
$cxx -std=c++17 -O1 "$src/samples/embed_replay/main.cpp" $flags -o "$tmp/pc_sample" \
  > "$tmp/pc.log" 2>&1 || { cat "$tmp/pc.log"; fail "the sample does not build with pkg-config's flags"; }
"$tmp/pc_sample" "$tmp/mesh.lbk" orbit > "$tmp/pc_sample.csv" 2> /dev/null ||
  fail "embed_replay (pkg-config build) failed"
cmp -s "$tmp/pc_sample.csv" "$tmp/expected.csv" ||
  fail "embed_replay (pkg-config build) triangle counts differ from lodbake-replay --csv"

# Every installed header compiles against the prefix alone (one translation
# unit including them all: no header reaches for a file left uninstalled).
(cd "$prefix/include/lodbake" && find formats lib -name '*.h' | sort | sed 's/.*/#include "&"/') \
  > "$tmp/all_headers.cpp"
[ "$(wc -l < "$tmp/all_headers.cpp")" -gt 50 ] || fail "too few headers installed"
# shellcheck disable=SC2086 # flags are words
$cxx -std=c++17 -fsyntax-only "$tmp/all_headers.cpp" $flags > "$tmp/headers.log" 2>&1 ||
  { head -20 "$tmp/headers.log"; fail "the installed headers do not compile on their own"; }

# A container without the hierarchy is refused with lodbake's exit code 3.
"$build/tools/lodbake-pack" "$mesh" -o "$tmp/base.lbk" --quiet > /dev/null 2>&1 || fail "lodbake-pack failed"
"$tmp/sample/embed_replay" "$tmp/base.lbk" > /dev/null 2> "$tmp/refused.err"
code=$?
[ "$code" -eq 3 ] && grep -q "no VHIE section" "$tmp/refused.err" ||
  fail "embed_replay on a container without VHIE: exit $code, $(cat "$tmp/refused.err")"
echo "install_embed: $tools tools installed, sample built by CMake and pkg-config, $(($(wc -l < "$tmp/expected.csv") - 1)) frames equal"
