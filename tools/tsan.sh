#!/usr/bin/env bash
# Runs the test suites that exercise TBB parallelism under ThreadSanitizer:
#   bash tools/tsan.sh            test_massage, test_pipeline, test_cli (and the seqmassage they run)
#   bash tools/tsan.sh all        every test suite
# ThreadSanitizer only sees synchronization in code it instrumented. Debian's libtbb is not, so
# with it every hand-over of work between TBB threads (a task's range, a pipeline token) is reported
# as a race: hundreds of false reports in test_pipeline alone. This script therefore builds oneTBB
# itself with -fsanitize=thread (its own TBB_SANITIZE option), from the Debian source package of
# the installed libtbb-dev (same version, same patches; fetched with apt-get source through a
# private apt configuration, nothing in /etc is changed), and links the TSan build against it.
# Everything lives in build-tsan/ and is reused by the next run. Exits 3 (before building
# seqmassage) when oneTBB's source cannot be fetched or built, 1 when a test fails.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
which="${1:-parallel}"
case "$which" in
  parallel) suites=(test_massage test_pipeline test_cli) ;;
  all) suites=() ;;
  *) echo "usage: bash tools/tsan.sh [parallel|all]" >&2; exit 2 ;;
esac

build="$root/build-tsan"
tbb_prefix="$build/onetbb-install"
jobs="$(nproc 2>/dev/null || echo 2)"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

# 1. oneTBB built with ThreadSanitizer (once). Each step checks its status: set -e does not
# apply inside a function called as a condition.
build_onetbb() {
  local source_package source_version apt_dir f
  source_package="$(dpkg-query -W -f='${source:Package}' libtbb-dev)" || return 1
  source_version="$(dpkg-query -W -f='${source:Version}' libtbb-dev)" || return 1
  echo "tsan: building $source_package $source_version with -fsanitize=thread"
  if ! command -v dpkg-source >/dev/null 2>&1; then
    apt-get install -y -qq --no-install-recommends dpkg-dev || return 1
  fi
  apt_dir="$build/apt"
  rm -rf "$apt_dir" "$build/onetbb-src" "$build/onetbb-build"
  mkdir -p "$apt_dir/sources.list.d" "$apt_dir/lists/partial" "$apt_dir/download" || return 1
  # The machine's own Debian sources, as deb-src entries.
  for f in /etc/apt/sources.list.d/*.sources; do
    if [ -f "$f" ]; then
      sed 's/^Types:.*/Types: deb-src/' "$f" >"$apt_dir/sources.list.d/$(basename "$f")"
    fi
  done
  : >"$apt_dir/sources.list"
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    if [ -f "$f" ]; then sed -n 's/^deb /deb-src /p' "$f" >>"$apt_dir/sources.list"; fi
  done
  local apt_options=(-o "Dir::Etc::SourceList=$apt_dir/sources.list"
    -o "Dir::Etc::SourceParts=$apt_dir/sources.list.d" -o "Dir::State::Lists=$apt_dir/lists")
  apt-get "${apt_options[@]}" update -qq || return 1
  (cd "$apt_dir/download" &&
    apt-get "${apt_options[@]}" source -qq --download-only "$source_package=$source_version" &&
    dpkg-source -x ./*.dsc "$build/onetbb-src" >/dev/null) || return 1
  cmake -S "$build/onetbb-src" -B "$build/onetbb-build" "${generator[@]}" "${launcher[@]}" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_INSTALL_PREFIX="$tbb_prefix" \
    -DTBB_SANITIZE=thread -DTBB_STRICT=OFF -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF \
    -DTBBMALLOC_BUILD=OFF -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON >/dev/null || return 1
  cmake --build "$build/onetbb-build" -j"$jobs" || return 1
  cmake --install "$build/onetbb-build" >/dev/null || return 1
}
if [ ! -f "$tbb_prefix/lib/cmake/TBB/TBBConfig.cmake" ]; then
  if ! build_onetbb; then
    echo "tsan: could not fetch or build oneTBB with ThreadSanitizer (see above)" >&2
    exit 3
  fi
fi

# 2. seqmassage with ThreadSanitizer, against that oneTBB.
cmake -S . -B "$build" "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSEQMASSAGE_TSAN=ON -DSEQMASSAGE_BUILD_TOOLS=OFF -DSEQMASSAGE_PYTHON=OFF -DSEQMASSAGE_UNITY_BUILD=ON -DTBB_DIR="$tbb_prefix/lib/cmake/TBB" >/dev/null
if [ ${#suites[@]} -gt 0 ]; then
  cmake --build "$build" -j"$jobs" --target "${suites[@]}" seqmassage
else
  cmake --build "$build" -j"$jobs"
fi

# 3. The suites: any report fails the test (exit code 66).
export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1}"
regex=""
if [ ${#suites[@]} -gt 0 ]; then
  regex="^($(IFS='|'; echo "${suites[*]}"))\$"
fi
ctest --test-dir "$build" --output-on-failure -j"$jobs" ${regex:+-R "$regex"}
