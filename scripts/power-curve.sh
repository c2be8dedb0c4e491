#!/usr/bin/env bash
# The power curve of docs/statistics.md: the smallest uniform energy gain the
# default gate detects, against the sample scale. A gain g multiplies the
# D x G x F BRDF's specular term (kernels/brdf.cl) for `mfv run`, and a
# Lambert's kd/pi (examples/brdf/lambert.cl) for `mfv check`. Each cell is
# the furnace verdict and the pooled test's z.
#   scripts/power-curve.sh [build/mfv] [seed]
set -euo pipefail
mfv=${1:-build/mfv}
seed=${2:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
verdict() {  # results.json -> "FAIL z=12.3"
  python3 -c 'import json,sys; g=json.load(open(sys.argv[1]))["groups"][0]; print(g["verdict"], "z=%.1f" % g["pooled"]["z"])' "$1"
}
printf "%-7s %-6s %-22s %-22s\n" gain scale "mfv run (ggx/...corr.)" "mfv check (lambert)"
for gain in 1.0025 1.005 1.01 1.02; do
  rm -rf "$tmp/k" && cp -r "$root/kernels" "$tmp/k"
  sed -i "s|return kd \* MFV_INV_PI + spec / (R(4.0) \* NoL) / NoV;|return kd * MFV_INV_PI + R($gain) * spec / (R(4.0) * NoL) / NoV;|" "$tmp/k/brdf.cl"
  grep -q "R($gain) \* spec" "$tmp/k/brdf.cl"
  sed "s|params\[0\] \* M_1_PI_F|${gain}f * params[0] * M_1_PI_F|" "$root/examples/brdf/lambert.cl" > "$tmp/lambert.cl"
  for scale in 1 2 4; do
    "$mfv" --kernel-dir "$tmp/k" run --check furnace --model ggx/smith_ggx_correlated --reference-samples 0 \
      --scale "$scale" --seed "$seed" --out "$tmp/r" > /dev/null || true
    "$mfv" check --brdf "$tmp/lambert.cl" --check furnace --scale "$scale" --seed "$seed" --out "$tmp/c" > /dev/null || true
    printf "%-7s %-6s %-22s %-22s\n" "$gain" "$scale" "$(verdict "$tmp/r/results.json")" "$(verdict "$tmp/c/results.json")"
  done
done
