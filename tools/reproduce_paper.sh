#!/usr/bin/env bash
# Builds tools/reproduce_paper and runs it: the paper's kinds of experiment (remeshes of the bunny
# and the fandisk, smoothing of the fandisk, cross-parameterizations) on ../shared/data, with the
# tables written into docs/paper.md. Skips with a message without the data.
# Extra arguments go to the program (e.g. --no-readme, --threads 1).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target reproduce_paper
./build/tools/reproduce_paper "$@"
