#!/usr/bin/env bash
# Installs the Debian 12 packages microfacet-verify needs, when missing.
set -euo pipefail
packages=(cmake g++ make pocl-opencl-icd ocl-icd-opencl-dev opencl-headers opencl-clhpp-headers
          catch2 libglm-dev librandom123-dev libcli11-dev nlohmann-json3-dev libfmt-dev libssl-dev
          libboost-math-dev libstb-dev
          libpng-dev    # 16-bit PNG tables of mfv energy --layout
          libtinyexr-dev  # float OpenEXR tables of mfv energy --layout and --compare
          gnuplot-nox   # gnuplot: optional at run time, for the plots
          python3-jsonschema python3-yaml)  # tests: outputs against schemas/, the CI snippets of docs/ci/
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The extra OpenCL implementations of the `portability` tests (Intel CPU,
# Oclgrind, rusticl), in a cache folder, never registered system-wide; optional.
bash "$(dirname "$0")/install-ocl-extras.sh"
