#!/usr/bin/env bash
# Issue 30's census: what a cold mfv run compiles, per kernel, and what each
# compile costs (docs/performance.md, "Cold start"). Runs mfv once with
# PoCL's kernel cache in a new empty folder and POCL_DEBUG=timing; each
# work-group function PoCL compiles logs an llvm_workgroup_ir_func_gen and an
# llvm_codegen time and leaves one KERNEL.so in the cache, in the same order
# (the files' mtimes). Prints each compile (program, kernel, variant,
# seconds) with --each, and per kernel family (a specialization's __dN,
# __gN, __mN suffix read as N) the count and the seconds, then the total.
# The seconds are wall time: on a loaded machine they are inflated by the
# load (the load average is printed); compare shares, or idle runs.
# Usage: scripts/pocl-census.sh [--each] [build/mfv] [mfv arguments...]
#   default arguments: --quiet run --out DIR (the default run)
set -euo pipefail

each=0
[[ "${1:-}" == --each ]] && { each=1; shift; }
mfv=${1:-build/mfv}
shift || true
work=$(mktemp -d "${TMPDIR:-/tmp}/mfv-census.XXXXXX")
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/pocl"
args=("$@")
[[ ${#args[@]} -eq 0 ]] && args=(--quiet run --out "$work/out")
echo "load $(cut -d' ' -f1-3 /proc/loadavg)"
POCL_CACHE_DIR="$work/pocl" POCL_KERNEL_CACHE=1 MFV_CACHE_DIR="$work/mfv" POCL_DEBUG=timing \
  "$mfv" "${args[@]}" >/dev/null 2>"$work/log" || echo "mfv exited $?" >&2

# seconds of each compile, in order: ir_func_gen + the codegen that follows it
awk '/TIMING/ && /llvm_workgroup_ir_func_gen|llvm_codegen/ {
       v = $(NF - 3); u = $(NF - 2); n = $NF
       for (i = 1; i <= NF; ++i) if ($i == ">>>") { v = $(i + 1); u = $(i + 2) }
       s = (u == "ms") ? v / 1e3 : (u == "us") ? v / 1e6 : (u == "ns") ? v / 1e9 : v
       if ($0 ~ /ir_func_gen/) gen = s; else { print gen + s; gen = 0 }
     }' "$work/log" >"$work/times"
# the .so files by mtime: PROGRAM KERNEL VARIANT
find "$work/pocl" -name '*.so' -printf '%T@ %P\n' | sort -n |
  awk '{ n = split($2, p, "/"); print p[1] p[2], p[n - 2], p[n - 1] }' >"$work/files"
nt=$(wc -l <"$work/times") nf=$(wc -l <"$work/files")
[[ "$nt" == "$nf" ]] || echo "warning: $nt timed compiles against $nf .so files: the pairing is off" >&2
paste -d' ' "$work/files" "$work/times" >"$work/census"
if ((each)); then
  awk '{ printf "%-12s %-40s %-28s %7.3f s\n", substr($1, 1, 10), $2, $3, $4 }' "$work/census"
fi
awk '{ k = $2; gsub(/__[dgm][0-9]+/, "__X", k); gsub(/__dX__gX/, "__dX_gX", k)
       c[k] += 1; s[k] += $4; t += $4; n += 1; prog[$1] = 1 }
     END { for (k in c) printf "%-44s %4d %8.2f s\n", k, c[k], s[k]
           np = 0; for (p in prog) ++np
           printf "%-44s %4d %8.2f s  (%d programs)\n", "all", n, t, np }' "$work/census" |
  sort -k3 -n -r
echo "load $(cut -d' ' -f1-3 /proc/loadavg)"
