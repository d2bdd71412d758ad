#!/usr/bin/env bash
# The browser test of report.html (tools/test.sh runs it after the Release build): writes the
# demo's report (configs/demo.json into out/demo) and a report of hostile strings (a frame named
# like an <img> tag, an output path holding </script><script>), then opens both from file:// in
# headless Chromium with no network (tests/web/report_browser.js) and saves the player's
# screenshot to out/demo/report_player.png (docs/images/report_player.png is a copy). Exit 3:
# skipped (no chromium, no node, or no puppeteer-core in web/node_modules: bash tools/setup.sh installs them), the message says why.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$root"
bin="${SEQMASSAGE_BIN:-build/src/cli/seqmassage}"
skip() {
  echo "report browser test SKIPPED: $1"
  exit 3
}
chromium="$(command -v chromium || command -v chromium-browser || true)"
[ -n "$chromium" ] || skip "no chromium (Debian's package; bash tools/setup.sh installs it)"
command -v node >/dev/null 2>&1 || skip "no node (bash tools/setup.sh installs nodejs)"
[ -d web/node_modules/puppeteer-core ] || skip "no web/node_modules/puppeteer-core (bash tools/setup.sh runs npm ci in web/)"
[ -x "$bin" ] || { echo "report browser test: $bin is missing (build it first)"; exit 1; }

"$bin" configs/demo.json >/dev/null 2>&1

# The hostile run: the demo's first frames under hostile names, into a hostile folder name.
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/frames"
i=0
for f in $(ls out/demo/input/*.obj | sort | head -n 4); do
  cp "$f" "$work/frames/frame_$i.obj"
  i=$((i + 1))
done
mv "$work/frames/frame_3.obj" "$work/frames/<img src=x onerror=alert(1)>.obj"
hostile_dir="$work/out</script><script>alert(1)</script>"
cat >"$work/config.json" <<JSON
{"job": "sequence", "input": {"frames": "$work/frames"}, "template": {"frame": 0},
 "output": {"dir": "$hostile_dir", "timings": false},
 "massage": {"iterations": 5}, "threads": 1}
JSON
"$bin" "$work/config.json" >/dev/null 2>&1

budget=$(( 50 * 1024 * 1024 ))
node tests/web/report_browser.js "$chromium" out/demo/report.html "$hostile_dir/report.html" \
  out/demo/report_player.png "$budget"
