#!/usr/bin/env bash
# Benchmark of the sequence job on every animated glTF model of ../shared/data/gltf: one run per
# model (default mesh and animation, keyframe times or --fps), GLB output, then the Khronos
# glTF-Validator on the GLB. Prints one row per model: glTF vertices, welded vertices, frames,
# wall time, frames/s, peak memory, mean shear before -> after (mean over frames of the per-frame
# mean, eq. 8), the largest distance between output and input surface, and the validator result.
# Prints timings only; asserts nothing.
#
#   bash tools/bench_gltf.sh [--threads N] [--fps F] [--iterations K] [--format gltf|obj]
#                            [--shape-target template|zero]
#
# Needs build/src/cli/seqmassage (cmake --build build --target seqmassage) and /usr/bin/python3;
# node with tools/node_modules/gltf-validator for the validator column (else "not run").
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
data="$root/../shared/data/gltf"
bin="$root/build/src/cli/seqmassage"
threads=0 fps="" iterations=15 format=gltf target=template
while [ $# -gt 0 ]; do
  case "$1" in
    --threads) threads="$2"; shift 2 ;;
    --fps) fps="$2"; shift 2 ;;
    --iterations) iterations="$2"; shift 2 ;;
    --format) format="$2"; shift 2 ;;
    --shape-target) target="$2"; shift 2 ;;
    *) echo "usage: bash tools/bench_gltf.sh [--threads N] [--fps F] [--iterations K] [--format gltf|obj] [--shape-target template|zero]" >&2; exit 2 ;;
  esac
done
[ -x "$bin" ] || { echo "bench_gltf: build seqmassage first ($bin not found)" >&2; exit 1; }
[ -d "$data" ] || { echo "bench_gltf: skipped: no glTF models at $data"; exit 0; }

models=(
  skinned/CesiumMan/glTF-Binary/CesiumMan.glb
  skinned/RiggedSimple/glTF-Binary/RiggedSimple.glb
  skinned/RiggedFigure/glTF-Binary/RiggedFigure.glb
  skinned/Fox/glTF-Binary/Fox.glb
  skinned/SimpleSkin/glTF/SimpleSkin.gltf
  morph/AnimatedMorphCube/glTF-Binary/AnimatedMorphCube.glb
  morph/AnimatedMorphSphere/glTF-Binary/AnimatedMorphSphere.glb
  morph/MorphStressTest/glTF-Binary/MorphStressTest.glb
  morph/SimpleMorph/glTF/SimpleMorph.gltf
)
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
validator=0
node "$root/tools/validate_gltf.js" --check >/dev/null 2>&1 && validator=1

printf '%-22s %6s %6s %6s %6s %8s %8s %8s  %-19s %10s  %s\n' model gltf_v welded frames failed wall_s frames/s peak_MB \
  "shear before->after" max_dist validator
for m in "${models[@]}"; do
  name="$(basename "${m%.*}")"
  fps_key=""
  [ -n "$fps" ] && fps_key=", \"fps\": $fps"
  cat >"$work/$name.json" <<JSON
{"job": "sequence", "input": {"gltf": "$data/$m"$fps_key},
 "output": {"dir": "$work/$name", "format": "$format"},
 "massage": {"iterations": $iterations, "shape_target": "$target"}, "threads": $threads}
JSON
  /usr/bin/time -f '%e %M' -o "$work/$name.time" "$bin" -q "$work/$name.json" 2>"$work/$name.log" ||
    true
  # A non-zero exit (some frames failed: see the failed column) puts a "Command exited" line first.
  read -r wall kb < <(tail -n 1 "$work/$name.time")
  check="not run"
  if [ "$format" = gltf ] && [ "$validator" = 1 ]; then
    check="$(node "$root/tools/validate_gltf.js" "$work/$name/sequence.glb" | head -n 1 | sed 's/^.*: //')"
  fi
  /usr/bin/python3 - "$work/$name/report.json" "$name" "$wall" "$kb" "$check" <<'PY'
import json, sys
path, name, wall, kb, check = sys.argv[1:]
r = json.load(open(path))
i, t = r["input"], r["totals"]
frames = t["frames_written"]
wall = float(wall)
shear = "%.4f -> %.4f" % (t["shear_before"]["mean_of_means"], t["shear_after"]["mean_of_means"])
print("%-22s %6d %6d %6d %6d %8.2f %8.1f %8.1f  %-19s %10.3g  %s" % (
    name, i["gltf_vertices"], i["vertices"], frames, t["failed"], wall, frames / wall if wall > 0 else 0,
    int(kb) / 1024, shear, t["hausdorff_max"], check))
PY
done
