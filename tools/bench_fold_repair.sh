#!/usr/bin/env bash
# Fold repair (checks.repair_folds) on the morph-target sphere and on the sequences without folds
# over the limit: runs a config with the repair off and on (same build, one after the other) and
# prints per run the frames refused, the frames repaired, frames with a fold left in the output,
# the mean shear before -> after (mean over frames of the per-frame mean, eq. 8; refused frames
# count as unchanged) and the wall time; then whether the written frames of the two runs are
# byte-identical. Prints figures only; asserts nothing.
#
#   bash tools/bench_fold_repair.sh [config.json] [--threads N]   (default configs/morph_sphere.json)
#
# Needs build/src/cli/seqmassage and /usr/bin/python3.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="$root/build/src/cli/seqmassage"
config="$root/configs/morph_sphere.json" threads=2
while [ $# -gt 0 ]; do
  case "$1" in
    --threads) threads="$2"; shift 2 ;;
    *) config="$1"; shift ;;
  esac
done
[ -x "$bin" ] || { echo "bench_fold_repair: build seqmassage first ($bin not found)" >&2; exit 1; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for repair in false true; do
  /usr/bin/python3 - "$config" "$work/$repair" "$repair" >"$work/$repair.json" <<'PY'
import json, os, sys
config, out, repair = sys.argv[1:]
c = json.load(open(config))
base = os.path.dirname(os.path.abspath(config))
for key in ("gltf", "frames", "pc2", "mdd", "mesh"):
    if key in c.get("input", {}) and isinstance(c["input"][key], str):
        c["input"][key] = os.path.join(base, c["input"][key])
if "mesh" in c.get("template", {}):
    c["template"]["mesh"] = os.path.join(base, c["template"]["mesh"])
c.setdefault("output", {})["dir"] = out
c["output"]["timings"] = False
c.setdefault("checks", {})["repair_folds"] = repair == "true"
print(json.dumps(c))
PY
  start=$(date +%s.%N)
  "$bin" -q --threads "$threads" "$work/$repair.json" 2>"$work/$repair.log" || true
  end=$(date +%s.%N)
  /usr/bin/python3 - "$work/$repair/report.json" "$work/$repair/summary.csv" "$repair" "$start" "$end" <<'PY'
import csv, json, sys
report, summary, repair, start, end = sys.argv[1:]
r = json.load(open(report))
t = r["totals"]
rows = list(csv.DictReader(open(summary)))
refused = sum(1 for x in rows if x["status"] == "failed")
folded_out = sum(1 for x in rows if x["status"] != "failed" and int(x["folded_triangles"]) > 0)
text = json.dumps(r)
repaired = text.count("repaired in")
print("repair_folds=%-5s frames %d, refused %d (%.1f %%), repaired %d, written optimized with a "
      "fold %d, mean shear %.4f -> %.4f, wall %.2f s" % (
          repair, len(rows), refused, 100.0 * refused / max(1, len(rows)), repaired, folded_out,
          t["shear_before"]["mean_of_means"], t["shear_after"]["mean_of_means"],
          float(end) - float(start)))
PY
done
if diff -rq -x report.json -x records -x summary.csv "$work/false" "$work/true" >/dev/null; then
  echo "outputs (frames, distortion tables): identical"
else
  echo "outputs (frames, distortion tables): $(diff -rq -x report.json -x records -x summary.csv "$work/false" "$work/true" | wc -l) files differ"
fi
