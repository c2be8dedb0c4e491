#!/bin/sh
# Draws docs/transmission-loss.svg from the measured loss table of
# docs/transmission.md ("Measured loss"): the single-scattering loss
# 1 - E_R,avg - E_T,avg of walter_ggx_correlated over eta, one curve per alpha,
# entering (solid) and leaving (dashed). Needs gnuplot (gnuplot-nox,
# scripts/install-deps.sh).
set -eu
cd "$(dirname "$0")/.."
data=$(mktemp)
trap 'rm -f "$data"' EXIT
# rows "| alpha | eta | side | E_R | E_T | loss | loss at mu=1 |" -> "alpha eta entering? loss"
grep -E '^\| [0-9.]+ \| [0-9.]+ \| (entering|leaving)' docs/transmission.md |
  awk -F'|' '{gsub(/ /, "", $2); gsub(/ /, "", $3); s = ($4 ~ /entering/) ? 1 : 0; gsub(/ /, "", $7); print $2, $3, s, $7}' |
  sort -k3,3r -k1,1g -k2,2g |
  awk '{k = $1 " " $3; if (NR > 1 && k != last) printf "\n\n"; last = k; print}' >"$data"
# blocks (gnuplot's index): entering at each alpha ascending (0-3), then leaving (4-7)
[ -s "$data" ] || { echo "plot-transmission-loss: no table rows in docs/transmission.md" >&2; exit 2; }
gnuplot <<GP
set terminal svg size 820,440 font "sans,12"
set output "docs/transmission-loss.svg"
set title "walter\\\\_ggx\\\\_correlated: single-scattering loss 1 - E_R,avg - E_T,avg"
set xlabel "eta (index below / above)"
set ylabel "loss"
set logscale x
set xtics (1.1, 1.33, 1.5, 2, 3)
set key outside right
set xrange [1.05:3.3]
set grid
alphas = "0.05 0.2 0.5 1"
plot for [k=1:4] "$data" index (k - 1) using 2:4 with linespoints lc k lw 2 title "alpha ".word(alphas, k)." entering", \
     for [k=1:4] "$data" index (k + 3) using 2:4 with linespoints lc k dt 2 lw 2 title "alpha ".word(alphas, k)." leaving"
GP
echo "wrote docs/transmission-loss.svg"
