#!/usr/bin/env python3
"""Records of mfv's five record-producing commands, and their comparison.

A refactor that must not change results (issue: one table of checks, one
layout, one harness) is proved by giving the same records before and after:

    scripts/records.py collect --mfv build/mfv --out /tmp/before   # old build
    scripts/records.py collect --mfv build/mfv --out /tmp/after    # new build
    scripts/records.py compare /tmp/before/records.json.gz /tmp/after/records.json.gz

The CTest `records_unchanged` runs `check` against tests/data/records/
golden.json.gz, the records of the build before the refactor. A change that is
meant to move values (a bug fix, a new estimator) regenerates it:

    scripts/records.py collect --mfv build/mfv --out /tmp/r
    cp /tmp/r/records.json.gz tests/data/records/golden.json.gz

and its commit message lists what moved (see `compare` against the old file).

`collect` runs `mfv run`, `energy`, `stability`, `agree` and `check` with a
fixed seed at small sample counts (about a minute on 2 cores) and keeps what
they conclude and measure: every verdict and count exactly, every estimate,
standard error and error figure as a number. Time stamps, timings, commit ids
and build details are left out: they differ between any two runs.

`compare` exits 1 when a record is missing, added, or different: strings
(verdicts, reasons, inputs) must be equal once their numbers are taken out,
integers (counts) equal, and other numbers equal within RTOL relative. The
default RTOL, 1e-5, is the float32 accumulation bound of docs/statistics.md
(Higham's gamma_k for the kernels' reduction depth, 7.63e-6) rounded up: two
builds that sum the same float terms in another order may differ by that
much, and a changed formula or estimator moves values by far more.
"""
import argparse
import gzip
import json
import math
import os
import re
import subprocess
import sys

SEED = "7"
DEVICE_KEY = "_device"  # numbers are compared only between runs on the same device

# Keys that describe when, where and how fast a run happened, not what it
# found: left out of the records wherever they appear.
VOLATILE = {
    "build", "build_options", "created", "date", "device", "provenance", "seconds",
    "timings", "tool", "samples_per_second", "build_seconds", "command", "kernel_dir",
}

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|0x[0-9a-fA-Fp.+-]+")


def flatten(value, path, out):
    if isinstance(value, dict):
        for k, v in value.items():
            if k not in VOLATILE:
                flatten(v, f"{path}.{k}" if path else k, out)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            flatten(v, f"{path}[{i}]", out)
    else:
        out[path] = value


def run_mfv(mfv, args, allowed=(0, 1)):
    """Runs mfv quietly; exit 1 (a failed verdict) is a record, not an error."""
    p = subprocess.run([mfv, "-q"] + args, capture_output=True, text=True)
    if p.returncode not in allowed:
        sys.exit(f"records: mfv {' '.join(args)} exited {p.returncode}: {p.stderr.strip()[:400]}")
    return p.returncode, p.stdout


def agree_rows(text):
    """The table of `mfv agree`: case name, then six columns."""
    rows = {}
    for line in text.splitlines():
        parts = line.split()
        # a row ends in "failures verdict": an integer and a word
        if len(parts) < 8 or parts[0] == "case" or not parts[-2].isdigit():
            continue
        name = " ".join(parts[:-6])
        keys = ["max_rel", "median_rel", "max_ulps", "budget", "failures", "verdict"]
        row = dict(zip(keys, parts[-6:]))
        try:
            for k in keys[:4]:
                row[k] = float(row[k])
        except ValueError:  # the summary line, not a row
            continue
        row["failures"] = int(row["failures"])
        rows[name] = row
    return rows


def collect(mfv, repo, out):
    os.makedirs(out, exist_ok=True)
    records = {}

    code, _ = run_mfv(mfv, ["run", "--seed", SEED, "--scale", "0.125", "--out", f"{out}/run"])
    run = json.load(open(f"{out}/run/results.json"))
    records[DEVICE_KEY] = " | ".join(run["device"].get(k, "") for k in ("name", "version", "driver"))
    records["run.exit"] = code
    # every group (one model x check verdict, with its pooled test and worst
    # point) and every 53rd integral: the groups summarise all integrals, the
    # sample of integrals pins individual estimates without a 100 MB file
    flatten({k: run[k] for k in ("groups", "reference", "run")}, "run", records)
    flatten(run["results"][::53], "run.results", records)
    records["run.results.count"] = len(run["results"])

    code, _ = run_mfv(mfv, ["energy", "--grid", "8x8", "--max-points", "1024", "--replicates", "4",
                            "--seed", SEED, "--out", f"{out}/energy"])
    records["energy.exit"] = code
    energy = json.load(open(f"{out}/energy/energy.json"))
    energy.pop("summary", None)
    flatten(energy, "energy", records)

    code, _ = run_mfv(mfv, ["stability", "--out", f"{out}/stability"])
    records["stability.exit"] = code
    flatten(json.load(open(f"{out}/stability/stability.json")), "stability", records)

    code, text = run_mfv(mfv, ["agree", "--seed", SEED, "--samples", "2000"])
    records["agree.exit"] = code
    flatten(agree_rows(text), "agree", records)

    for example in ("ggx.cl", "ggx_missing_pi.cl"):
        code, _ = run_mfv(mfv, ["check", "--brdf", f"{repo}/examples/brdf/{example}", "--seed", SEED,
                                "--samples", "1024", "--out", f"{out}/check_{example}"])
        records[f"check.{example}.exit"] = code
        check = json.load(open(f"{out}/check_{example}/results.json"))
        check["results"] = check["results"][::53]
        flatten(check, f"check.{example}", records)

    with gzip.open(f"{out}/records.json.gz", "wt") as f:
        json.dump(records, f, indent=0, sort_keys=True)
    print(f"records: {len(records)} values in {out}/records.json.gz")


