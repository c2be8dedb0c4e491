#!/usr/bin/env bash
# Regenerates everything in results/ from one commit, with the build of that
# commit: the conformance suite (mfv run), the energy tables (D x G and whole
# models), the stability sweep, the sampler tests with their images, the
# benchmark and the convergence study. About 25 min on 2 cores.
#
#   bash scripts/regenerate-results.sh [--out DIR] [--quick] [--allow-dirty]
#
# --out DIR      write there instead of results/ (a test writes to /tmp)
# --quick        tiny sizes, a minute in all: checks the script, not the numbers
# --allow-dirty  run on a tree with uncommitted changes (outputs say "-dirty")
#
# The full per-integral results.json (about 29 MB) stays out of git
# (.gitignore); results/summary.json is the run without its per-integral
# records. Exit status: 0 when every command matched expectation.
set -euo pipefail
cd "$(dirname "$0")/.."
out=results quick=0 dirty=0
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --allow-dirty) dirty=1; shift ;;
    *) echo "regenerate-results.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
if [ "$dirty" = 0 ] && [ -n "$(git status --porcelain --untracked-files=no -- . ':(exclude)results')" ]; then
  echo "regenerate-results.sh: uncommitted changes outside results/; commit them (or --allow-dirty)" >&2
  exit 2
fi
bash scripts/build.sh
mfv="$PWD/build/mfv --quiet"
if [ "$quick" = 1 ]; then
  run=(--check d_norm furnace --model ggx/ --samples 256)
  energy=(--models ggx/smith_ggx_correlated --grid 4x4 --max-points 1024)
  energy_models=(--models 'lambert[' --grid 4x4 --max-points 1024)
  stability=(--only 'D ggx' --terms-only)
  samplers=(--samples 65536 --bins 16x32 --device-only)
  bench=(--integrand d_norm --integrals 4 --samples 4096 --ref-samples 256 --repeats 1)
  convergence=(--case ggx:0.1:1 --check d_norm --estimator mis --max-log2 9 --ref-max-log2 8 --replicates 2)
else
  run=() energy=() energy_models=(--models '[') stability=() samplers=() bench=() convergence=()
fi
mkdir -p "$out"
# every output comes from this run: nothing stale from an earlier commit stays
rm -rf "$out"/{energy,energy_models,stability,samplers,bench,convergence} \
       "$out"/{results.json,summary.json,report.md,junit.xml}
status=0
step() {  # step NAME COMMAND...: runs it, logs its stdout to $out/NAME.log, remembers a failure
  local name=$1; shift
  echo "== $name: $*"
  if ! "$@" > "$out/$name.log"; then status=1; echo "   $name did not match expectation (see $out/$name.log)"; fi
  tail -n 2 "$out/$name.log" | sed 's/^/   /'
}
step run $mfv run --out "$out" "${run[@]}"
python3 - "$out/results.json" "$out/summary.json" <<'PY'
import json, sys
run = json.load(open(sys.argv[1]))
run.pop("results", None)  # the per-integral records stay in results.json, out of git
json.dump(run, open(sys.argv[2], "w"), indent=1)
PY
step energy $mfv energy --out "$out/energy" "${energy[@]}"
# kernels/abi/sheen_table.h is the one copy of the E_sheen table (what the
# kernel and the reference read, from its own 16x16 run; see its header):
# the default run's sheen_table.h is not kept beside it.
rm -f "$out/energy/sheen_table.h"
step energy_models $mfv energy --out "$out/energy_models" "${energy_models[@]}"
step stability $mfv stability --out "$out/stability" "${stability[@]}"
step samplers $mfv samplers --plots --out "$out/samplers" "${samplers[@]}"
step bench $mfv bench --out "$out/bench" "${bench[@]}"
step convergence $mfv convergence --out "$out/convergence" "${convergence[@]}"
rm -f "$out"/*.log
echo "results in $out from commit $(git rev-parse --short HEAD)$([ "$dirty" = 1 ] && echo ' (tree may be dirty)')"
exit $status
