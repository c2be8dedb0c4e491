#!/usr/bin/env bash
# mfv against Mitsuba 3 on the same integral, back to back in one run:
# the directional albedo of GGX + height-correlated Smith G2 + F = 1 at
# alpha = 0.5, mu = 0.5 (quadrature 0.6982507). Prints both JSON results and
# a table of medians: samples/s, variance per sample, seconds to SE 1e-4, and
# the ratio. Not part of CI (the peers need Python packages from PyPI).
#
# Setup (Debian 12, once):
#   apt-get install -y libllvm19                 # Dr.Jit 1.5 fails on Debian's LLVM 15
#   python3 -m venv /work/peers-venv && /work/peers-venv/bin/pip install mitsuba numpy numba
# Usage:
#   scripts/bench-peers.sh [build dir] [peers dir] [venv]   # defaults: build ../shared/peers /work/peers-venv
#   ROUNDS=3 scripts/bench-peers.sh                          # alternate mfv and Mitsuba 3 times
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
peers=${2:-$here/../shared/peers}
venv=${3:-/work/peers-venv}
rounds=${ROUNDS:-3}
case_=ggx/smith_ggx_correlated/none:0.5:0.5
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-$(dpkg -L libllvm19 2>/dev/null | grep -m1 'libLLVM.so.19' || true)}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$rounds"); do
  "$build/mfv" bench --case "$case_" --repeats 9 --seed "$r" --out "$out/mfv$r" >/dev/null
  cat "$out/mfv$r/bench.json" >"$out/mfv$r.json"
  "$venv/bin/python" "$peers/mitsuba_albedo.py" --log2n 26 --repeats 9 --cases 0.5:0.5 --est corr-vis \
    --seed "$r" >"$out/mi$r.json"
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$out" "$rounds" <<'PY'
import json, statistics as st, sys
out, rounds = sys.argv[1], int(sys.argv[2])
m = [json.load(open(f"{out}/mfv{r}.json")) for r in range(1, rounds + 1)]
p = [json.loads(open(f"{out}/mi{r}.json").read().splitlines()[-1]) for r in range(1, rounds + 1)]
for x in m: print("mfv", json.dumps({k: x[k] for k in ("estimate", "rms_stderr", "samples", "samples_per_s", "variance_per_sample", "seconds_to_se_1e-4", "median_cpu_seconds", "load_average")}))
for x in p: print("mitsuba", json.dumps({k: x[k] for k in ("mean", "se", "samples_per_s_median", "var_per_sample", "load")}))
mi_rate = st.median(x["samples_per_s_median"] for x in p)
mi_var = st.median(x["var_per_sample"] for x in p)
mi_t = mi_var / 1e-8 / mi_rate
mf_rate = st.median(x["samples_per_s"] for x in m)
mf_var = st.median(x["variance_per_sample"] for x in m)
mf_t = st.median(x["seconds_to_se_1e-4"] for x in m)
print(f"\n| system | samples/s | variance/sample | s to SE 1e-4 |\n|---|---|---|---|")
print(f"| Mitsuba 3 llvm_ad_rgb, visible normals + height-correlated G2 | {mi_rate:.3g} | {mi_var:.3g} | {mi_t:.3g} |")
print(f"| mfv bench --case {'ggx/smith_ggx_correlated/none:0.5:0.5'} (the suite's estimator) | {mf_rate:.3g} | {mf_var:.3g} | {mf_t:.3g} |")
print(f"\nmedians of {rounds} alternating rounds; Mitsuba 3 / mfv time to SE 1e-4: {mi_t / mf_t:.1f}x")
PY
