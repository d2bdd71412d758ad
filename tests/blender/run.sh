#!/usr/bin/env bash
# The Blender add-on's tests, headless: each tests/blender/test_*.py in its own
# `blender -b --factory-startup --python-exit-code 1 --python ...`, with the add-on enabled from
# this checkout and the module built at build/python (and the command line at
# build/src/cli/seqmassage, which the tests compare against).
#   bash tests/blender/run.sh          (tools/test.sh runs it after the Release tests)
#   bash tests/blender/run.sh mesh_cache   only test_mesh_cache.py
#   SEQMASSAGE_BUILD_DIR=build-dev bash tests/blender/run.sh   another build folder than build/
# test_modal_*.py drive the operators as from the UI (modal, Esc pressed), which needs a window:
# they run in a windowed Blender on a virtual display (xvfb-run, Debian's xvfb) with
# --enable-event-simulate, and are skipped with a message where xvfb-run is missing.
# Exit status: 0 passed; 1 failed; 3 skipped (no blender, or the module is not built).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
log() { echo "test_blender: $*"; }

if ! command -v blender >/dev/null 2>&1; then
  log "SKIPPED: blender is not installed (bash tools/setup.sh installs it as an extra)"
  exit 3
fi
build="${SEQMASSAGE_BUILD_DIR:-build}"
case "$build" in /*) ;; *) build="$root/$build" ;; esac
module_dir="$build/python"
if ! compgen -G "$module_dir/seqmassage*.so" >/dev/null; then
  log "SKIPPED: the seqmassage Python module is not built ($module_dir/seqmassage*.so);" \
    "CMake builds it when it finds Python 3 and pybind11"
  exit 3
fi
cli="$build/src/cli/seqmassage"
[ -x "$cli" ] || { log "FAILED: no $cli"; exit 1; }

export SEQMASSAGE_ROOT="$root" SEQMASSAGE_MODULE_DIR="$module_dir" SEQMASSAGE_CLI="$cli" \
  SEQMASSAGE_TEST_DIR="$build/blender-test" SEQMASSAGE_ADDON_ZIP="$build/blender/seqmassage_blender.zip"
# The add-on must find the module itself (its preferences), not through the environment.
unset PYTHONPATH
failed=0
for test in "$root"/tests/blender/test_"${1:-}"*.py; do
  name="$(basename "$test")"
  start=$SECONDS
  status=0
  out="$build/blender-test/$name.log"
  mkdir -p "$(dirname "$out")"
  case "$name" in
    test_modal_*)
      if ! command -v xvfb-run >/dev/null 2>&1; then
        log "$name SKIPPED: needs a window, and xvfb-run (Debian's xvfb) is not installed"
        continue
      fi
      timeout 600 xvfb-run -a -s "-screen 0 1280x720x24" blender --factory-startup \
        --enable-event-simulate --python-exit-code 1 --python "$test" >"$out" 2>&1 || status=$?
      ;;
    *) blender -b --factory-startup --python-exit-code 1 --python "$test" >"$out" 2>&1 || status=$? ;;
  esac
  grep -E "^(test_[a-z_]+\.py|Info|Warning|Error):" "$out" || true
  if [ "$status" = 0 ] && grep -q "^$name: PASSED" "$out"; then
    log "$name passed ($((SECONDS - start)) s)"
  else
    log "$name FAILED (exit $status); the log, $out:"
    tail -40 "$out"
    failed=1
  fi
done
exit "$failed"
