#!/usr/bin/env bash
# Regenerates the documentation's figures (tools/figures/*.png) from the demo run: runs tools/demo.sh
# (build, then configs/demo.json into out/demo), then plot_distortion.py (Figures 5, 7, 8 of the
# paper) and render_mesh.py (Figures 4 and 6) on frame 23, the demo's most bent frame.
#   bash tools/make_figures.sh             run the demo, then draw
#   bash tools/make_figures.sh --no-run    draw from an existing out/demo
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if [ "${1:-}" != "--no-run" ]; then
  bash tools/demo.sh >/dev/null
fi
run=out/demo
[ -f "$run/summary.csv" ] || { echo "make_figures: $run/summary.csv not found (run without --no-run)" >&2; exit 1; }
py=/usr/bin/python3
"$py" -c 'import matplotlib' 2>/dev/null || py=python3
frame=23
name="$(printf 'frame_%04d' "$frame")"
shear_red="$("$py" -c 'import json, sys; print(json.load(open(sys.argv[1]))["outputs"]["colored"]["shear_red"])' "$run/report.json")"

figures=tools/figures
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$figures"
"$py" tools/plot_distortion.py "$run" --out "$tmp" --frame "$frame" --formats png --dpi 70 >/dev/null
cp "$tmp/shear_per_frame.png" "$figures/fig5_shear_per_frame.png"
cp "$tmp/shear_histogram_$name.png" "$figures/fig7_shear_histogram.png"
cp "$tmp/convergence.png" "$figures/fig8_convergence.png"
view=(--elev 10 --azim -90 --zoom 1.3 --dpi 75)
"$py" tools/render_mesh.py "$run/colored/before/$name.ply" "$run/colored/after/$name.ply" \
  --out "$figures/fig4_colored.png" --titles "input, frame $frame" "corrected, frame $frame" \
  --colorbar "$shear_red" "${view[@]}" >/dev/null
"$py" tools/render_mesh.py "$run/checker/before/$name.obj" "$run/checker/after/$name.obj" \
  --out "$figures/fig6_checker.png" --titles "input, frame $frame" "corrected, frame $frame" \
  --subdivide 5 "${view[@]}" >/dev/null
ls -l "$figures"
