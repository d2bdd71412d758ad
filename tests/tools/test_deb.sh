#!/usr/bin/env bash
# The Debian package: `cpack -G DEB` in the build folder, then the .deb inspected (dpkg-deb -I:
# name, version, Depends; dpkg-deb -c: the files) and, where this test may install packages (as
# root with CI=true, or SEQMASSAGE_TEST_DEB_INSTALL=1), installed with apt-get, run, removed.
#   bash tests/tools/test_deb.sh [BUILD_DIR]     (default build)
# Exit status: 0 passed, 1 failed, 3 skipped (no dpkg-deb).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"
log() { echo "test_deb: $*"; }
fail() { log "FAILED: $*"; exit 1; }
command -v dpkg-deb >/dev/null || { log "SKIPPED: no dpkg-deb (not Debian)"; exit 3; }

version="$(sed -nE 's/^project\(seqmassage VERSION ([0-9.]+).*/\1/p' "$root/CMakeLists.txt")"
arch="$(dpkg --print-architecture)"
deb="$build/seqmassage_${version}_${arch}.deb"
rm -f "$deb"
(cd "$build" && cpack -G DEB >cpack.log 2>&1) || { cat "$build/cpack.log"; fail "cpack -G DEB"; }
[ -f "$deb" ] || fail "cpack wrote no $(basename "$deb")"
log "$(basename "$deb"): $(du -k "$deb" | cut -f1) KiB"

info="$(dpkg-deb -I "$deb")"
field() { dpkg-deb -f "$deb" "$1"; }
[ "$(field Package)" = seqmassage ] || fail "Package: $(field Package)"
[ "$(field Version)" = "$version" ] || fail "Version: $(field Version), expected $version"
depends="$(field Depends)"
log "Depends: $depends"
# Derived from the linked libraries (dpkg-shlibdeps): the C and C++ runtimes, oneTBB, OpenSSL.
for lib in libc6 libstdc++6 libtbb libssl python3; do
  grep -q "$lib" <<<"$depends" || fail "Depends lacks $lib: $depends"
done
files="$(dpkg-deb -c "$deb" | awk '{print $6}')"
for want in ./usr/bin/seqmassage ./usr/share/man/man1/seqmassage.1 \
  ./usr/share/bash-completion/completions/seqmassage ./usr/share/seqmassage/seqmassage_blender.zip \
  ./usr/share/doc/seqmassage/configs/demo.json ./usr/share/doc/seqmassage/copyright; do
  grep -qx -- "$want" <<<"$files" || fail "the package lacks $want"
done
grep -qE '^\./usr/lib/python3/dist-packages/seqmassage\..*\.so$' <<<"$files" ||
  fail "the package lacks the Python module in /usr/lib/python3/dist-packages"
grep -qE "$root|/build/" <<<"$files" && fail "the package holds build paths"
log "dpkg-deb -c: $(wc -l <<<"$files") entries, the expected files present"

may_install=0
[ "$(id -u)" = 0 ] && [ "${CI:-}" = true ] && may_install=1
[ "${SEQMASSAGE_TEST_DEB_INSTALL:-0}" = 1 ] && may_install=1
if [ "$may_install" != 1 ]; then
  log "PASSED (not installed: needs root with CI=true, or SEQMASSAGE_TEST_DEB_INSTALL=1)"
  exit 0
fi
if dpkg-query -W -f='${Status}' seqmassage 2>/dev/null | grep -q "install ok installed"; then
  log "SKIPPED installing: a seqmassage package is installed already"
  exit 0
fi
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get install -y -qq "$deb" >/dev/null || fail "apt-get install $deb"
trap '$sudo apt-get remove -y -qq seqmassage >/dev/null 2>&1 || true' EXIT
tmp="$(mktemp -d)"
got="$(cd "$tmp" && /usr/bin/seqmassage --version)"
case "$got" in "seqmassage $version "*) ;; *) fail "installed --version: $got";; esac
mkdir -p "$tmp/configs" && cp /usr/share/doc/seqmassage/configs/demo.json "$tmp/configs/"
(cd "$tmp" && /usr/bin/seqmassage -q configs/demo.json) || fail "the installed demo"
got="$(cd "$tmp" && env -u PYTHONPATH /usr/bin/python3 -c 'import seqmassage; print(seqmassage.__version__)')"
[ "$got" = "$version" ] || fail "installed module: $got"
man -w seqmassage >/dev/null 2>&1 || [ ! -x /usr/bin/man ] || fail "man seqmassage: not found"
rm -rf "$tmp"
$sudo apt-get remove -y -qq seqmassage >/dev/null || fail "apt-get remove"
trap - EXIT
[ ! -e /usr/bin/seqmassage ] || fail "/usr/bin/seqmassage left after removal"
log "installed with apt-get, ran --version, the demo and import seqmassage, removed"
log "PASSED"
