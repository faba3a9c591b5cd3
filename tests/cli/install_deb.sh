#!/bin/sh
# install_deb.sh BUILD TMP
#
# CPack's Debian packages (docs/install.md): `cpack -G DEB` in BUILD makes
# lodbake (the tools and man pages; Depends from dpkg-shlibdeps) and
# lodbake-dev (headers, static libraries, CMake package, lodbake.pc; Depends
# on the -dev packages its users compile against). Checks both with dpkg-deb
# -I and -c, and that lodbake.pc unpacked from lodbake-dev points at the
# package's own headers.
set -u
build=$1
tmp=$2

fail() {
  echo "install_deb: $*" >&2
  exit 1
}

rm -rf "$tmp"
mkdir -p "$tmp"
(cd "$build" && cpack -G DEB -B "$tmp") > "$tmp/cpack.log" 2>&1 ||
  { cat "$tmp/cpack.log"; fail "cpack -G DEB failed"; }
tools_deb=$(ls "$tmp"/lodbake_*.deb 2> /dev/null)
dev_deb=$(ls "$tmp"/lodbake-dev_*.deb 2> /dev/null)
[ -f "$tools_deb" ] || fail "no lodbake_*.deb in $tmp: $(ls "$tmp")"
[ -f "$dev_deb" ] || fail "no lodbake-dev_*.deb in $tmp: $(ls "$tmp")"

dpkg-deb -I "$tools_deb" > "$tmp/tools.info" || fail "dpkg-deb -I $tools_deb failed"
dpkg-deb -c "$tools_deb" > "$tmp/tools.list" || fail "dpkg-deb -c $tools_deb failed"
grep -q "^ Package: lodbake$" "$tmp/tools.info" || fail "tools package not named lodbake"
# The tools link Boost.ProgramOptions, libcrypto and zlib dynamically.
for dep in libc6 libstdc++6 libboost-program-options libssl zlib1g; do
  grep "^ Depends:" "$tmp/tools.info" | grep -q "$dep" ||
    fail "lodbake's Depends lacks $dep: $(grep '^ Depends:' "$tmp/tools.info")"
done
for tool in "$build"/tools/lodbake-*; do
  [ -x "$tool" ] || continue
  name=$(basename "$tool")
  grep -q " \./usr/bin/$name$" "$tmp/tools.list" || fail "lodbake lacks /usr/bin/$name"
  grep -q " \./usr/share/man/man1/$name\.1\.gz$" "$tmp/tools.list" ||
    fail "lodbake lacks /usr/share/man/man1/$name.1.gz"
done
grep -q "\./usr/include/" "$tmp/tools.list" && fail "lodbake holds headers (they belong in lodbake-dev)"

dpkg-deb -I "$dev_deb" > "$tmp/dev.info" || fail "dpkg-deb -I $dev_deb failed"
dpkg-deb -c "$dev_deb" > "$tmp/dev.list" || fail "dpkg-deb -c $dev_deb failed"
grep -q "^ Package: lodbake-dev$" "$tmp/dev.info" || fail "dev package not named lodbake-dev"
grep "^ Depends:" "$tmp/dev.info" | grep -q "nlohmann-json3-dev" ||
  fail "lodbake-dev's Depends lacks nlohmann-json3-dev"
if grep -q "LODBAKE_DRACO_CODEC:BOOL=ON" "$build/CMakeCache.txt"; then
  grep "^ Depends:" "$tmp/dev.info" | grep -q "libdraco-dev" || fail "lodbake-dev's Depends lacks libdraco-dev"
fi
for file in include/lodbake/formats/sections/open_container.h include/lodbake/lib/replay/vhier_replay.h \
  lib/liblodbake_formats.a lib/liblodbake_replay.a lib/cmake/lodbake/lodbakeConfig.cmake \
  lib/cmake/lodbake/lodbakeTargets.cmake lib/pkgconfig/lodbake.pc; do
  grep -q " \./usr/$file$" "$tmp/dev.list" || fail "lodbake-dev lacks /usr/$file"
done
grep -q "\./usr/bin/" "$tmp/dev.list" && fail "lodbake-dev holds tools (they belong in lodbake)"

# Unpacked anywhere, lodbake.pc names the headers and archives beside it.
dpkg-deb -x "$dev_deb" "$tmp/root" || fail "dpkg-deb -x $dev_deb failed"
cflags=$(PKG_CONFIG_PATH=$tmp/root/usr/lib/pkgconfig pkg-config --cflags lodbake) ||
  fail "pkg-config cannot read the packaged lodbake.pc"
includedir=${cflags#-I}
includedir=${includedir%% *}
[ -f "$includedir/formats/sections/open_container.h" ] ||
  fail "the packaged lodbake.pc's include folder $includedir lacks formats/"
echo "install_deb: $(basename "$tools_deb") and $(basename "$dev_deb") checked"
