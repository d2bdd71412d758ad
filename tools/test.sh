#!/usr/bin/env bash
# Builds seqmassage and runs every test: the Release build, then the test suite again under
# AddressSanitizer + UndefinedBehaviorSanitizer, then the suites that run TBB in parallel under
# ThreadSanitizer (tools/tsan.sh). This is the README's test command and all that .ci/run does.
#   SEQMASSAGE_SKIP_SANITIZERS=1   the Release build only
#   SEQMASSAGE_SKIP_TSAN=1         no ThreadSanitizer stage
#   SEQMASSAGE_SKIP_CLUSTER=1      no cluster stage (Slurm end to end, the Kubernetes manifest)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash tools/setup.sh
jobs="$(nproc 2>/dev/null || echo 2)"
# Each stage's wall time, so a CI log shows where the time goes.
stage_start=$SECONDS
stage() {
  echo "test: $1 done in $((SECONDS - stage_start)) s"
  stage_start=$SECONDS
}

# ccache when installed: the pip build (tests/tools/test_pip.sh, in build-pip/) then reuses these
# objects; paths are hashed relative to the checkout.
launcher=()
if command -v ccache >/dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$root}"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSEQMASSAGE_UNITY_BUILD=ON "${launcher[@]}" >/dev/null
cmake --build build -j"$jobs"
stage "Release build"
ctest --test-dir build --output-on-failure -j"$jobs"
stage "Release tests"

# The Python module's tests (pytest), against the module the Release build wrote to build/python
# and the system Python it was built for; skipped only when CMake did not build the module.
if ls build/python/seqmassage*.so >/dev/null 2>&1; then
  PYTHONPATH=build/python /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python
  stage "Python module tests"
else
  echo "test: Python module tests SKIPPED: the module was not built (CMake found no Python 3" \
    "headers or pybind11: bash tools/setup.sh installs python3-dev and pybind11-dev)"
fi

# The layout: no include points back up inside a folder or between folders (docs/development.md).
/usr/bin/python3 tools/include_graph.py --check >/dev/null || {
  /usr/bin/python3 tools/include_graph.py --check
  exit 1
}
stage "include graph"

# Installed as users install it: cmake --install into a temporary prefix, the .deb (cpack; installed
# and removed only as root with CI=true), pip install . into a venv; 3: skipped, the script says why.
for test in install deb pip; do
  status=0
  bash "tests/tools/test_$test.sh" || status=$?
  [ "$status" = 0 ] || [ "$status" = 3 ] || exit "$status"
  stage "installing: $test"
done

# The Blender add-on, headless (tests/blender/run.sh), whenever blender is installed; 3: skipped
# (no blender, or no Python module), the script says why.
status=0
bash tests/blender/run.sh || status=$?
if [ "$status" = 3 ]; then
  echo "test: Blender add-on stage SKIPPED (see above)"
elif [ "$status" != 0 ]; then
  exit "$status"
fi
stage "Blender add-on"

# report.html in headless Chromium from file:// (tests/web/run.sh): the demo's player, plots and
# budget, and hostile strings shown as text; 3: skipped (no chromium), the script says why.
status=0
bash tests/web/run.sh || status=$?
if [ "$status" = 3 ]; then
  echo "test: report browser stage SKIPPED (see above)"
elif [ "$status" != 0 ]; then
  exit "$status"
fi
stage "report.html in a browser"

# The cluster scripts as users submit them: through a local Slurm cluster (installed and started
# by tools/slurm_local.sh), and the Kubernetes manifest (kubectl, offline). 3: skipped, the
# script says why.
if [ "${SEQMASSAGE_SKIP_CLUSTER:-0}" != 1 ]; then
  for test in slurm k8s_manifest; do
    status=0
    bash "tests/tools/test_$test.sh" || status=$?
    [ "$status" = 0 ] || [ "$status" = 3 ] || exit "$status"
    stage "cluster: $test"
  done
fi

if [ "${SEQMASSAGE_SKIP_SANITIZERS:-0}" != 1 ]; then
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSEQMASSAGE_ASAN=ON \
    -DSEQMASSAGE_BUILD_TOOLS=OFF -DSEQMASSAGE_PYTHON=OFF -DSEQMASSAGE_UNITY_BUILD=ON \
    "${launcher[@]}" >/dev/null
  cmake --build build-asan -j"$jobs"
  stage "ASan+UBSan build"
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan --output-on-failure -j"$jobs"
  stage "ASan+UBSan tests"

  if [ "${SEQMASSAGE_SKIP_TSAN:-0}" != 1 ]; then
    status=0
    bash tools/tsan.sh || status=$?
    stage "ThreadSanitizer (oneTBB, build and tests)"
    if [ "$status" = 3 ]; then
      echo "test: ThreadSanitizer stage SKIPPED: oneTBB could not be built with it (see above)"
    elif [ "$status" != 0 ]; then
      exit "$status"
    fi
  fi
fi
