#!/usr/bin/env bash
# The README's first command: installs what is missing, builds seqmassage and runs the embedded
# default job (configs/demo.json: a generated drifted sequence, no outside data needed).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash tools/setup.sh
# Configured as tools/test.sh configures it (a unity build), so that the quick start builds what
# the tests passed on, and the test command reuses this build.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSEQMASSAGE_UNITY_BUILD=ON >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target seqmassage
./build/src/cli/seqmassage configs/demo.json "$@"
echo "demo: results are in $root/out/demo (frames/, summary.csv, report.json, distortion/,"
echo "  colored/ and checker/ before and after, iterations.csv); figures:"
echo "  /usr/bin/python3 tools/plot_distortion.py out/demo   (or bash tools/make_figures.sh)"
