#!/usr/bin/env bash
# Installs whatever seqmassage needs that this Debian machine lacks (apt-get), and nothing else.
# Safe to run again: what is present is skipped.
#   bash tools/setup.sh             build and test dependencies, then the optional extras
#   SEQMASSAGE_SETUP_EXTRAS=0 ...   skip the extras (plots, glTF validator, clang for fuzzing,
#                                   Blender)
# The required packages must install; an extra that cannot be installed only prints a warning
# (its tests then skip with a message).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
updated=0
apt_install() {
  if [ "$updated" = 0 ]; then
    $sudo apt-get update -qq
    updated=1
  fi
  $sudo apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}
have_pkg() { dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"; }

required=(g++ make cmake libeigen3-dev libtbb-dev nlohmann-json3-dev libtinygltf-dev catch2
  libssl-dev libstb-dev libcli11-dev pybind11-dev python3-dev python3-numpy python3-pytest
  # Installing and packaging (tests/tools/test_install.sh, test_deb.sh, test_pip.sh): the man
  # page, the .deb's Depends (dpkg-shlibdeps, file), pip in a venv, the stubs' type check, and
  # ccache, which lets the pip build reuse the objects of build/.
  help2man man-db dpkg-dev file python3-venv python3-setuptools python3-wheel mypy ccache)
missing=()
for p in "${required[@]}"; do have_pkg "$p" || missing+=("$p"); done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  apt_install "${missing[@]}"
else
  echo "setup: build and test packages present"
fi

[ "${SEQMASSAGE_SETUP_EXTRAS:-1}" = 1 ] || exit 0

# Extras, each best-effort: plots, sanitizer/libFuzzer runtimes, node for the glTF-Validator.
extra() {  # extra NAME CHECK-COMMAND PACKAGE...
  local name="$1" check="$2"
  shift 2
  if eval "$check" >/dev/null 2>&1; then return 0; fi
  echo "setup: installing $name ($*)"
  apt_install "$@" || echo "setup: warning: could not install $name; its tests will skip"
}
extra "matplotlib" "/usr/bin/python3 -c 'import matplotlib'" python3-matplotlib
extra "clang" "command -v clang++" clang
extra "clang runtimes" "have_pkg libclang-rt-dev || have_pkg libclang-rt-14-dev" libclang-rt-dev
extra "dpkg-source (oneTBB source for ThreadSanitizer)" "command -v dpkg-source" dpkg-dev
extra "node and npm" "command -v node && command -v npm" nodejs npm
# kubectl for the Kubernetes manifest's test; Debian's conflicts with other kubectl packages.
extra "kubectl" "command -v kubectl" kubernetes-client
# Blender for the add-on's tests (its Debian build runs the system Python 3, as the module
# does), and a virtual X display for the panel's screenshot (tools/blender_screenshot.sh) and
# the modal operators' test (tests/blender/test_modal_cancel.py, a windowed Blender).
extra "blender" "command -v blender" blender
extra "xvfb" "command -v xvfb-run" xvfb

# The Khronos glTF-Validator (npm package), used by the glTF output tests when present.
if command -v npm >/dev/null 2>&1 && [ ! -d "$root/tools/node_modules/gltf-validator" ]; then
  (cd "$root/tools" && npm install --silent --no-audit --no-fund --no-save gltf-validator@2.0.0-dev.3.10 >/dev/null 2>&1) ||
    echo "setup: warning: could not install gltf-validator (npm); glTF validation tests will skip"
fi
# report.html's 3D player (three.js, bundled by esbuild at build time) and the browser test's
# driver (puppeteer-core), from npm at the versions web/package-lock.json pins; and Debian's
# chromium, which the browser test drives headless. Without them the report keeps its tables
# and plots and says why the player is missing, and the browser test skips.
if command -v npm >/dev/null 2>&1 && [ ! -x "$root/web/node_modules/.bin/esbuild" ]; then
  (cd "$root/web" && npm ci --silent --no-audit --no-fund >/dev/null 2>&1) ||
    echo "setup: warning: could not install web/node_modules (npm ci); report.html will have no 3D player"
fi
extra "chromium" "command -v chromium" chromium
exit 0
