#!/usr/bin/env bash
# mfv against Mitsuba 3 on the same integral, back to back in one run: the
# directional albedo of GGX + height-correlated Smith G2 + F = 1 at
# (alpha, mu) = (0.5, 0.5), (0.1, 0.1), (0.01, 0.9) (quadrature 0.6982507,
# 0.8834550, 0.9998865: ggx_np.py beside the peers' scripts).
#
# mfv: `mfv bench --case` (the suite's estimator), one call's wall time and SE
# at the fewest points reaching SE 1e-4 and 1e-5.
# Mitsuba 3 (the stronger anchor, mitsuba_albedo_qmc.py: visible normals on
# its low-discrepancy samplers, SE from 32 independently randomized
# replicates): multijitter and multijitter + dr.freeze at 256 ... 65536
# points per replicate, ldsampler at 4096; for each, one call's wall time
# and SE, the extrapolated time to SE 1e-4 and 1e-5 (variance / SE² /
# samples per second, from the 4096-point run), and the smallest measured
# call reaching each SE. Not part of CI (the peers need Python packages from PyPI).
#
# Setup (Debian 12, once):
#   apt-get install -y libllvm19                 # Dr.Jit 1.5 fails on Debian's LLVM 15
#   python3 -m venv /work/peers-venv && /work/peers-venv/bin/pip install mitsuba numpy scipy
# Usage:
#   scripts/bench-peers.sh [build dir] [peers dir] [venv]   # defaults: build ../shared/peers /work/peers-venv
#   ROUNDS=3 scripts/bench-peers.sh                          # alternate mfv and Mitsuba 3 times (medians)
#   CASES="0.5:0.5:0.6982507" scripts/bench-peers.sh         # one case
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
peers=${2:-$here/../shared/peers}
venv=${3:-/work/peers-venv}
rounds=${ROUNDS:-1}
cases=${CASES:-0.5:0.5:0.6982507 0.1:0.1:0.8834550 0.01:0.9:0.9998865}
sizes=${SIZES:-256 1024 4096 16384 65536}
export DRJIT_LIBLLVM_PATH=${DRJIT_LIBLLVM_PATH:-$(dpkg -L libllvm19 2>/dev/null | grep -m1 'libLLVM.so.19' || true)}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "load average at the start: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq "$rounds"); do
  for c in $cases; do
    IFS=: read -r a mu truth <<<"$c"
    "$build/mfv" bench --case "ggx/smith_ggx_correlated/none:$a:$mu" --repeats 9 --seed "$r" --out "$out/mfv" >/dev/null
    cp "$out/mfv/bench.json" "$out/mfv_${c}_$r.json"
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
python3 - "$out" "$rounds" "$cases" <<'PY'
import json, statistics as st, sys
out, rounds, cases = sys.argv[1], int(sys.argv[2]), sys.argv[3].split()
med = lambda xs: st.median(xs) if xs else float("nan")
for c in cases:
    a, mu, truth = c.split(":")
    print(f"\n## alpha {a}, mu {mu} (truth {truth}); medians of {rounds} round(s)\n")
    m = [json.load(open(f"{out}/mfv_{c}_{r}.json")) for r in range(1, rounds + 1)]
    rows = [json.loads(l) for r in range(1, rounds + 1) for l in open(f"{out}/mi_{c}_{r}.jsonl") if l.startswith("{")]
    print("| system | points x replicates | variance/sample | one call: wall, SE | extrapolated s to SE 1e-4, 1e-5 |")
    print("|---|---|---|---|---|")
    for k in range(2):
        ts = [x["targets"][k] for x in m]
        t = ts[0]
        print(f"| mfv bench --case, SE target {t['target_se']:g} | {t['points_per_replicate']} x {m[0]['replicates']} "
              f"| {med([x['variance_per_sample'] for x in ts]):.3g} | {1e3 * med([x['median_seconds'] for x in ts]):.3g} ms, "
              f"{med([x['rms_stderr'] for x in ts]):.2g} | - |")
    best = {}
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
            for target in (1e-4, 1e-5):
                if se <= target and tag != "ld" and (target not in best or wall < best[target][0]):
                    best[target] = (wall, f"{tag} {n} x 32")
            extra = f"{var / 1e-8 / rate * 1e3:.3g} ms, {var / 1e-10 / rate * 1e3:.3g} ms" if n == 4096 else "-"
            print(f"| Mitsuba 3 {tag} | {n} x 32 | {var:.3g} | {1e3 * wall:.3g} ms, {se:.2g} | {extra} |")
    print()
    for k, target in enumerate((1e-4, 1e-5)):
        mf = med([x["targets"][k]["median_seconds"] for x in m])
        if target in best:
            w, what = best[target]
            print(f"one call to SE <= {target:g}: mfv {1e3 * mf:.3g} ms, Mitsuba 3's best measured {1e3 * w:.3g} ms ({what}): "
                  f"mfv {'<=' if mf <= w else '>'} Mitsuba")
        else:
            print(f"one call to SE <= {target:g}: mfv {1e3 * mf:.3g} ms; no measured Mitsuba 3 call reached it (SIZES)")
PY
