#!/usr/bin/env bash
# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
#
# Checks that every C++ source of the repository (.h, .hpp, .cpp, .cc under modules/ example/ tutorial/
# benchmark/ test/) is formatted as .clang-format says.
#   bash scripts/check_format.sh          check; exit 1 and list the files (and a diff) when one differs
#   bash scripts/check_format.sh --fix    reformat those files in place
# Environment: CLANG_FORMAT (default clang-format-14, else clang-format), VSP_FORMAT_DIFF_LINES (lines
# of diff shown on failure, default 60).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
fix=0
case "${1:-}" in
  --fix) fix=1 ;;
  "") ;;
  -h|--help) sed -n '4,10p' "$0"; exit 0 ;;
  *) echo "check_format.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
esac
CLANG_FORMAT="${CLANG_FORMAT:-$(command -v clang-format-14 || command -v clang-format || true)}"
if [ -z "$CLANG_FORMAT" ]; then
  echo "check_format.sh: clang-format not found (Debian package clang-format, see scripts/install_deps.sh)" >&2
  exit 1
fi

# The tracked sources when this is a git checkout, and the new ones not yet added (a file created before its
# first commit was left out; build folders, ignored, are never looked at); else every source.
dirs=(modules example tutorial benchmark test)
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files --cached --others --exclude-standard -- "${dirs[@]}" | grep -E '\.(h|hpp|cpp|cc)$')
else
  mapfile -t files < <(find "${dirs[@]}" -type f \( -name '*.h' -o -name '*.hpp' -o -name '*.cpp' -o -name '*.cc' \) | sort)
fi
[ ${#files[@]} -gt 0 ] || { echo "check_format.sh: no source found" >&2; exit 1; }

if [ "$fix" -eq 1 ]; then
  printf '%s\0' "${files[@]}" | xargs -0 "$CLANG_FORMAT" -i --style=file
  echo "check_format.sh: ${#files[@]} files formatted with $($CLANG_FORMAT --version | sed 's/.*version //')"
  exit 0
fi

bad=()
lines=0
diffs="$(mktemp)"
trap 'rm -f "$diffs"' EXIT
# One clang-format process per 50 files, as many at a time as cores, reports the files that differ
# (--dry-run -Werror: "FILE:LINE:COL: error: code should be clang-formatted"); only those are diffed.
# (A process and a diff for each of the 200 files took 20 s.)
mapfile -t differing < <(printf '%s\0' "${files[@]}" |
  xargs -0 -n 50 -P "$(nproc)" "$CLANG_FORMAT" --style=file --dry-run -Werror 2>&1 |
  sed -nE 's/^(.*):[0-9]+:[0-9]+: error: .*clang-format.*/\1/p' | sort -u)
for f in "${differing[@]}"; do
  if ! "$CLANG_FORMAT" --style=file "$f" | diff -u --label "$f" --label "$f (clang-format)" "$f" - >>"$diffs"; then
    bad+=("$f")
  fi
done
if [ ${#bad[@]} -eq 0 ]; then
  echo "check_format.sh: ${#files[@]} files, all formatted as .clang-format says"
  exit 0
fi
lines=$(grep -c '^-[^-]' "$diffs" || true)
echo "check_format.sh: FAILED: ${#bad[@]} of ${#files[@]} files differ from .clang-format ($lines lines to change):"
printf '  %s\n' "${bad[@]}"
shown="${VSP_FORMAT_DIFF_LINES:-60}"
echo "-- first $shown lines of the diff (- as written, + as clang-format wants it):"
head -n "$shown" "$diffs"
echo "-- to fix: bash scripts/check_format.sh --fix   (then review and commit the change)"
echo "-- to skip this stage in a local run of scripts/test.sh: VSP_SKIP_FORMAT=1"
exit 1
