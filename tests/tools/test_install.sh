#!/usr/bin/env bash
# `cmake --install` into a temporary prefix, then the installed files used as a user would, with
# nothing from the checkout or the build on any path: `seqmassage --version`, the demo config from
# share/doc/seqmassage/configs, `man -l` on the man page, bash completion, the Python module
# with only the prefix's folder on PYTHONPATH, and the add-on zip's bl_info. Also checks that
# docs/seqmassage.1 is what tools/make_manpage.sh writes from the current --help.
#   bash tests/tools/test_install.sh [BUILD_DIR]     (default build)
# Exit status: 0 passed, 1 failed.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
build="${1:-$root/build}"
log() { echo "test_install: $*"; }
fail() { log "FAILED: $*"; exit 1; }

version="$(sed -nE 's/^project\(seqmassage VERSION ([0-9.]+).*/\1/p' "$root/CMakeLists.txt")"
[ -n "$version" ] || fail "no project(seqmassage VERSION ...) in CMakeLists.txt"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
cmake --install "$build" --prefix "$prefix" >"$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install"; }
log "installed $(find "$prefix" -type f | wc -l) files under the prefix"

# No path of the checkout or the build in any installed text file (scripts, docs, configs).
if grep -rIl -e "$root" -e "$build" "$prefix" >"$tmp/leaks" 2>/dev/null; then
  fail "installed files name the source or build tree: $(cat "$tmp/leaks")"
fi

# The program, run from a folder outside the checkout with a minimal PATH.
cd "$tmp"
run() { env -i HOME="$tmp" PATH="$prefix/bin:/usr/bin:/bin" "$@"; }
out="$(run seqmassage --version)"
case "$out" in "seqmassage $version "*) ;; *) fail "--version printed '$out', expected seqmassage $version";; esac
log "--version: $out"
mkdir -p "$tmp/demo/configs"
cp "$prefix/share/doc/seqmassage/configs/demo.json" "$tmp/demo/configs/"
run seqmassage -q "$tmp/demo/configs/demo.json" || fail "the demo config from share/ did not run"
[ -s "$tmp/demo/out/demo/summary.csv" ] || fail "the demo wrote no summary.csv"
frames="$(($(wc -l <"$tmp/demo/out/demo/summary.csv") - 1))"
[ "$frames" = 24 ] || fail "the demo's summary has $frames rows, expected 24"
log "demo config from share/doc/seqmassage/configs: 24 frames"

# The man page: renders, names the version, lists the options of the current --help.
page="$prefix/share/man/man1/seqmassage.1"
[ -f "$page" ] || fail "no man page at share/man/man1/seqmassage.1"
if command -v man >/dev/null; then
  text="$(MANWIDTH=100 man -l "$page" 2>/dev/null | col -b 2>/dev/null || MANWIDTH=100 man -l "$page")"
  grep -q -- "--threads" <<<"$text" || fail "man -l: no --threads in the page"
  grep -q "seqmassage $version" <<<"$text" || fail "man -l: the page is not of version $version"
  log "man -l: $(wc -l <<<"$text") lines"
else
  log "man not installed: the page's rendering not checked"
fi
if command -v help2man >/dev/null; then
  bash "$root/tools/make_manpage.sh" "$build/src/cli/seqmassage" "$tmp/seqmassage.1"
  # The page's date (the .TH line) and help2man's own version line do not count.
  strip() { grep -v -e '^\.TH ' -e '^\.\\" DO NOT MODIFY' "$1"; }
  diff <(strip "$root/docs/seqmassage.1") <(strip "$tmp/seqmassage.1") >"$tmp/man.diff" ||
    { cat "$tmp/man.diff"; fail "docs/seqmassage.1 is stale: run bash tools/make_manpage.sh"; }
  log "docs/seqmassage.1 is current"
else
  log "help2man not installed: docs/seqmassage.1 not compared with --help"
fi

# Bash completion: commands, options and config files.
completion="$prefix/share/bash-completion/completions/seqmassage"
[ -f "$completion" ] || fail "no bash completion"
mkdir -p "$tmp/cfg" && touch "$tmp/cfg/a.json" "$tmp/cfg/b.txt"
complete_words() {  # complete_words WORD... : what completing the last word offers
  env -i HOME="$tmp" PATH="$prefix/bin:/usr/bin:/bin" bash -c '
    source "$0"; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); COMP_LINE="$*"; COMP_POINT=${#COMP_LINE}
    _seqmassage; printf "%s\n" "${COMPREPLY[@]}"' "$completion" "$@"
}
# Captured first: grep -q in a pipe would stop reading at its match, and the writer's SIGPIPE
# fails the pipeline under pipefail now and then.
offered="$(cd "$tmp/cfg" && complete_words seqmassage --thr)"
grep -qx -- "--threads" <<<"$offered" || fail "completion: --thr"
offered="$(cd "$tmp/cfg" && complete_words seqmassage me)"
grep -qx "merge" <<<"$offered" || fail "completion: commands"
offered="$(cd "$tmp/cfg" && complete_words seqmassage merge -)"
grep -qx -- "--quiet" <<<"$offered" || fail "completion: merge options"
got="$(cd "$tmp/cfg" && complete_words seqmassage "")"
grep -qx "a.json" <<<"$got" || fail "completion: config files ($got)"
grep -qx "b.txt" <<<"$got" && fail "completion offers a non-config file"
log "bash completion: commands, options, config files"

# The Python module with only the prefix's folder on the path.
module="$(find "$prefix" -name 'seqmassage*.so' | head -1)"
if [ -n "$module" ]; then
  pydir="$(dirname "$module")"
  [ -f "$pydir/seqmassage.pyi" ] || fail "no seqmassage.pyi next to the module"
  got="$(env -i HOME="$tmp" PYTHONPATH="$pydir" /usr/bin/python3 -c \
    "import seqmassage; print(seqmassage.__version__, seqmassage.__file__)")"
  case "$got" in "$version $prefix/"*) ;; *) fail "import seqmassage: '$got'";; esac
  log "python3 -c 'import seqmassage' from ${pydir#"$prefix"/}: $got"
else
  log "the Python module is not installed (not built): skipped"
fi

# The add-on zip: one top folder, bl_info of the project's version.
zip="$prefix/share/seqmassage/seqmassage_blender.zip"
[ -f "$zip" ] || fail "no add-on zip"
/usr/bin/python3 - "$zip" "$version" <<'PY' || fail "add-on zip"
import ast, sys, zipfile
names = zipfile.ZipFile(sys.argv[1]).namelist()
assert all(n.startswith("seqmassage_blender/") for n in names), names
tree = ast.parse(zipfile.ZipFile(sys.argv[1]).read("seqmassage_blender/__init__.py"))
info = next(ast.literal_eval(n.value) for n in tree.body
            if isinstance(n, ast.Assign) and n.targets[0].id == "bl_info")
want = tuple(int(x) for x in sys.argv[2].split("."))
assert info["version"] == want, (info["version"], want)
PY
log "add-on zip: bl_info version $version"
log "PASSED"
