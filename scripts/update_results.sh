#!/usr/bin/env bash
# ViSP sensor-aided pose estimation. Copyright (C) the VispSensorPose authors. GPL-2.0-or-later, see LICENSE.
#
# Regenerates the results tables of doc/results.md (and the summary table of README.md) from the output
# of the programs that measure them, so that the documents cannot disagree with the programs or with
# each other. Each table sits between <!-- BEGIN name --> and <!-- END name --> and is replaced whole.
#
#   bash scripts/update_results.sh [--quick | --full] [--check] [--build DIR]
#
#   --quick      (default) the seeded programs that take seconds: the gravity paper's Table I, the
#                robustness checks, the simulated laser sequence, the demo's two sequences
#   --full       also the studies that take minutes: stress (10^6-10^7 configurations, about 1 min) and
#                the laser synthetic study (about 7 min on one core)
#   --speed      also the peer benchmark (about 3 min): its times depend on the machine and its load, so
#                run it on an otherwise idle machine
#   --check      write nothing: exit 1, with the difference, when a regenerated table differs from the
#                document (ctest runs `--quick --check` as test results_doc_current)
#   --build DIR  the build folder holding the programs (default build/); build them first, e.g.
#                cmake --build build --target table1-gravity-p3p gravity-robustness laser-sequence-eval vsp-demo
#                (--full also: stress-gravity stress-laser laser-synthetic-eval bench-peers)
# Tables that are not regenerated (those of --full and --speed otherwise) are left as they are. Tables
# that hold times (the demo's time per frame) keep only the columns that do not depend on the machine,
# except the benchmark's.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode=quick
speed=0
check=0
build="$root/build"
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) mode=quick; shift ;;
    --full) mode=full; shift ;;
    --speed) speed=1; shift ;;
    --check) check=1; shift ;;
    --build) build="$(cd "$2" && pwd)"; shift 2 ;;
    -h|--help) sed -n '4,24p' "$0"; exit 0 ;;
    *) echo "update_results.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done
results="$root/doc/results.md"
readme="$root/README.md"
work="$(mktemp -d /tmp/vsp-results.XXXXXX)"
trap 'rm -rf "$work"' EXIT
blocks="$work/blocks"
mkdir -p "$blocks"
log() { echo "[update_results] $*" >&2; }

program() { # program NAME: path of a built program (its folder in the build tree), or a clear error
  local dir
  case "$1" in
    table1-gravity-p3p|gravity-robustness) dir=example/pose_gravity ;;
    laser-sequence-eval|laser-synthetic-eval) dir=example/laser_conic ;;
    vsp-demo) dir=example/demo ;;
    stress-gravity|stress-laser) dir=benchmark/stress ;;
    bench-peers) dir=benchmark/peers ;;
  esac
  if [ ! -x "$build/$dir/$1" ]; then
    echo "update_results.sh: program $build/$dir/$1 not found (cmake --build $build --target $1)" >&2
    exit 1
  fi
  echo "$build/$dir/$1"
}

# The first markdown table (a run of lines starting with '|') of standard input.
first_table() { awk '/^\|/ {print; found = 1; next} found {exit}'; }

# --- the gravity paper's Table I ---------------------------------------------------------------------
gen_table1() {
  log "table1-gravity-p3p --trials 8000 --seed 1"
  "$(program table1-gravity-p3p)" --trials 8000 --seed 1 >"$work/table1.txt"
  {
    first_table <"$work/table1.txt"
    echo
    # The failures line without the run time.
    grep '^Trials:' "$work/table1.txt" | sed -E 's/ Time [0-9.]+ s\.?$//'
  } >"$blocks/table1.md"
}