def same_number(a, b, rtol):
    if isinstance(a, bool) or isinstance(b, bool) or isinstance(a, int) and isinstance(b, int):
        return a == b
    if isinstance(a, float) and isinstance(b, float) and (math.isnan(a) or math.isnan(b)):
        return math.isnan(a) and math.isnan(b)
    if math.isinf(rtol) or a == b:
        return True
    return abs(a - b) <= rtol * max(abs(a), abs(b))


def same_string(a, b, rtol):
    if NUMBER.sub("#", a) != NUMBER.sub("#", b):
        return False
    for x, y in zip(NUMBER.findall(a), NUMBER.findall(b)):
        try:
            fx, fy = float.fromhex(x) if x.startswith("0x") else float(x), float.fromhex(y) if y.startswith("0x") else float(y)
        except ValueError:
            if x != y:
                return False
            continue
        # printed numbers carry 3 to 12 significant digits: equal when equal
        # as printed, or within rtol
        if x != y and not math.isinf(rtol) and abs(fx - fy) > rtol * max(abs(fx), abs(fy)):
            return False
    return True


def compare(before_path, after_path, rtol, limit):
    before, after = (json.load(gzip.open(p, "rt")) for p in (before_path, after_path))
    problems = []
    same_device = before.get(DEVICE_KEY) == after.get(DEVICE_KEY)
    if not same_device:
        # another CPU may round a builtin (exp, pow, sqrt) differently in its
        # last bit: then only what the numbers decide is compared (verdicts,
        # counts, exit codes, the words of every message), not the numbers
        print(f"records: devices differ ({before.get(DEVICE_KEY)!r} vs {after.get(DEVICE_KEY)!r}): "
              "comparing verdicts, counts and messages, not values")
        rtol = math.inf
    for k in sorted(before.keys() - after.keys()):
        problems.append(f"missing after: {k} = {before[k]!r}")
    for k in sorted(after.keys() - before.keys()):
        problems.append(f"new after: {k} = {after[k]!r}")
    for k in sorted(before.keys() & after.keys()):
        a, b = before[k], after[k]
        if isinstance(a, str) and isinstance(b, str):
            ok = same_string(a, b, rtol)
        elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
            ok = same_number(a, b, rtol)
        else:
            ok = a == b
        if not ok:
            problems.append(f"changed: {k}: {a!r} -> {b!r}")
    print(f"records: {len(before)} before, {len(after)} after, {len(problems)} differ (rtol {rtol:g})")
    for p in problems[:limit]:
        print("  " + p)
    if len(problems) > limit:
        print(f"  ... and {len(problems) - limit} more")
    return 1 if problems else 0


def selftest(golden):
    """compare must fail on a changed verdict, a value moved by 1e-4, a lost
    record, and pass a value moved within rounding."""
    import copy
    import tempfile
    base = json.load(gzip.open(golden, "rt"))
    verdict = next(k for k, v in base.items() if k.endswith(".verdict") and v == "pass")
    estimate = next(k for k, v in base.items() if k.endswith(".estimate") and isinstance(v, float) and v > 0)
    cases = {
        "a verdict changed": (lambda r: r.__setitem__(verdict, "FAIL"), 1),
        "an estimate moved by 1e-4": (lambda r: r.__setitem__(estimate, r[estimate] * (1 + 1e-4)), 1),
        "a record lost": (lambda r: r.pop(verdict), 1),
        "an estimate moved by 1e-6 (rounding)": (lambda r: r.__setitem__(estimate, r[estimate] * (1 + 1e-6)), 0),
    }
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for name, (change, want) in cases.items():
            r = copy.deepcopy(base)
            change(r)
            path = os.path.join(tmp, "changed.json.gz")
            with gzip.open(path, "wt") as f:
                json.dump(r, f)
            got = compare(golden, path, 1e-5, 3)
            print(f"selftest: {name}: compare exits {got} (want {want})")
            failed += got != want
    return 1 if failed else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    c = sub.add_parser("collect")
    c.add_argument("--mfv", required=True)
    c.add_argument("--repo", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    c.add_argument("--out", required=True)
    d = sub.add_parser("compare")
    d.add_argument("before")
    d.add_argument("after")
    d.add_argument("--rtol", type=float, default=1e-5)
    d.add_argument("--limit", type=int, default=40)
    k = sub.add_parser("check", help="collect into --out, then compare with --golden")
    k.add_argument("--mfv", required=True)
    k.add_argument("--repo", default=os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    k.add_argument("--out", required=True)
    k.add_argument("--golden", required=True)
    t = sub.add_parser("selftest")
    t.add_argument("golden")
    args = ap.parse_args()
    if args.cmd == "collect":
        collect(args.mfv, args.repo, args.out)
        return 0
    if args.cmd == "check":
        collect(args.mfv, args.repo, args.out)
        return compare(args.golden, f"{args.out}/records.json.gz", 1e-5, 40)
    if args.cmd == "selftest":
        return selftest(args.golden)
    return compare(args.before, args.after, args.rtol, args.limit)


if __name__ == "__main__":
    sys.exit(main())
