#!/usr/bin/env bash
# Shows that a change keeps every output byte: builds seqmassage at a base commit and from the
# working tree, runs the same jobs with both and compares every file they write.
#
#   bash tools/compare_outputs.sh [BASE]     BASE: a commit (default: the merge base with main,
#                                            or HEAD~1 on main itself), e.g. HEAD~3 or main
#
# Jobs: configs/demo.json; the Vlasic crane (configs/sequence_example.json) and samba sequences;
# CesiumMan to GLB (configs/gltf_cesiumman.json); configs/remesh_*.json and smooth_fandisk.json,
# each with "output.timings": false. A job whose data is absent is skipped with a message. Data:
# $SEQMASSAGE_DATA, default ../shared/data beside the checkout (where configs/ point).
# Every output file must be byte-identical; report.json (and report.shard-*.json) may differ only
# in "versions". Builds go to build-compare/ (kept, so a rerun is incremental). Exit status: 0
# identical, 1 differences, 2 usage or build error.
#   BASE_BIN=... NEW_BIN=... bash tools/compare_outputs.sh BASE   use these seqmassage builds
#                                            (of BASE and of the working tree) instead of building
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

base="${1:-}"
if [[ -z "$base" ]]; then
  base="$(git merge-base HEAD main 2>/dev/null || true)"
  [[ -z "$base" || "$base" == "$(git rev-parse HEAD)" ]] && base="HEAD~1"
fi
if ! base_sha="$(git rev-parse --verify --quiet "$base^{commit}")"; then
  echo "compare_outputs: '$base' is not a commit" >&2
  exit 2
fi
data="${SEQMASSAGE_DATA:-$root/../shared/data}"
jobs="$(nproc 2>/dev/null || echo 2)"

builds="$root/build-compare"
base_src="$builds/src-${base_sha:0:12}"
if [[ ! -f "$base_src/CMakeLists.txt" ]]; then
  rm -rf "$base_src"
  mkdir -p "$base_src"
  git archive "$base_sha" | tar -x -C "$base_src"
fi
build() {  # source dir, build dir
  cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$2" -j"$jobs" --target seqmassage >/dev/null
}
base_bin="${BASE_BIN:-$builds/base-${base_sha:0:12}/src/cli/seqmassage}"
new_bin="${NEW_BIN:-$builds/new/src/cli/seqmassage}"
if [[ -z "${BASE_BIN:-}" ]]; then
  echo "building base ${base_sha:0:12} ($(git log -1 --format=%s "$base_sha" | cut -c1-60))"
  build "$base_src" "$builds/base-${base_sha:0:12}" ||
    { echo "compare_outputs: base build failed" >&2; exit 2; }
fi
if [[ -z "${NEW_BIN:-}" ]]; then
  echo "building the working tree"
  build "$root" "$builds/new" || { echo "compare_outputs: working tree build failed" >&2; exit 2; }
fi
for b in "$base_bin" "$new_bin"; do
  [[ -x "$b" ]] || { echo "compare_outputs: '$b' is not an executable" >&2; exit 2; }
done

# Both builds run the same config files at the same absolute paths, so that the paths written
# into reports and records agree: <work>/w/configs/*.json, data at <work>/shared/data, outputs
# under <work>/w/out, moved aside after each build's run.
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/w/configs" "$work/shared"
ln -s "$(cd "$data" 2>/dev/null && pwd || echo "$data")" "$work/shared/data"

cases=()
add_case() {  # config file name in configs/, data it needs ("" for none)[, sed expression]
  local name="$1" needs="$2" edit="${3:-}"
  local src="configs/$name"
  [[ -f "$src" ]] || src="configs/sequence_example.json"  # the samba copy
  if [[ -n "$needs" && ! -e "$data/$needs" ]]; then
    echo "skipped $name: $data/$needs is absent"
    return
  fi
  local timings='s/"output": *{/"output": { "timings": false,/'
  grep -q '"timings"' "$src" && timings='s/"timings": *true/"timings": false/'
  sed -e "$timings" ${edit:+-e "$edit"} "$src" >"$work/w/configs/$name"
  cases+=("$name")
}
add_case demo.json ""
add_case sequence_example.json sequences/vlasic_crane
add_case samba.json sequences/vlasic_samba 's/vlasic_crane/vlasic_samba/g'
add_case gltf_cesiumman.json gltf/skinned/CesiumMan
for f in configs/remesh_*.json; do
  needs="$(grep -o 'shared/data/[^"]*' "$f" | head -1 | sed 's|shared/data/||')"
  add_case "$(basename "$f")" "$needs"
done
add_case smooth_fandisk.json static/fandisk/c3d_fandisk.obj
[[ ${#cases[@]} -gt 0 ]] || { echo "compare_outputs: no job to run" >&2; exit 2; }

run_all() {  # binary, where the outputs go
  for c in "${cases[@]}"; do
    local status=0
    "$1" -q "$work/w/configs/$c" >"$work/w/$c.log" 2>&1 || status=$?
    echo "  $c: exit $status" >>"$work/status-$(basename "$2")"
  done
  mv "$work/w/out" "$2"
}
echo "running ${#cases[@]} jobs with the base build"
run_all "$base_bin" "$work/base"
echo "running ${#cases[@]} jobs with the working tree build"
run_all "$new_bin" "$work/new"

# Every file, byte for byte; reports also without their "versions".
same_report() {
  /usr/bin/env python3 - "$1" "$2" <<'EOF'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for r in (a, b):
    r.pop("versions", None)
sys.exit(0 if a == b else 1)
EOF
}
status=0
if ! diff -q "$work/status-base" "$work/status-new" >/dev/null; then
  echo "exit statuses differ:"
  diff "$work/status-base" "$work/status-new" || true
  status=1
fi
(cd "$work/base" && find . -type f | sort) >"$work/files-base"
(cd "$work/new" && find . -type f | sort) >"$work/files-new"
if ! diff -q "$work/files-base" "$work/files-new" >/dev/null; then
  echo "file lists differ (< base only, > working tree only):"
  diff "$work/files-base" "$work/files-new" | grep '^[<>]' || true
  status=1
fi
identical=0
versions_only=0
while read -r f; do
  [[ -f "$work/new/$f" ]] || continue
  if cmp -s "$work/base/$f" "$work/new/$f"; then
    identical=$((identical + 1))
  elif [[ "$(basename "$f")" == report*.json ]] && same_report "$work/base/$f" "$work/new/$f"; then
    versions_only=$((versions_only + 1))
  else
    echo "differs: ${f#./}"
    status=1
  fi
done <"$work/files-base"
for c in "${cases[@]}"; do
  dir="$(sed -n 's/.*"dir": *"\.\.\/out\/\([^"]*\)".*/\1/p' "$work/w/configs/$c")"
  n="$(grep -c "^\./$dir/" "$work/files-base" || true)"
  echo "  $c: $n files ($(grep "  $c:" "$work/status-base" | sed 's/.*: //'))"
done
echo "base ${base_sha:0:12} vs working tree: $identical files identical, $versions_only reports" \
  "differing only in versions, $(wc -l <"$work/files-base") files in all"
[[ $status -eq 0 ]] && echo "every output byte is the same" || echo "outputs differ"
exit $status
