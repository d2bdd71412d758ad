#!/usr/bin/env bash
# The tracking benchmark (docs/tracking-benchmark.md): untracked data sets made from tracked
# captures, the naive baseline, and the score of a tracker's output.
#
#   bash tools/bench_track.sh data OUT               build the GPL remesher, write OUT/samba,
#                                                    OUT/crane, OUT/horse (CGAL: libcgal-dev)
#   bash tools/bench_track.sh baseline OUT [SET...]  naive scheme into OUT/SET/baseline, scored
#                                                    (OUT/SET/baseline.txt, baseline.csv)
#   bash tools/bench_track.sh score OUT TRACKED      score TRACKED/SET for every SET of OUT
#                                                    that TRACKED has
#   bash tools/bench_track.sh score OUT FRAMES SET   score one folder of tracked frames
#
# Environment: SEQMASSAGE_DATA (default ../shared/data beside the checkout), BUILD (build
# folder, default build; the remesher is configured there with SEQMASSAGE_BUILD_GPL_BENCH=ON),
# CRANE_FRAMES (default 175), SEED (default 1), BASELINE_OPTIONS (massage key=value pairs for
# the baseline, e.g. 'iterations=30 distance_term=plane closest_points=exact').
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="${SEQMASSAGE_DATA:-$root/../shared/data}"
build="${BUILD:-$root/build}"
python=/usr/bin/python3
sets=(samba crane horse)

usage() { sed -n 2,18p "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 2; }
[ $# -ge 2 ] || usage
cmd="$1"
out="$2"
shift 2

remesher() {
  if [ ! -x "$build/tools/bench_track_remesh" ]; then
    cmake -S "$root" -B "$build" -DSEQMASSAGE_BUILD_GPL_BENCH=ON >/dev/null
    cmake --build "$build" -j2 --target bench_track_remesh >&2
  fi
  echo "$build/tools/bench_track_remesh"
}

make_set() {  # make_set NAME ARGS...: one data set, skipped when its meta.json exists
  local name="$1"
  shift
  if [ -f "$out/$name/meta.json" ]; then
    echo "bench_track: $out/$name exists, kept"
    return
  fi
  echo "bench_track: building $out/$name"
  "$tool" --out "$out/$name" --seed "${SEED:-1}" "$@"
}

module_path() {
  if [ ! -d "$build/python" ] || ! ls "$build"/python/seqmassage*.so >/dev/null 2>&1; then
    cmake --build "$build" -j2 --target seqmassage_python >&2
  fi
  echo "$build/python"
}

case "$cmd" in
  data)
    tool="$(remesher | tail -n 1)"
    seq="$data/sequences"
    # samba: the OBJ folder holds every 2nd source frame (frame k = mesh_{2k}).
    make_set samba --source "$seq/vlasic_samba"
    make_set crane --source "$seq/vlasic_crane_full/crane.pc2" \
      --rest "$seq/vlasic_crane_full/rest.obj" --count "${CRANE_FRAMES:-175}"
    # horse: the OBJ folder holds every 4th source frame (frame k = {4k+1}).
    make_set horse --source "$seq/sumner_horse_gallop"
    ;;
  baseline)
    [ $# -gt 0 ] || set -- "${sets[@]}"
    py="$(module_path)"
    for s in "$@"; do
      [ -f "$out/$s/meta.json" ] || { echo "bench_track: no data set $out/$s" >&2; exit 1; }
      # shellcheck disable=SC2086
      PYTHONPATH="$py" "$python" "$root/tools/bench_track_baseline.py" "$out/$s" \
        "$out/$s/baseline" ${BASELINE_OPTIONS:-}
      PYTHONPATH="$py" "$python" "$root/tools/bench_track_eval.py" "$out/$s" \
        "$out/$s/baseline" --csv "$out/$s/baseline.csv" | tee "$out/$s/baseline.txt"
    done
    ;;
  score)
    [ $# -ge 1 ] || usage
    tracked="$1"
    shift
    py="$(module_path)"
    if [ $# -ge 1 ]; then
      PYTHONPATH="$py" "$python" "$root/tools/bench_track_eval.py" "$out/$1" "$tracked"
      exit 0
    fi
    for s in "${sets[@]}"; do
      [ -d "$tracked/$s" ] && [ -f "$out/$s/meta.json" ] || continue
      PYTHONPATH="$py" "$python" "$root/tools/bench_track_eval.py" "$out/$s" "$tracked/$s"
    done
    ;;
  *) usage ;;
esac
