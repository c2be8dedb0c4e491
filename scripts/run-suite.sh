#!/usr/bin/env bash
# Installs what is missing, builds, and runs the default job: the conformance
# suite over the whole catalog (mfv run), writing results/. Extra arguments go
# to mfv run. Exit code: mfv run's (0 when every verdict matches expectation).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/mfv devices
./build/mfv run --out results "$@"
