#!/usr/bin/env bash
# Installs what is missing, builds, and runs the default job: the pointwise
# agreement of every term and D x G x F BRDF, kernel vs double reference.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
./build/mfv devices
./build/mfv agree "$@"
