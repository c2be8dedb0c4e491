#!/usr/bin/env bash
# Which kernels PoCL vectorizes: runs an mfv command with PoCL's kernel cache
# off and its loop-vectorizer remarks on, and prints, per work-group function
# PoCL compiles, whether the loop over work-items was vectorized and how wide.
# Usage: scripts/pocl-vectorization.sh build/mfv bench --integrand d_norm --repeats 1
#        scripts/pocl-vectorization.sh build/mfv run --check masking --model ggx/smith_ggx
#
# Per CPU target, on any x86-64 CPU: --targets avx2,avx512 compiles for each
# of PoCL's kernel libraries (POCL_KERNELLIB_NAME: avx2 is PoCL's `haswell`
# target, avx512 its `skylake-avx512`; Debian's PoCL picks its target from
# the library, not from POCL_LLVM_CPU_NAME) and prints one column per target:
#        scripts/pocl-vectorization.sh --targets avx2,avx512 build/mfv bench --integrand d_norm --repeats 1
# With --targets, mfv's program cache is on in a fresh folder (and so is a
# fresh PoCL cache): asking PoCL for a program's binary compiles every kernel
# of the program at build time, so each target reports every kernel of every
# program the command builds, not only those it launches. Where the CPU lacks
# a target's instructions the command then dies at its first launch (SIGILL);
# the report is complete by then, and the script ignores the exit status.
# PoCL chooses only among the libraries the host CPU can run (POCL_KERNELLIB_NAME
# selects down, never up), so on a CPU without AVX-512 the avx512 target is
# compiled with build/libmfv_pretend_avx512.so preloaded (tests/pretend_avx512:
# LLVM's host features plus AVX-512, so PoCL compiles for skylake-avx512 as on
# an AVX-512 host; MFV_PRETEND_AVX512 names another copy). Each target's
# device name is checked first: a target PoCL does not compile for is an
# error (exit 2), never a column of another target's widths.
set -euo pipefail

# The remarks on stdin -> "kernel<TAB>width" lines (width: 8, 4, ... or "scalar").
parse() {
  { grep -oE "'_pocl_kernel_[a-z0-9_]+' inlined into '_pocl_kernel_[a-z0-9_]+_workgroup'|vectorized loop \([^)]*\)" || true; } |
    sed -E "s/'_pocl_kernel_([a-z0-9_]+)' inlined into .*/\1/" |
    awk '/^vectorized/ { if (k != "") v[k] = $0; next } { k = $0; if (!(k in v)) v[k] = "not vectorized"; order[++n] = k }
         END { for (i = 1; i <= n; ++i) if (!seen[order[i]]++) printf "%s\t%s\n", order[i], v[order[i]] }'
}

if [[ "${1:-}" != "--targets" ]]; then
  POCL_KERNEL_CACHE=0 POCL_VECTORIZER_REMARKS=1 "$@" 2>&1 | parse | awk -F'\t' '{ printf "%-22s %s\n", $1, $2 }'
  exit 0
fi

IFS=, read -r -a targets <<<"${2:?--targets needs a list, e.g. avx2,avx512}"
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# The LLVM CPU PoCL compiles for with kernel library $1 (and preload $2):
# its device name is pthread-<cpu>-<the CPU's brand>.
target_cpu() {
  env ${2:+LD_PRELOAD="$2"} POCL_KERNELLIB_NAME="$1" "$mfv" devices 2>/dev/null |
    grep -m1 -oE 'pthread-[a-z0-9_-]+' | sed -E 's/^pthread-//; s/-$//' || true
}
mfv=$1
pretend=${MFV_PRETEND_AVX512:-$(dirname "$mfv")/libmfv_pretend_avx512.so}
declare -A preload
for t in "${targets[@]}"; do
  case $t in avx2) want=haswell ;; avx512) want=skylake-avx512 ;; *) want= ;; esac
  preload[$t]=
  cpu=$(target_cpu "$t" "")
  if [[ -n $want && $cpu != "$want" && $t == avx512 && -f $pretend ]]; then
    preload[$t]=$pretend
    cpu=$(target_cpu "$t" "$pretend")
  fi
  # no PoCL CPU device (another driver): no remarks, an empty column as before
  if [[ -n $want && -n $cpu && $cpu != "$want" ]]; then
    echo "pocl-vectorization.sh: target $t: PoCL compiles for '$cpu' here, not '$want'" >&2
    exit 2
  fi
done
for t in "${targets[@]}"; do
  mkdir -p "$work/$t/mfv" "$work/$t/pocl"
  # `|| true`: a target the CPU cannot run stops the command at its first launch
  (env ${preload[$t]:+LD_PRELOAD="${preload[$t]}"} MFV_PROGRAM_CACHE=1 MFV_CACHE_DIR="$work/$t/mfv" POCL_CACHE_DIR="$work/$t/pocl" \
    POCL_KERNELLIB_NAME="$t" POCL_KERNEL_CACHE=0 POCL_VECTORIZER_REMARKS=1 "$@" 2>&1 || true) | parse |
    sed -E 's/vectorized loop \(vectorization width: ([0-9]+).*/\1-wide/; s/not vectorized/scalar/' >"$work/$t.txt"
done
# one row per kernel (first seen order over the targets), one column per target ("-": not compiled)
awk -F'\t' -v targets="${targets[*]}" '
  BEGIN { nt = split(targets, t, " ") }
  { f = FILENAME; sub(/.*\//, "", f); sub(/\.txt$/, "", f); w[$1, f] = $2; if (!($1 in s)) { s[$1] = 1; order[++n] = $1 } }
  END {
    printf "%-30s", "kernel"; for (j = 1; j <= nt; ++j) printf " %-8s", t[j]; printf "\n"
    for (i = 1; i <= n; ++i) {
      printf "%-30s", order[i]
      for (j = 1; j <= nt; ++j) printf " %-8s", ((order[i], t[j]) in w ? w[order[i], t[j]] : "-")
      printf "\n"
    }
  }' $(for t in "${targets[@]}"; do echo "$work/$t.txt"; done)
