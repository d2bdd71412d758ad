#!/usr/bin/env bash
# The README's first command: installs what is missing, builds seqmassage and runs the embedded
# default job (configs/demo.json: a generated drifted sequence, no outside data needed).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target seqmassage
./build/src/cli/seqmassage configs/demo.json "$@"
echo "demo: results are in $root/out/demo (frames/, summary.csv, report.json, distortion/,"
echo "  colored/ and checker/ before and after, iterations.csv); figures:"
echo "  /usr/bin/python3 tools/plot_distortion.py out/demo   (or bash tools/make_figures.sh)"
