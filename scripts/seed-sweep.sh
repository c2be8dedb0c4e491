#!/usr/bin/env bash
# Runs the default conformance suite under 20 seeds and prints one line per
# seed; exits non-zero if any seed gives an unexpected verdict. About 15 min
# on 2 cores (the CI test runs the same at a quarter of the samples).
set -uo pipefail
cd "$(dirname "$0")/.."
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
for seed in $(seq 1 20); do
  ./build/mfv run --seed "$seed" "$@" > "$log" 2>&1
  rc=$?
  echo "seed $seed exit $rc: $(grep -E "verdicts:|worst disagreement" "$log" | sed 's/ at .*//' | tr '\n' ' ')"
  [ "$rc" -eq 0 ] || status=1
done
exit $status
