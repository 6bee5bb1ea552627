#!/usr/bin/env bash
# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
#
# Prints the library functions longer than 80 lines and the library files longer than 600 lines
# (the structure rules of doc/structure.md); exits 1 when there is any, 0 otherwise.
#
#   bash scripts/check_structure.sh [--max-function N] [--max-file N] [PATH...]
#
# PATH: files or folders to check (default: every modules/*/src and modules/*/include), *.h and *.cpp.
# Needs only bash, find and awk. A function is found by its layout, the project's (clang-format)
# one: its signature starts at column 0 and its body is a block whose braces stand alone at column
# 0 (a signature line may also end with the opening brace); its length runs from the first line of
# its signature (template line included) to its closing brace. Blocks opened after namespace,
# class, struct, enum or union are not functions; the members defined inside a class are indented
# and not measured (they are one-liners or short accessors in this code base).
set -euo pipefail

max_function=80
max_file=600
paths=()
while [ $# -gt 0 ]; do
  case "$1" in
    --max-function) max_function="$2"; shift 2 ;;
    --max-file) max_file="$2"; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) paths+=("$1"); shift ;;
  esac
done
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ ${#paths[@]} -eq 0 ]; then
  cd "$repo"
  for d in modules/*/src modules/*/include; do [ -d "$d" ] && paths+=("$d"); done
fi

mapfile -t files < <(find "${paths[@]}" -type f \( -name '*.h' -o -name '*.cpp' \) | sort)
[ ${#files[@]} -gt 0 ] || { echo "check_structure.sh: no source file under ${paths[*]}" >&2; exit 2; }

status=0
for f in "${files[@]}"; do
  n=$(wc -l <"$f")
  if [ "$n" -gt "$max_file" ]; then
    echo "file     $f: $n lines (> $max_file)"
    status=1
  fi
done

# One line per function over the limit: "function <file>:<first>-<last>: <n> lines (<signature>)".
long=$(awk -v max="$max_function" '
  FNR == 1 { start = 0; inFunction = 0; signature = 0 }
  # A line at column 0 that can begin a declaration: remember it as the candidate signature start.
  /^[A-Za-z_~]/ && !inFunction {
    if (!signature || prevEnded) { signature = FNR; text = $0 }
    else if (text ~ /^template/ && text !~ /\(/) { text = text " " $0 } # name the function after its template line
    prevEnded = ($0 ~ /[;}][ \t]*$/ || $0 ~ /^(public|private|protected):/)
  }
  !/^[A-Za-z_~]/ && !inFunction && /^(#|\/\/|[ \t]*$)/ { signature = 0 }
  function opens(t) {
    return t !~ /^(namespace|class|struct|enum|union|extern)([ \t]|$)/ &&
           t !~ /^template <[^>]*> *(class|struct)[ \t]/ && t !~ /^typedef[ \t]/ && t !~ /=[ \t]*\{?[ \t]*$/ &&
           t !~ /^(static )?(const|constexpr) [^(]*=/
  }
  # Opening brace alone at column 0, or at the end of a signature line at column 0.
  !inFunction && ((/^\{[ \t]*$/ && signature) || (/^[A-Za-z_~].*\)[^;]*\{[ \t]*$/)) {
    if (/^\{/) { first = signature; sig = text } else { first = FNR; sig = $0 }
    if (opens(sig)) { inFunction = 1; start = first; head = sig }
    signature = 0
    next
  }
  inFunction && /^\}/ {
    len = FNR - start + 1
    if (len > max) {
      sub(/[ \t]*\(.*/, "", head)
      printf "function %s:%d-%d: %d lines (%s)\n", FILENAME, start, FNR, len, head
    }
    inFunction = 0; signature = 0
  }
' "${files[@]}")
if [ -n "$long" ]; then
  echo "$long"
  status=1
fi
if [ $status -eq 0 ]; then
  echo "check_structure.sh: ${#files[@]} files, no function over $max_function lines, no file over $max_file lines"
fi
exit $status
