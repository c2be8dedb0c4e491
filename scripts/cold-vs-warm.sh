#!/usr/bin/env bash
# Issue 30's measure: the cold first default run against the warm one.
# Runs N alternated rounds of `mfv --quiet run --out DIR`: cold (POCL_CACHE_DIR
# and MFV_CACHE_DIR new empty folders), then warm (the same folders again),
# in each mode asked: MFV_COMPILE_AHEAD=0, =1, or unset, mfv's default (docs/ci.md,
# "Compiling ahead in a second process"), and prints each run and the medians of wall
# and CPU seconds (user + sys of mfv and its children, GNU time) and the
# cold / warm ratios. The load average is printed before each run: on a
# shared machine, compare only rounds taken at similar load.
# Usage: scripts/cold-vs-warm.sh [build/mfv] [rounds=3] [modes="off on"]
#   modes: "off" (MFV_COMPILE_AHEAD=0: no child), "on" (=1), "default" (unset:
#   a child where a core is free when the run starts), in any combination.
set -euo pipefail

mfv=${1:-build/mfv}
rounds=${2:-3}
modes=${3:-off on}
work=$(mktemp -d "${TMPDIR:-/tmp}/mfv-cold-vs-warm.XXXXXX")
trap 'rm -rf "$work"' EXIT
for mode in $modes; do
  [[ "$mode" =~ ^(off|on|default)$ ]] || { echo "unknown mode '$mode': expected off, on or default" >&2; exit 2; }
done
[[ -x /usr/bin/time ]] || { echo "needs GNU time (/usr/bin/time)" >&2; exit 2; }

# one run: prints "wall cpu" (seconds); $1 = caches folder, $2 = mode
one() {
  local t="$work/time" env=(POCL_CACHE_DIR="$1/pocl" MFV_CACHE_DIR="$1/mfv")
  case "$2" in
    off) env+=(MFV_COMPILE_AHEAD=0) ;;
    on) env+=(MFV_COMPILE_AHEAD=1) ;;
    default) ;;
  esac
  rm -rf "$work/out"
  env "${env[@]}" /usr/bin/time -o "$t" -f "%e %U %S" "$mfv" --quiet run --out "$work/out" >/dev/null 2>&1 ||
    { echo "mfv run failed (exit $?)" >&2; exit 1; }
  awk '{ printf "%.1f %.1f\n", $1, $2 + $3 }' "$t"
}

median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

for mode in $modes; do
  : >"$work/cold" && : >"$work/warm"
  for ((r = 1; r <= rounds; ++r)); do
    caches="$work/caches.$mode.$r"
    mkdir -p "$caches/pocl" "$caches/mfv"
    for kind in cold warm; do
      load=$(cut -d' ' -f1 /proc/loadavg)
      read -r wall cpu < <(one "$caches" "$mode")
      echo "$wall $cpu" >>"$work/$kind"
      printf 'ahead=%-3s round %d %-4s %6.1f s wall %6.1f s CPU  (load %s)\n' "$mode" "$r" "$kind" "$wall" "$cpu" "$load"
    done
    rm -rf "$caches"
  done
  cw=$(cut -d' ' -f1 "$work/cold" | median) cc=$(cut -d' ' -f2 "$work/cold" | median)
  ww=$(cut -d' ' -f1 "$work/warm" | median) wc=$(cut -d' ' -f2 "$work/warm" | median)
  awk -v m="$mode" -v cw="$cw" -v cc="$cc" -v ww="$ww" -v wc="$wc" 'BEGIN {
    printf "ahead=%s medians: cold %.1f s wall / %.1f s CPU, warm %.1f s / %.1f s: cold/warm %.2fx wall, %.2fx CPU\n",
           m, cw, cc, ww, wc, cw / ww, cc / wc }'
done
