#!/usr/bin/env bash
# The default detector on one frame of the hard sequence rendered with each seed of a range: the share of the
# ring found where the stripe is at least 3 times the sensor noise, and where what the JPEG compression kept of
# it still is (make-laser-sequence's conditions.csv, columns detector_coverage_3sigma and
# detector_kept_coverage_3sigma), then their means and the seeds under 95 %.
#   bash scripts/faint_ring_seeds.sh [--quality Q] [--frame F] FIRST LAST
# Defaults: quality 60 (make-laser-sequence's), frame 56 (the faint fading ring). Needs make-laser-sequence
# built in build/ (or VSP_BUILD_DIR): cmake --build build --target make-laser-sequence. Parallel jobs: VSP_JOBS
# (default: the number of cores). A seed whose sequence cannot be rendered is reported and left out of the means.
# Example (the figures of doc/results.md): bash scripts/faint_ring_seeds.sh 1 24
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${VSP_BUILD_DIR:-$here/build}"
jobs="${VSP_JOBS:-$(nproc)}"
quality=60
frame=56
while [ $# -gt 2 ]; do
  case "$1" in
  --quality) quality="$2"; shift 2 ;;
  --frame) frame="$2"; shift 2 ;;
  *) break ;;
  esac
done
if [ $# -ne 2 ] || ! [[ "$1" =~ ^[0-9]+$ && "$2" =~ ^[0-9]+$ ]] || [ "$1" -gt "$2" ]; then
  echo "usage: bash scripts/faint_ring_seeds.sh [--quality Q] [--frame F] FIRST LAST (seeds, FIRST <= LAST)" >&2
  exit 2
fi
program="$build/example/laser_conic/make-laser-sequence"
if [ ! -x "$program" ]; then
  echo "$program not found: build it first (cmake --build $build --target make-laser-sequence)" >&2
  exit 1
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

# One seed: renders the sequence, keeps its conditions.csv, drops the images.
render() {
  local seed="$1" dir="$work/seed$1"
  if "$program" --hard --seed "$seed" --quality "$quality" --output "$dir" >"$work/log$seed.txt" 2>&1; then
    cp "$dir/conditions.csv" "$work/conditions$seed.csv"
  fi
  rm -rf "$dir"
}
export -f render
export program work quality
seq "$1" "$2" | xargs -P "$jobs" -I{} bash -c 'render {}'

echo "Hard sequence (make-laser-sequence --hard --quality $quality), frame $frame, default detector:"
echo "seed  coverage_3sigma  kept_coverage_3sigma"
for seed in $(seq "$1" "$2"); do
  file="$work/conditions$seed.csv"
  if [ ! -f "$file" ]; then
    echo "$seed  failed to render (make-laser-sequence: $(tail -1 "$work/log$seed.txt" 2>/dev/null))"
    continue
  fi
  # The columns by name: frame, and the two coverages.
  awk -F, -v seed="$seed" -v frame="$frame" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $col["frame"] == frame { printf "%s  %s  %s\n", seed, $col["detector_coverage_3sigma"], $col["detector_kept_coverage_3sigma"] }
  ' "$file"
done | tee "$work/rows.txt"
awk '
  $2 ~ /^[0-9.]+$/ { n++; c += $2; if ($2 < 0.95) under = under " " $1 " (" sprintf("%.1f", 100 * $2) " %)" }
  $3 ~ /^[0-9.]+$/ { m++; k += $3; if ($3 < 0.95) kunder++ }
  END {
    if (n == 0) { print "no seed measured"; exit 1 }
    printf "mean over %d seeds: %.2f %% of the ring at 3 sigma, %.2f %% of what the compression kept\n", n, 100 * c / n, m ? 100 * k / m : 0
    printf "seeds under 95 %%: %s; of what the compression kept: %d\n", under == "" ? "none" : substr(under, 2), kunder
  }
' "$work/rows.txt"
