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
set -euo pipefail

# The remarks on stdin -> "kernel<TAB>width" lines (width: 8, 4, ... or "scalar").
parse() {
  grep -oE "'_pocl_kernel_[a-z0-9_]+' inlined into '_pocl_kernel_[a-z0-9_]+_workgroup'|vectorized loop \([^)]*\)" |
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
for t in "${targets[@]}"; do
  mkdir -p "$work/$t/mfv" "$work/$t/pocl"
  # `|| true`: a target the CPU cannot run stops the command at its first launch
  (MFV_PROGRAM_CACHE=1 MFV_CACHE_DIR="$work/$t/mfv" POCL_CACHE_DIR="$work/$t/pocl" POCL_KERNELLIB_NAME="$t" \
    POCL_KERNEL_CACHE=0 POCL_VECTORIZER_REMARKS=1 "$@" 2>&1 || true) | parse |
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
