#!/usr/bin/env python3
"""Flops per work-item counted from the compiled kernels (mfv bench's flop
counts, checked against the hand counts in host/checks/bench.cpp).

Runs an mfv command with PoCL's kernel compiler keeping its files
(POCL_LEAVE_KERNEL_COMPILER_TEMP_FILES, a fresh POCL_CACHE_DIR, mfv's program
cache on so every kernel of every program is compiled), disassembles each
kernel's work-group function (parallel.bc) with clang, and counts the float
operations in the body of the vectorized loop over work-items (LLVM's
`vector.body`), per lane: fadd, fsub, fmul, fdiv, frem, sqrt, minnum/maxnum
(and fmin/fmax as fcmp + select are not counted), fma/fmuladd as 2. In a
vectorized loop every instruction runs for every work-item (branches became
selects), so the static count per lane is the dynamic count per work-item.
Kernels PoCL left scalar have no vector body: reported as "scalar". The
reductions (sum_values, sum_pairs, sum_rqmc) and `integrate` loop inside a
work-item: their vector body is an inner loop's, not a per-item count.
Integer operations (Philox: mul, xor, add, shifts, and/or) are counted apart.

Usage: scripts/kernel-flops.py [--target avx2|avx512] build/mfv bench --integrand d_norm --repeats 1
Needs clang-15 (the LLVM of Debian's PoCL) to read the bitcode.
"""
import collections
import os
import re
import shutil
import subprocess
import sys
import tempfile

FLOAT_OPS = {"fadd": 1, "fsub": 1, "fmul": 1, "fdiv": 1, "frem": 1}
FLOAT_CALLS = {"sqrt": 1, "minnum": 1, "maxnum": 1, "fma": 2, "fmuladd": 2}
INT_OPS = {"mul", "add", "sub", "xor", "lshr", "shl", "ashr", "and", "or"}


def lanes(ty):
    m = re.match(r"<(\d+) x ", ty)
    return int(m.group(1)) if m else 1


def count(ll):
    """Per-kernel (flops, int ops, width) from the first vector.body of each
    _pocl_kernel_* function."""
    out = {}
    for fn in re.finditer(r"^define [^@]*@_pocl_kernel_([a-z0-9_]+)\(.*?^}", ll, re.M | re.S):
        name, body = fn.group(1), fn.group(0)
        if name.endswith("_workgroup") or name.endswith("_workgroup_fast") or name in out:
            continue
        vb = re.search(r"^vector\.body:.*?(?=^[a-z_.0-9]+:)", body, re.M | re.S)
        if not vb:
            out[name] = None
            continue
        flops = ints = 0
        width = 0
        for line in vb.group(0).splitlines():
            m = re.match(r"\s*%\S+ = (\w+)(?: [a-z ]*?)? (<\d+ x \w+>|float|double|i\d+) ", line)
            if m and m.group(1) in FLOAT_OPS:
                flops += FLOAT_OPS[m.group(1)] * lanes(m.group(2))
                width = max(width, lanes(m.group(2)))
                continue
            if m and m.group(1) in INT_OPS and m.group(2).startswith("<"):
                ints += lanes(m.group(2))
                width = max(width, lanes(m.group(2)))
                continue
            c = re.search(r"call [a-z ]*(<\d+ x (?:float|double)>|float|double) @llvm\.(\w+)\.", line)
            if c and c.group(2) in FLOAT_CALLS:
                flops += FLOAT_CALLS[c.group(2)] * lanes(c.group(1))
        width = width or 1
        out[name] = (flops / width, ints / width, width)
    return out


def main(argv):
    target = None
    if argv[:1] == ["--target"]:
        target, argv = argv[1], argv[2:]
    if not argv:
        sys.exit(__doc__)
    clang = shutil.which("clang-15") or "/usr/lib/llvm-15/bin/clang"
    work = tempfile.mkdtemp(prefix="mfv-flops-")
    try:
        env = dict(os.environ, POCL_CACHE_DIR=work + "/pocl", MFV_PROGRAM_CACHE="1", MFV_CACHE_DIR=work + "/mfv",
                   POCL_LEAVE_KERNEL_COMPILER_TEMP_FILES="1")
        if target:
            env["POCL_KERNELLIB_NAME"] = target
        subprocess.run(argv, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rows = {}
        for root, _, files in os.walk(work + "/pocl"):
            if "parallel.bc" in files and os.path.basename(root) == "0-0-0":
                ll = subprocess.run([clang, "-S", "-emit-llvm", "-x", "ir", os.path.join(root, "parallel.bc"), "-o", "-"],
                                    capture_output=True, text=True, check=True).stdout
                for k, v in count(ll).items():
                    rows.setdefault(k, v)
        print(f"{'kernel':30} {'flops/item':>10} {'int ops/item':>12} {'width':>6}")
        for k, v in rows.items():
            if v is None:
                print(f"{k:30} {'scalar':>10}")
            else:
                print(f"{k:30} {v[0]:10.1f} {v[1]:12.1f} {v[2]:6d}")
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main(sys.argv[1:])
