#!/usr/bin/env bash
# Which kernels PoCL vectorizes: runs an mfv command with PoCL's kernel cache
# off and its loop-vectorizer remarks on, and prints, per work-group function
# PoCL compiles, whether the loop over work-items was vectorized and how wide.
# Usage: scripts/pocl-vectorization.sh build/mfv bench --integrand d_norm --repeats 1
#        scripts/pocl-vectorization.sh build/mfv run --check masking --model ggx/smith_ggx
set -euo pipefail
POCL_KERNEL_CACHE=0 POCL_VECTORIZER_REMARKS=1 "$@" 2>&1 |
  grep -oE "'_pocl_kernel_[a-z0-9_]+' inlined into '_pocl_kernel_[a-z0-9_]+_workgroup'|vectorized loop \([^)]*\)" |
  sed -E "s/'_pocl_kernel_([a-z0-9_]+)' inlined into .*/\1/" |
  awk '/^vectorized/ { if (k != "") v[k] = $0; next } { k = $0; if (!(k in v)) v[k] = "not vectorized"; order[++n] = k }
       END { for (i = 1; i <= n; ++i) if (!seen[order[i]]++) printf "%-22s %s\n", order[i], v[order[i]] }'