# --- robustness of the gravity checks ----------------------------------------------------------------
gen_robustness() {
  log "gravity-robustness --trials 1000 --seed 1"
  "$(program gravity-robustness)" --trials 1000 --seed 1 >"$work/robustness.txt"
  {
    echo "| Experiment | Measured quantity | Value | Target |"
    echo "|---|---|---:|---|"
    # "experiment  description  value  target", fields separated by two spaces or more.
    awk -F'  +' 'NF >= 3 && $1 ~ /^[a-z0-9_]+$/ {
      target = (NF >= 4 && $4 != "") ? $4 : "-"; sub(/ +$/, "", target)
      printf "| %s | %s | %s | %s |\n", $1, $2, $3, target
    }' "$work/robustness.txt"
    echo
    tail -n 1 "$work/robustness.txt"
  } >"$blocks/robustness.md"
}

# --- the simulated laser sequence (the laser paper's Table 2) ------------------------------------------
gen_sequence() {
  log "laser-sequence-eval"
  "$(program laser-sequence-eval)" --output "$work/sequence" >"$work/sequence.txt"
  {
    first_table <"$work/sequence.txt"
    echo
    grep '^Detection error' "$work/sequence.txt"
    grep -oE '^[0-9]+ frames of .*, [0-9]+ to [0-9]+ trace points detected per frame' "$work/sequence.txt" |
      sed -E 's/^([0-9]+) frames of [^,]*, /\1 frames, /'
  } >"$blocks/sequence.md"
}

# --- laser-sequence-eval's frame-by-frame comparisons on the shipped sequences ------------------------------
# comparison_rows NAME "OPTIONS" TITLE_START: runs laser-sequence-eval with OPTIONS on each "label;arguments"
# line of stdin (output in $work/NAME_k.txt) and prints the rows of its comparison table (the one after the
# line starting with TITLE_START), each prefixed by the run's label.
comparison_rows() {
  local name=$1 options=$2 title=$3 k=0
  while IFS=';' read -r label args; do
    k=$((k + 1))
    # shellcheck disable=SC2086 # the arguments are words
    "$(program laser-sequence-eval)" $args $options --output "$work/$name" >"$work/${name}_$k.txt" 2>/dev/null || true
    awk -v label="$label" -v title="$title" 'index($0, title) == 1 {on = 1; next}
      on && /^\| [A-Z]/ && !/: mean ± std/ {print "| " label " " $0}' "$work/${name}_$k.txt"
  done
}

gen_second_pass() {
  log "laser-sequence-eval --check-against-first-pass (simulated and hard sequences)"
  {
    echo "| Sequence, laser | GP-3 | default detector: mean ± std, median | first pass alone | difference: mean (standard error) | frames better / worse |"
    echo "|---|---|---|---|---|---|"
    comparison_rows second_pass --check-against-first-pass "GP-3 with the default detector" <<EOF_RUNS
laser_sequence, calibrated;
laser_hard, calibrated;--data $root/data/laser_hard
laser_hard, true;--data $root/data/laser_hard --laser $root/data/laser_hard/laser_true.txt
EOF_RUNS
  } >"$blocks/second_pass.md"
}

gen_tracking() {
  log "laser-sequence-eval --track 20 --check-against-whole-frame (simulated and hard sequences)"
  {
    echo "| Sequence | GP-3 | tracking: mean ± std, median | whole frame | difference: mean (standard error) | frames better / worse |"
    echo "|---|---|---|---|---|---|"
    comparison_rows tracking "--track 20 --check-against-whole-frame" "GP-3 with tracking" <<EOF_RUNS
laser_sequence;
laser_hard;--data $root/data/laser_hard
EOF_RUNS
    echo
    local k=0 label
    for label in laser_sequence laser_hard; do
      k=$((k + 1))
      grep -h -E "^(Tracking:|Frames with a plane)" "$work/tracking_$k.txt" | sed "s/^/- $label: /"
    done
  } >"$blocks/tracking.md"
}

