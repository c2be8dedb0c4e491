#!/usr/bin/env bash
# Installs the extra OpenCL implementations the `portability` tests run on,
# into a cache folder, never registered system-wide (/etc/OpenCL/vendors is
# left alone): each gets its own ICD folder, picked per run with
#   OCL_ICD_VENDORS=$MFV_OCL_CACHE/vendors/<name> mfv devices
# (rusticl also needs RUSTICL_ENABLE=llvmpipe). Names: intel, oclgrind, rusticl.
#   intel:    Intel's CPU runtime, PyPI intel-opencl-rt + intel-cmplr-lib-rt
#             (the wheel's own .icd names a path that does not exist: ours
#             points at the installed libintelocl.so)
#   oclgrind: Debian oclgrind; it reports itself as a GPU, so registering it
#             system-wide would make it everyone's default device
#   rusticl:  Mesa's rusticl on llvmpipe, from Debian mesa-opencl-icd,
#             unpacked (its package would register clover and rusticl)
# Each is optional: a failure prints one line and the others go on; the
# portability tests then skip that implementation with a message.
# Exit status: 0 always unless MFV_OCL_EXTRAS_REQUIRED=1 (CI) and one failed.
set -uo pipefail
cache="${MFV_OCL_CACHE:-$HOME/.cache/mfv/ocl}"
vendors="$cache/vendors"
intel_version=2026.2.0
mkdir -p "$vendors"
failed=()

have_icd() { [ -s "$vendors/$1/$1.icd" ] && [ -e "$(cat "$vendors/$1/$1.icd")" ]; }
write_icd() { mkdir -p "$vendors/$1" && echo "$2" > "$vendors/$1/$1.icd"; }

install_intel() {
  have_icd intel && return 0
  local py
  py="$(command -v python3)" || { echo "no python3"; return 1; }
  "$py" -m pip install -q --disable-pip-version-check --no-warn-script-location --root-user-action=ignore \
    --prefix "$cache/intel" "intel-opencl-rt==$intel_version" "intel-cmplr-lib-rt==$intel_version" || return 1
  [ -e "$cache/intel/lib/libintelocl.so" ] || { echo "libintelocl.so not in $cache/intel/lib"; return 1; }
  write_icd intel "$cache/intel/lib/libintelocl.so"
}

install_oclgrind() {
  have_icd oclgrind && return 0
  if ! dpkg-query -W -f='${Status}' oclgrind 2>/dev/null | grep -q "install ok installed"; then
    apt-cache show oclgrind >/dev/null 2>&1 || apt-get update -qq >/dev/null 2>&1
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends oclgrind >/dev/null || return 1
  fi
  local lib
  lib="$(dpkg -L oclgrind liboclgrind-21.10 2>/dev/null | grep 'liboclgrind-rt-icd\.so$' | head -1)"
  [ -n "$lib" ] || lib="$(find /usr/lib -name liboclgrind-rt-icd.so 2>/dev/null | head -1)"
  [ -n "$lib" ] || { echo "liboclgrind-rt-icd.so not found"; return 1; }
  write_icd oclgrind "$lib"
}

install_rusticl() {
  have_icd rusticl && return 0
  # its libraries from Debian, the ICD itself unpacked into the cache
  local deps
  mesa_deps() { apt-cache depends mesa-opencl-icd 2>/dev/null | awk '/Depends: [a-z]/ {print $2}' | grep -v opencl | sort -u; }
  deps="$(mesa_deps)"
  [ -n "$deps" ] || { apt-get update -qq >/dev/null 2>&1; deps="$(mesa_deps)"; }
  [ -n "$deps" ] || { echo "apt-cache knows no mesa-opencl-icd"; return 1; }
  # shellcheck disable=SC2086
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $deps >/dev/null || return 1
  local tmp
  tmp="$(mktemp -d)"
  (cd "$tmp" && apt-get download -qq mesa-opencl-icd 2>/dev/null) || { rm -rf "$tmp"; return 1; }
  rm -rf "$cache/mesa" && dpkg -x "$tmp"/mesa-opencl-icd_*.deb "$cache/mesa" || { rm -rf "$tmp"; return 1; }
  rm -rf "$tmp" "$cache/mesa/etc"  # its /etc/OpenCL/vendors files: not ours to register
  local lib="$cache/mesa/usr/lib/x86_64-linux-gnu/libRusticlOpenCL.so.1"
  [ -e "$lib" ] || lib="$(find "$cache/mesa" -name 'libRusticlOpenCL.so.1' | head -1)"
  [ -n "$lib" ] && [ -e "$lib" ] || { echo "libRusticlOpenCL.so.1 not in the package"; return 1; }
  write_icd rusticl "$lib"
}

for name in intel oclgrind rusticl; do
  if out="$("install_$name" 2>&1)"; then
    :
  else
    echo "install-ocl-extras: $name not installed, its portability tests will skip: $(echo "$out" | tail -1)" >&2
    failed+=("$name")
  fi
done
if [ ${#failed[@]} -gt 0 ] && [ "${MFV_OCL_EXTRAS_REQUIRED:-0}" = 1 ]; then
  echo "install-ocl-extras: required but missing: ${failed[*]}" >&2
  exit 1
fi
exit 0
