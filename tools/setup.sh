#!/usr/bin/env bash
# Installs whatever seqmassage needs that this Debian machine lacks (apt-get), and nothing else.
# Safe to run again: packages already present are skipped.
#   bash tools/setup.sh            build and test dependencies
#   SEQMASSAGE_SETUP_EXTRAS=0 ...  skip the optional ones (plots, glTF validator, clang for fuzzing)
set -euo pipefail

packages=(g++ make cmake libeigen3-dev libtbb-dev nlohmann-json3-dev libtinygltf-dev catch2)
if [ "${SEQMASSAGE_SETUP_EXTRAS:-1}" = 1 ]; then
  # plots (tools/plot_distortion.py), glTF-Validator (node), libFuzzer and sanitizer runtimes
  packages+=(python3-matplotlib nodejs npm clang libclang-rt-dev)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
else
  echo "setup: all packages present"
fi

# The Khronos glTF-Validator (npm package), used by the glTF output tests when present.
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${SEQMASSAGE_SETUP_EXTRAS:-1}" = 1 ] && command -v npm >/dev/null 2>&1 &&
   [ ! -d "$root/tools/node_modules/gltf-validator" ]; then
  (cd "$root/tools" && npm install --silent --no-audit --no-fund --no-save gltf-validator@2 >/dev/null 2>&1) ||
    echo "setup: could not install gltf-validator (npm); glTF validation tests will skip"
fi
