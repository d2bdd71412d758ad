#!/usr/bin/env bash
# report.html's size and writing time on the demo, a folder of OBJ frames (e.g. the crane) and a
# generated 1,000-frame sequence: runs each job and prints the page's size, the frames its player
# keeps, the run's time and the time of the whole-run outputs (report.json's
# run.seconds_outputs_finish: report.html, assembled from report_data/, and iterations.csv).
#   bash tools/bench_report_html.sh [FRAMES_FOLDER ...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${SEQMASSAGE_BIN:-$root/build/src/cli/seqmassage}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

report() {  # report NAME OUTPUT_DIR
  /usr/bin/python3 - "$1" "$2" <<'PY'
import json, os, re, sys
name, out = sys.argv[1], sys.argv[2]
r = json.load(open(os.path.join(out, "report.json")))
page = open(os.path.join(out, "report.html"), encoding="utf-8").read()
data = json.loads(re.search(r'id="sm-data">(.*?)</script>', page, re.S).group(1))
p = data.get("player") or {}
run = r.get("run", {})
print(f"{name}: {r['totals']['frames_written']} frames, {p.get('vertices', '?')} vertices; "
      f"report.html {os.path.getsize(os.path.join(out, 'report.html')) / 2**20:.2f} MiB, "
      f"player keeps {len(p.get('frames', []))} of {p.get('frames_total', 0)} frames; "
      f"run {run.get('seconds', 0):.2f} s, whole-run outputs {run.get('seconds_outputs_finish', 0):.3f} s "
      f"({100 * run.get('seconds_outputs_finish', 0) / max(run.get('seconds', 1), 1e-9):.1f} % of the run)")
PY
}

/usr/bin/python3 -c 'import json, sys; c = json.load(open(sys.argv[1])); c["output"]["dir"] = sys.argv[2]
json.dump(c, open(sys.argv[3], "w"))' "$root/configs/demo.json" "$work/demo" "$work/demo.json"
"$bin" "$work/demo.json" >/dev/null 2>&1
report demo "$work/demo"

for frames in "$@"; do
  name="$(basename "$frames")"
  cat >"$work/$name.json" <<JSON
{"job": "sequence", "input": {"frames": "$frames"}, "output": {"dir": "$work/$name"}}
JSON
  "$bin" "$work/$name.json" >/dev/null 2>&1
  report "$name" "$work/$name"
done

cat >"$work/long.json" <<JSON
{"job": "sequence",
 "input": {"synthetic": {"frames": 1000, "segments": 16, "rings": 24, "drift": 0.6}},
 "output": {"dir": "$work/long"}, "massage": {"iterations": 3}}
JSON
"$bin" "$work/long.json" >/dev/null 2>&1
report "generated, 1000 frames" "$work/long"
