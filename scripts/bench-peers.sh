#!/usr/bin/env bash
# mfv against Mitsuba 3 on the same integral, back to back in one run: the
# directional albedo of GGX + height-correlated Smith G2 + F = 1 at
# (alpha, mu) = (0.5, 0.5), (0.1, 0.1), (0.01, 0.9) (quadrature 0.6982507,
# 0.8834550, 0.9998865: ggx_np.py beside the peers' scripts).
#
# mfv: `mfv bench --case` (the suite's estimator), 9 timed calls at each
# whole-net point count per replicate (its bench.json `grid`).
# Mitsuba 3 (the stronger anchor, mitsuba_albedo_qmc.py: visible normals on
# its low-discrepancy samplers, SE from 32 independently randomized
# replicates): multijitter and multijitter + dr.freeze at SIZES points per
# replicate (multijitter rounds a size to its grid), 9 timed calls each,
# ldsampler at 4096; the extrapolated time to SE 1e-4 and 1e-5 (variance /
# SE² / samples per second, from the 4096-point run).
# One rule for both sides: a point count "reaches" SE s where the median over
# rounds of its timed calls' rms SE is at most s, and the cell's call is the
# reaching count with the smallest median wall time. The last table gives,
# per cell, mfv's call, Mitsuba 3's best (multijitter with or without
# dr.freeze) and mfv / Mitsuba. Not part of CI (the peers need Python
# packages from PyPI).
#
# Setup (Debian 12, once):
#   apt-get install -y libllvm19                 # Dr.Jit 1.5 fails on Debian's LLVM 15
#   python3 -m venv /work/peers-venv && /work/peers-venv/bin/pip install mitsuba numpy scipy
# Usage:
#   scripts/bench-peers.sh [build dir] [peers dir] [venv]   # defaults: build ../shared/peers /work/peers-venv
#   ROUNDS=3 scripts/bench-peers.sh                          # alternate mfv and Mitsuba 3 times (medians)
#   CASES="0.5:0.5:0.6982507" scripts/bench-peers.sh         # one case
#   MFV_KERNELS="before=/tmp/k0 after=kernels" scripts/bench-peers.sh
#       # mfv with each kernel folder (mfv --kernel-dir) in every round, back
#       # to back with Mitsuba 3: a before/after in one run from one binary
#       # (default: one entry, the embedded kernels)
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
peers=${2:-$here/../shared/peers}
venv=${3:-/work/peers-venv}
rounds=${ROUNDS:-1}
cases=${CASES:-0.5:0.5:0.6982507 0.1:0.1:0.8834550 0.01:0.9:0.9998865}
sizes=${SIZES:-256 384 512 768 1024 1536 2048 3072 4096 8192 16384 65536}
kernels=${MFV_KERNELS:-mfv=}
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-$(dpkg -L libllvm19 2>/dev/null | grep -m1 'libLLVM.so.19' || true)}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$rounds"); do
  for c in $cases; do
    IFS=: read -r a mu truth <<<"$c"
    for kd in $kernels; do
      label=${kd%%=*} dir=${kd#*=}
      "$build/mfv" ${dir:+--kernel-dir "$dir"} bench --case "ggx/smith_ggx_correlated/none:$a:$mu" --repeats 9 \
        --seed "$r" --out "$out/mfv" >/dev/null
      cp "$out/mfv/bench.json" "$out/mfv_${label}_${c}_$r.json"
    done
    qmc=("$venv/bin/python" "$peers/mitsuba_albedo_qmc.py" --R 32 --repeats 9 --alpha "$a" --mu "$mu" --truth "$truth"
      --seed "$r")
    for n in $sizes; do
      "${qmc[@]}" --n "$n" --samplers multijitter --tag "mj" >>"$out/mi_${c}_$r.jsonl"
      "${qmc[@]}" --n "$n" --samplers multijitter --freeze --tag "mj+freeze" >>"$out/mi_${c}_$r.jsonl"
    done
    "${qmc[@]}" --n 4096 --samplers ldsampler --tag "ld" >>"$out/mi_${c}_$r.jsonl"
  done
done
echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$out" "$rounds" "$cases" "$kernels" <<'PY'
import json, statistics as st, sys
out, rounds, cases = sys.argv[1], int(sys.argv[2]), sys.argv[3].split()
labels = [k.split("=", 1)[0] for k in sys.argv[4].split()]
med = lambda xs: st.median(xs) if xs else float("nan")
targets = (1e-4, 1e-5)
summary = []
for c in cases:
    a, mu, truth = c.split(":")
    print(f"\n## alpha {a}, mu {mu} (truth {truth}); medians of {rounds} round(s)\n")
    rows = [json.loads(l) for r in range(1, rounds + 1) for l in open(f"{out}/mi_{c}_{r}.jsonl") if l.startswith("{")]
    print("| system | points x replicates | variance/sample | one call: wall, rms SE | extrapolated s to SE 1e-4, 1e-5 |")
    print("|---|---|---|---|---|")
    best = {**{lb: {} for lb in labels}, "Mitsuba 3": {}}
    def consider(side, what, n, wall, se):
        for t in targets:
            if se <= t and (t not in best[side] or wall < best[side][t][0]):
                best[side][t] = (wall, se, what)
    # mfv: each whole-net count of bench --case's grid (medians over the rounds that timed it)
    for lb in labels:
        m = [json.load(open(f"{out}/mfv_{lb}_{c}_{r}.json")) for r in range(1, rounds + 1)]
        by_n = {}
        for x in m:
            for g in x["grid"]: by_n.setdefault(g["points_per_replicate"], []).append(g)
        for n in sorted(by_n):
            gs = by_n[n]
            wall, se = med([g["median_seconds"] for g in gs]), med([g["rms_stderr"] for g in gs])
            consider(lb, f"{n} x {m[0]['replicates']}", n, wall, se)
            print(f"| {lb} bench --case | {n} x {m[0]['replicates']} | {med([g['variance_per_sample'] for g in gs]):.3g} "
                  f"| {1e3 * wall:.3g} ms, {se:.2g} | - |")
    for tag in ("mj", "mj+freeze", "ld"):
        by_n = {}
        for x in rows:
            if x["tag"] == tag: by_n.setdefault(x["n_per_replicate"], []).append(x)
        for n in sorted(by_n):
            xs = by_n[n]
            wall = med([sorted(x["times_s"])[len(x["times_s"]) // 2] for x in xs])
            se = med([x["rms_se_per_call"] for x in xs])
            var = med([x["var_per_sample"] for x in xs])
            rate = med([x["samples_per_s_median"] for x in xs])
            if tag != "ld": consider("Mitsuba 3", f"{tag} {n} x 32", n, wall, se)
            extra = f"{var / 1e-8 / rate * 1e3:.3g} ms, {var / 1e-10 / rate * 1e3:.3g} ms" if n == 4096 else "-"
            print(f"| Mitsuba 3 {tag} | {n} x 32 | {var:.3g} | {1e3 * wall:.3g} ms, {se:.2g} | {extra} |")
    for lb in labels:
        for t in targets:
            summary.append((lb, a, mu, t, best[lb].get(t), best["Mitsuba 3"].get(t)))
print("\n## One call reaching each SE: mfv against Mitsuba 3's best (multijitter, with or without dr.freeze)\n")
print(f"Medians of {rounds} round(s); a count reaches SE s where its timed calls' rms SE (median over rounds) is at most s.\n")
print("| mfv | alpha, mu | SE | mfv: points x replicates, wall, rms SE | Mitsuba 3 best: sampler, points x replicates, wall, rms SE | mfv / Mitsuba |")
print("|---|---|---|---|---|---|")
fmt = lambda b: f"{b[2]}, {1e3 * b[0]:.3g} ms, {b[1]:.2g}" if b else "none reached (SIZES)"
for lb, a, mu, t, bm, bi in summary:
    ratio = f"{bm[0] / bi[0]:.2f}" if bm and bi else "-"
    print(f"| {lb} | {a}, {mu} | {t:g} | {fmt(bm)} | {fmt(bi)} | {ratio} |")
PY