# A fixed-width summary of the demo (header line starting with "method") as a markdown table, without
# its last column (the time per frame, which depends on the machine).
demo_table() { # demo_table FIRST_WORD_OF_SECTION_TITLE
  awk -v section="$1" '
    index($0, "Summary of the " section) == 1 {inside = 1; next}
    inside && /^method/ {
      # Column starts: the first letter of each header field (fields are separated by 2+ spaces).
      n = 0; line = $0
      for (i = 1; i <= length(line); ++i)
        if (substr(line, i, 1) != " " && (i == 1 || substr(line, i - 2, 2) == "  ")) start[++n] = i
      start[n + 1] = length(line) + 1000
      header = 1
    }
    inside && n > 0 {
      if (!header && $0 !~ / [0-9]+\/[0-9]+ /) exit
      row = "|"
      for (c = 1; c < n; ++c) {
        cell = substr($0, start[c], start[c + 1] - start[c]); gsub(/^ +| +$/, "", cell); gsub(/\+\/-/, "±", cell)
        row = row " " cell " |"
      }
      print row
      if (header) { sep = "|"; for (c = 1; c < n; ++c) sep = sep "---|"; print sep; header = 0 }
    }' "$work/demo.txt"
}

gen_demo() {
  log "vsp-demo"
  "$(program vsp-demo)" --output "$work/demo" >"$work/demo.txt"
  demo_table "laser" >"$blocks/demo_laser.md"
  {
    echo "| Condition | Frames | Planes | Points detected | Kept as inliers | Altitude error, mean / worst (mm) |"
    echo "|---|---:|---:|---:|---:|---:|"
    sed -nE 's/^  ([a-z_]+) +([0-9]+) frames, ([0-9]+) planes, +([0-9]+) points, +([0-9.]+) % inliers, +([0-9.]+) \/ +([0-9.]+) mm$/| \1 | \2 | \3 | \4 | \5 % | \6 \/ \7 |/p' \
      "$work/demo.txt"
    echo
    grep '^Frames without laser' "$work/demo.txt" || true
  } >"$blocks/demo_conditions.md"
  demo_table "gravity" >"$blocks/demo_gravity.md"
}

# --- stress: random exact configurations ---------------------------------------------------------------
stress_rows() { # "SOLVER  n=..  correct=.. ..." lines as table rows
  awk '{
    row = "| " $1
    for (i = 2; i <= NF; ++i) { split($i, kv, "="); v = kv[2]; if (kv[1] == "wrong") v = "**" v "**"; row = row " | " v }
    print row " |"
  }'
}

gen_stress() {
  local g l
  g="$(program stress-gravity)"
  l="$(program stress-laser)"
  log "stress-gravity (p3p 1e7, p2p 1e6, ls 1e6) and stress-laser (1e6), seed 1"
  {
    echo "| Solver | Configurations | Correct | Degenerate | Ambiguous | No answer | Wrong | Skipped | Worst correct error |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|"
    {
      "$g" --solver p3p --n 1e7 --seed 1
      "$g" --solver p2p --n 1e6 --seed 1
      "$g" --solver ls --n 1e6 --seed 1
      "$l" --method all --n 1e6 --seed 1
    } | grep -E '^[A-Z_0-9-]+ +n=' | stress_rows
  } >"$blocks/stress.md"
}

