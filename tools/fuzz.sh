#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, Release with ASan + UBSan, assertions kept) into build-fuzz/
# and runs each for SECONDS (default 60), one after another.
#   bash tools/fuzz.sh [SECONDS] [TARGET...]      targets: obj off ply config gltf point_cache (default: all)
#   FUZZ_ARGS="-max_len=8192" bash tools/fuzz.sh   extra libFuzzer flags
# The growing corpus of each target is build-fuzz/corpus/<target>/ (kept between runs; seeded from
# tests/fuzz/corpus/<target>/ and tests/fuzz/regressions/<target>/). A crash or finding stops that
# target and leaves its input in build-fuzz/artifacts/<target>/; after fixing it, copy the input to
# tests/fuzz/regressions/<target>/, where test_fuzz_regressions replays it in every build.
# Exits 1 if any target found something.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

all_targets=(obj off ply config gltf point_cache)
seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || [ "$seconds" -lt 1 ]; then
  echo "usage: bash tools/fuzz.sh [SECONDS] [TARGET...]   (targets: ${all_targets[*]})" >&2
  exit 2
fi
shift $(($# > 0 ? 1 : 0))
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=("${all_targets[@]}")
for t in "${targets[@]}"; do
  if [[ " ${all_targets[*]} " != *" $t "* ]]; then
    echo "fuzz: unknown target '$t' (targets: ${all_targets[*]})" >&2
    exit 2
  fi
done

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz: clang++ not found; installing the extras with tools/setup.sh" >&2
  bash tools/setup.sh
fi
command -v clang++ >/dev/null 2>&1 || { echo "fuzz: clang++ is required" >&2; exit 1; }

build="$root/build-fuzz"
generator=()
command -v ninja >/dev/null 2>&1 && generator=(-G Ninja)
launcher=()
command -v ccache >/dev/null 2>&1 && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# -O2 -g without -DNDEBUG: an optimized build whose assertions (Eigen's index checks) stay on.
cmake -S . -B "$build" "${generator[@]}" "${launcher[@]}" \
  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O2 -g" \
  -DSEQMASSAGE_ASAN=ON -DSEQMASSAGE_FUZZ=ON -DSEQMASSAGE_BUILD_TESTS=OFF \
  -DSEQMASSAGE_BUILD_TOOLS=OFF >/dev/null
jobs="$(nproc 2>/dev/null || echo 2)"
cmake --build "$build" -j"$jobs" --target "${targets[@]/#/fuzz_}"

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
status=0
summary=()
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"
  artifacts="$build/artifacts/$t"
  log="$build/fuzz_$t.log"
  mkdir -p "$corpus" "$artifacts"
  seeds=("tests/fuzz/corpus/$t")
  [ -d "tests/fuzz/regressions/$t" ] && seeds+=("tests/fuzz/regressions/$t")
  dict=()
  [ -f "tests/fuzz/dict/$t.dict" ] && dict=("-dict=tests/fuzz/dict/$t.dict")
  echo "fuzz: $t for ${seconds}s (log: ${log#"$root"/})"
  # shellcheck disable=SC2086
  if "$build/tests/fuzz/fuzz_$t" -max_total_time="$seconds" -print_final_stats=1 -timeout=10 \
    -rss_limit_mb=1024 -artifact_prefix="$artifacts/" "${dict[@]}" ${FUZZ_ARGS:-} \
    "$corpus" "${seeds[@]}" >"$log" 2>&1; then
    result="no finding"
  else
    result="FINDING (see $log and ${artifacts#"$root"/}/)"
    status=1
  fi
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)"
  rate="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)"
  cov="$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)"
  corp="$(grep -o 'corp: [0-9]*/[0-9]*[a-zA-Z]*' "$log" | tail -1 | cut -d' ' -f2)"
  files="$(find "$corpus" -type f | wc -l)"
  # corpus: libFuzzer's final corpus (units/bytes); files: everything kept in build-fuzz/corpus.
  summary+=("$(printf '%-7s %5ss %9s runs %6s exec/s  cov %5s  corpus %11s  (%s files)  %s' \
    "$t" "$seconds" "${runs:-?}" "${rate:-?}" "${cov:-?}" "${corp:-?}" "$files" "$result")")
done
printf '%s\n' "${summary[@]}"
exit "$status"
