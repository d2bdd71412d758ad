#!/usr/bin/env bash
# `pip install .` of the checkout into a fresh virtual environment (--system-site-packages, for
# Debian's numpy; --no-build-isolation: no network), the Python tests run against that install
# (the stubs' mypy check against the installed seqmassage.pyi), and `pip wheel .`. The build
# folder is build-pip/, beside build/: with ccache (tools/setup.sh installs it) the pip build
# reuses the objects of build/ and builds the module's target only.
#   bash tests/tools/test_pip.sh
# Exit status: 0 passed, 1 failed, 3 skipped (no python3 -m venv).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
log() { echo "test_pip: $*"; }
fail() { log "FAILED: $*"; exit 1; }
/usr/bin/python3 -c "import venv, ensurepip" 2>/dev/null ||
  { log "SKIPPED: no python3 -m venv (python3-venv)"; exit 3; }
version="$(sed -nE 's/^project\(seqmassage VERSION ([0-9.]+).*/\1/p' "$root/CMakeLists.txt")"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$tmp/venv"
py="$tmp/venv/bin/python"
start=$SECONDS
(cd "$root" && "$py" -m pip install -q --no-build-isolation --no-index .) >"$tmp/pip.log" 2>&1 ||
  { tail -40 "$tmp/pip.log"; fail "pip install ."; }
log "pip install . in $((SECONDS - start)) s"
site="$("$py" -c 'import sysconfig; print(sysconfig.get_path("platlib"))')"
got="$(cd "$tmp" && env -u PYTHONPATH "$py" -c 'import seqmassage; print(seqmassage.__version__, seqmassage.__file__)')"
case "$got" in "$version $tmp/venv/"*) ;; *) fail "the venv imports '$got'";; esac
[ -f "$site/seqmassage.pyi" ] && [ -f "$site/seqmassage-stubs/__init__.pyi" ] ||
  fail "the stubs are not installed in $site"
log "import seqmassage: $got"
# The Python tests against the installed module; the command line of build/ for the tests that
# compare with it (skipped if it is not built).
(cd "$tmp" && env -u PYTHONPATH SEQMASSAGE_CLI="$root/build/src/cli/seqmassage" \
  SEQMASSAGE_STUB_DIR="$site" "$py" -m pytest -q -p no:cacheprovider "$root/tests/python") ||
  fail "the Python tests against the pip install"
"$py" -m pip show -f seqmassage >"$tmp/show" && grep -q "^Version: $version" "$tmp/show" ||
  fail "pip show: $(head -3 "$tmp/show")"
(cd "$root" && "$py" -m pip wheel -q --no-build-isolation --no-index --no-deps -w "$tmp/wheels" .) \
  >"$tmp/wheel.log" 2>&1 || { tail -40 "$tmp/wheel.log"; fail "pip wheel ."; }
wheel="$(ls "$tmp"/wheels/seqmassage-"$version"-*.whl 2>/dev/null | head -1)"
[ -n "$wheel" ] || fail "pip wheel wrote no seqmassage-$version-*.whl"
"$py" - "$wheel" <<'PY' || fail "the wheel's contents"
import sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
assert any(n.startswith("seqmassage.") and n.endswith(".so") for n in names), names
assert "seqmassage.pyi" in names and "seqmassage-stubs/__init__.pyi" in names, names
PY
log "pip wheel .: $(basename "$wheel")"
log "PASSED"
