#!/usr/bin/env bash
# Time to a target standard error on the Kulla-Conty 32x32 table (issue 33,
# docs/performance.md "mfv energy: a 32x32 table to 1e-6 and 1e-7"), measured on
# a subset of its cells and extrapolated per cell, or on the whole table.
#
#   scripts/bench-energy-table.sh TARGET [CELLS] [MFV]
#
# TARGET: --target (e.g. 1e-6). CELLS: "subset" (default): 36 cells (y, x) of
# mu = y/31, alpha = (x/31)^2, x = (7y + 3) mod 32 for y = 0..31 (each row and
# each column once) plus the four corners, queried with --at; "strideK": every
# K-th cell of that subset (stride9: y = 0, 9, 18, 27); "full": the whole table
# (--layout kulla-conty:32).
# Prints the CPU, the load average before and after, wall and CPU seconds, QMC
# points, and for a subset the CPU seconds per cell and that times 1024.
# Every run is --fp64 with ggx/smith_ggx_correlated (the layout's default).
set -euo pipefail
target=${1:?usage: bench-energy-table.sh TARGET [subset|strideK|full] [MFV]}
cells=${2:-subset}
mfv=${3:-build/mfv}
args=()
n=1024
if [[ $cells == full ]]; then
  args=(--layout kulla-conty:32)
else
  stride=1
  [[ $cells == stride* ]] && stride=${cells#stride}
  pts=$(python3 - "$stride" <<'PY'
import sys
cells = [(y, (7 * y + 3) % 32) for y in range(32)]
cells += [c for c in [(0, 0), (0, 31), (31, 0), (31, 31)] if c not in cells]
print(" ".join(f"--at {y / 31!r},{(x / 31) ** 2!r}" for y, x in cells[:: int(sys.argv[1])]))
PY
)
  read -r -a args <<<"$pts"
  n=$((${#args[@]} / 2))
fi
echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), $(nproc) cores"
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)"
start=$(date +%s.%N)
out=$( { /usr/bin/time -f 'cpu_user_s %U cpu_sys_s %S' "$mfv" energy --models ggx/smith_ggx_correlated --fp64 \
  --target "$target" --max-points 16777216 "${args[@]}"; } 2>&1 )
end=$(date +%s.%N)
echo "$out" | grep -E '^accuracy|QMC points|cpu_user_s'
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
cpu=$(echo "$out" | awk '/cpu_user_s/ {print $2 + $4}')
python3 - "$start" "$end" "$cpu" "$n" <<'PY'
import sys
start, end, cpu, n = map(float, sys.argv[1:])
print(f"cells {n:.0f}: wall {end - start:.1f} s, CPU {cpu:.1f} s, CPU per cell {cpu / n:.2f} s")
if n != 1024:
    print(f"extrapolated to 1024 cells: {cpu / n * 1024 / 60:.1f} min CPU ({cpu / n * 1024 / 120:.1f} min wall on 2 idle cores)")
PY
