#!/usr/bin/env bash
# clang-tidy (.clang-tidy at the top of the tree) over the project's own sources, using the
# compile_commands.json of a build configured with -DCMAKE_EXPORT_COMPILE_COMMANDS=ON.
#   scripts/run_clang_tidy.sh [path-regex]     (default: every .cpp of modules/ example/ tutorial/ benchmark/ test/)
# Environment: BUILD_DIR (default build-bench; configured here if needed), JOBS (default 2).
# Writes the full log to $BUILD_DIR/clang-tidy.log and prints the number of findings per file and check.
# Exit status: 0 when there is no finding, 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$(pwd)"
BUILD_DIR="${BUILD_DIR:-build-bench}"
JOBS="${JOBS:-2}"
FILTER="${1:-$ROOT/(modules|example|tutorial|benchmark|test)/.*\.cpp$}"
TIDY="$(command -v clang-tidy-14 || command -v clang-tidy)"
RUN_TIDY="$(command -v run-clang-tidy-14 || command -v run-clang-tidy)"

if [ ! -f "$BUILD_DIR/compile_commands.json" ]; then
  cmake -S . -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
fi
# Generated sources (moc-like, configure_file) are not ours; run-clang-tidy takes a regex of files.
"$RUN_TIDY" -clang-tidy-binary "$TIDY" -p "$BUILD_DIR" -j "$JOBS" -quiet "$FILTER" \
  >"$BUILD_DIR/clang-tidy.log" 2>&1 || true

# One line per finding: "path:line:col: warning: message [check]", deduplicated (headers are seen many times).
# clang-tidy colours its output even into a file: strip the escape sequences before matching.
sed -E $'s/\x1b\\[[0-9;]*m//g' "$BUILD_DIR/clang-tidy.log" | grep -E "^/.*: (warning|error): .*\[[a-z0-9.,-]+\]$" | sort -u \
  >"$BUILD_DIR/clang-tidy-findings.txt" || true
count=$(wc -l <"$BUILD_DIR/clang-tidy-findings.txt")
echo "clang-tidy: $count findings (full log: $BUILD_DIR/clang-tidy.log)"
if [ "$count" -gt 0 ]; then
  echo "-- per file:"
  sed -E "s|^$ROOT/||; s|:[0-9]+:[0-9]+: .*||" "$BUILD_DIR/clang-tidy-findings.txt" | sort | uniq -c | sort -rn
  echo "-- per check:"
  sed -E 's|.*\[([a-z0-9.,-]+)\]$|\1|' "$BUILD_DIR/clang-tidy-findings.txt" | sort | uniq -c | sort -rn
  exit 1
fi