# --- the laser synthetic study (the laser paper's Sec. 7.1) --------------------------------------------
gen_synthetic() {
  log "laser-synthetic-eval --seed 1 (minutes)"
  "$(program laser-synthetic-eval)" --seed 1 --output "$work/synthetic" >"$work/synthetic.txt"
  first_table <"$work/synthetic.txt" >"$blocks/synthetic_outliers.md"
  # Mean errors altitude mm / roll deg / pitch deg, median normal error deg, at the levels of the paper's
  # figures, from the CSV files of the studies.
  {
    echo "| Study (paper figure) | Level | PP-5 | PP-3 | GP-3 |"
    echo "|---|---|---|---|---|"
    for spec in "noise:image noise (Fig. 7):px:0.5 1 3" "intrinsics:intrinsics fx, fy, u0, v0 (Fig. 9):px:0 2.5 5 20" \
        "extent:baseline extent (Fig. 10):mm:5 10" "baseline:laser position, 3 axes:mm:5 10" \
        "roughness:ground roughness (Fig. 11):mm:5 20"; do
      IFS=: read -r file title unit levels <<<"$spec"
      awk -F, -v title="$title" -v unit="$unit" -v levels="$levels" '
        BEGIN { n = split(levels, want, " "); for (i = 1; i <= n; ++i) keep[want[i] + 0] = i }
        NR > 1 && (($1 + 0) in keep) {
          cell = sprintf("%.3g / %.2g / %.2g, %.2g°", $5, $6, $7, $9)
          value[$1 + 0, $2] = cell
        }
        END {
          for (i = 1; i <= n; ++i) {
            l = want[i] + 0
            printf "| %s | %s %s | %s | %s | %s |\n", (i == 1 ? title : ""), want[i], unit, value[l, "PP5"], value[l, "PP3"], value[l, "GP3"]
          }
        }' "$work/synthetic/$file.csv"
    done
  } >"$blocks/synthetic_errors.md"
}

# --- speed against the peers ----------------------------------------------------------------------------
gen_speed() {
  log "bench-peers (minutes; times depend on the machine)"
  "$(program bench-peers)" --seed 42 --out "$work/speed.md" >/dev/null
  {
    echo "Machine: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores."
    echo
    # Headings of the program's output one level below the page's.
    sed -E 's/^#### /##### /; s/^### /#### /' "$work/speed.md"
  } >"$blocks/speed.md"
}

# --- the README's summary: values taken from the regenerated tables of doc/results.md -----------------
# row FILE_OR_BLOCK PATTERN COLUMN: a cell of the first row of a markdown table matching PATTERN.
cell() { grep -m1 -E "$2" "$1" | awk -F'|' -v c="$3" '{gsub(/^ +| +$/, "", $(c + 1)); print $(c + 1)}'; }

