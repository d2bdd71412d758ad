#!/usr/bin/env bash
# Writes docs/seqmassage.1, the man page seqmassage(1), from the program's own --help and
# --version (help2man, Debian's help2man). Run after changing the help text or the version;
# tests/tools/test_install.sh checks that the page is current.
#   bash tools/make_manpage.sh [PROGRAM [OUTPUT]]   (default build/src/cli/seqmassage, docs/seqmassage.1)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
program="${1:-$root/build/src/cli/seqmassage}"
output="${2:-$root/docs/seqmassage.1}"
command -v help2man >/dev/null || { echo "make_manpage: help2man is not installed" >&2; exit 3; }
extra="$(mktemp)"
trap 'rm -f "$extra"' EXIT
{
  echo "[SEE ALSO]"
  echo "The configuration reference: \\fBseqmassage config \\-\\-reference\\fR;"
  echo "the commands' own help: \\fBseqmassage measure \\-\\-help\\fR, \\fBseqmassage merge \\-\\-help\\fR."
  echo "The documentation, example configs and the Blender add-on are installed under"
  echo "\\fIshare/doc/seqmassage\\fR and \\fIshare/seqmassage\\fR of the installation prefix."
} >"$extra"
# The page names the program's version only, not the libraries' and compiler's of this build.
version="$("$program" --version | cut -d' ' -f1-2)"
help2man --no-info --section=1 --include="$extra" --version-string="$version" \
  --name="remove texture swimming from animated triangle-mesh sequences (Mesh Massage)" \
  --output="$output" "$program"
