#!/usr/bin/env bash
# The add-on's panel as PNG, docs/images/blender-panel.png: Blender drawn headless on a virtual X
# display (Xvfb), the scene and the panel set up by tools/blender_screenshot.py. Needs blender,
# xvfb-run (Debian: xvfb) and the built module (build/python).
#   bash tools/blender_screenshot.sh [OUT.png]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/docs/images/blender-panel.png}")"
for tool in blender xvfb-run; do
  command -v "$tool" >/dev/null || { echo "blender_screenshot: $tool not installed" >&2; exit 1; }
done
mkdir -p "$(dirname "$out")"
rm -f "$out"
export SEQMASSAGE_ROOT="$root"
unset PYTHONPATH
# Blender's UI needs OpenGL 3.3: Mesa's software renderer on the virtual display gives it.
xvfb-run -a -s "-screen 0 900x1100x24" \
  blender --factory-startup --window-geometry 0 0 900 1100 \
  --python "$root/tools/blender_screenshot.py" -- "$out"
[ -s "$out" ] || { echo "blender_screenshot: no $out written (see above)" >&2; exit 1; }
echo "blender_screenshot: $out"