gen_summary() {
  local doc="$1" t="$work/doc-blocks"
  mkdir -p "$t"
  # The blocks as they will be in doc/results.md after this run.
  for name in table1 robustness sequence demo_laser demo_gravity stress synthetic_outliers speed; do
    if [ -f "$blocks/$name.md" ]; then cp "$blocks/$name.md" "$t/$name.md"; else
      awk -v n="$name" '$0 == "<!-- BEGIN " n " -->" {on = 1; next} $0 == "<!-- END " n " -->" {on = 0} on' "$doc" >"$t/$name.md"
    fi
  done
  {
    echo "| Result | Measured | Paper / target | Details |"
    echo "|---|---|---|---|"
    echo "| Gravity P3P, the paper's Table I: trials with ε < 0.02 (8000 trials, 2 px, σ_g = 0.01) | $(cell "$t/table1.md" '^\| P3P_IMU \|' 2) (refined: $(cell "$t/table1.md" '^\| P3P_IMU_REFINED \|' 2)) | 93 % | [Table I](doc/results.md#gravity-aided-pose-the-papers-table-i) |"
    echo "| Gravity RANSAC on pure outliers, success claimed (n = 200) | $(cell "$t/robustness.md" 'n = 200, threshold 0.0040' 3) % | ≤ 1 % | [robustness](doc/results.md#gravity-aided-pose-robustness-of-the-checks) |"
    echo "| Laser GP-3 on the hard sequence (rendered, distorted 80° lens): altitude error mean ± std, median (mm) | $(cell "$t/demo_laser.md" '^\| GP3 \|' 3) | — | [demo](doc/results.md#circular-laser-hard-simulated-sequence-the-demo) |"
    echo "| Laser PP-5 / PP-3 / GP-3 on the paper's Table 2 sequence (simulated): altitude error (mm) | $(cell "$t/sequence.md" '^\| Altitude error' 2) / $(cell "$t/sequence.md" '^\| Altitude error' 3) / $(cell "$t/sequence.md" '^\| Altitude error' 4) | real data: 11.3 / 7.9 / 7.5 | [Table 2](doc/results.md#circular-laser-simulated-sequence-the-papers-table-2) |"
    local breakdown="not generated yet (\`--full\`)"
    if grep -q '^| PP5 |' "$t/synthetic_outliers.md"; then
      breakdown="$(cell "$t/synthetic_outliers.md" '^\| PP5 \|' 2) / $(cell "$t/synthetic_outliers.md" '^\| PP3 \|' 2) / $(cell "$t/synthetic_outliers.md" '^\| GP3 \|' 2)"
    fi
    echo "| Laser outlier break-down PP-5 / PP-3 / GP-3 | $breakdown | 75 / 86 / 85 % | [Table 1](doc/results.md#circular-laser-synthetic-study-the-papers-sec-71) |"
    echo "| Stress: solvers with a wrong answer on random exact configurations (10⁶-10⁷ each) | $(grep -cE '\| \*\*[1-9]' "$t/stress.md" || true) of $(tail -n +3 "$t/stress.md" | grep -c '^|' || true) | 0 | [stress](doc/results.md#stress-random-exact-configurations) |"
    echo "| Gravity P3P vs OpenCV AP3P / vpPose LAGRANGE (4 points): speed-up | $(cell "$t/speed.md" 'faster than cv::solveP3P' 2) / $(cell "$t/speed.md" 'faster than vpPose LAGRANGE' 2) | ≥ 100× / ≥ 200× | [speed](doc/results.md#speed-against-the-peers) |"
    echo "| Whole 1600×1200 frame (detection + GP-3, worst floor) / one cv::cvtColor | $(cell "$t/speed.md" 'whole frame' 2 | sed 's/ (.*//') | ≤ 0.5× | [speed](doc/results.md#speed-against-the-peers) |"
    echo "| Tracking a 1600×1200 frame (previous conic, 20 px, + GP-3, worst floor) / one cv::cvtColor | $(cell "$t/speed.md" '^\| tracking ' 2 | sed 's/ (.*//') | ≤ 0.1× | [speed](doc/results.md#speed-against-the-peers) |"
  } >"$blocks/summary.md"
}

# Replaces each block of FILE that has a regenerated version; prints the result to standard output.
replace_blocks() {
  awk -v dir="$blocks" '
    match($0, /^<!-- BEGIN [a-z0-9_]+ -->$/) {
      name = substr($0, 12, length($0) - 15); file = dir "/" name ".md"
      print
      if ((getline test < file) > 0) {
        print test; while ((getline line < file) > 0) print line; close(file); skipping = 1
      }
      next
    }
    /^<!-- END [a-z0-9_]+ -->$/ { skipping = 0 }
    !skipping' "$1"
}

gen_table1
gen_robustness
gen_sequence
gen_second_pass
gen_tracking
gen_demo
if [ "$mode" = full ]; then
  gen_stress
  gen_synthetic
fi
if [ "$speed" -eq 1 ]; then gen_speed; fi
gen_summary "$results"

status=0
for doc in "$results" "$readme"; do
  replace_blocks "$doc" >"$work/new.md"
  if cmp -s "$doc" "$work/new.md"; then
    log "$(basename "$doc"): up to date"
  elif [ "$check" -eq 1 ]; then
    echo "update_results.sh: ${doc#"$root"/} disagrees with the programs' output:" >&2
    diff -u --label "${doc#"$root"/} (as written)" --label "regenerated" "$doc" "$work/new.md" >&2 || true
    echo "update_results.sh: run 'bash scripts/update_results.sh --quick --build <build folder>' and commit the result" >&2
    status=1
  else
    cp "$work/new.md" "$doc"
    log "$(basename "$doc"): tables regenerated ($mode mode)"
  fi
done
exit $status
