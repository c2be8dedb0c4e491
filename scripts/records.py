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

Each value is keyed by what it is, not where it stands in a list: a record of
a list (a verdict group, an integral, a stability case or region, a model's
energy row) by its check, model, terms, name, region and numeric parameters,
e.g. run.groups{check=energy model=lambert[kd=1]}.verdict. A change that
inserts a case shows as that record added; the rest still compare equal.

`compare` reports records added, records removed and values changed
separately, and exits 1 on any of them: strings (verdicts, reasons, inputs)
must be equal once their numbers are taken out, integers (counts) equal, and
other numbers equal within RTOL relative. The
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
import zlib

SEED = "7"
DEVICE_KEY = "_device"  # numbers are compared only between runs on the same device

# Keys that describe when, where and how fast a run happened, not what it
# found: left out of the records wherever they appear.
VOLATILE = {
    "build", "build_options", "created", "date", "device", "provenance", "seconds",
    "timings", "tool", "samples_per_second", "build_seconds", "command", "kernel_dir",
}

CLOSE = re.compile(r"\}")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|0x[0-9a-fA-Fp.+-]+")


# A record in a list is keyed by what it is, not by where it stands: the
# values of these fields (those it has, in this order) and its numeric
# parameters, e.g. run.groups{check=energy model=lambert[kd=1]}.verdict, so a
# case inserted before it leaves its key unchanged. Records with the same
# identity are told apart by a count (#2, #3, ...). Lists of numbers (a grid's
# values, a table's cells) stay indexed by position: the grid fixes them.
ID_FIELDS = ("check", "model", "name", "group", "family", "D", "G", "F", "d", "g", "f", "region", "at", "params")


def identity(record):
    """The identity of a list element, or None for one that is not a record."""
    if not isinstance(record, dict):
        return None
    parts = []
    for k in ID_FIELDS:
        v = record.get(k)
        if isinstance(v, dict):  # parameters: the numeric ones (not a measured worst_pair)
            v = ",".join(f"{p}={x!r}" for p, x in sorted(v.items())
                         if isinstance(x, (int, float)) and not isinstance(x, bool))
        elif k == "at" and isinstance(v, str):  # "D in region cos_grazing (160 evaluated)": the place, not the count
            v = re.sub(r"\s*\([^()]*\)$", "", v)
        if v not in (None, ""):
            parts.append(f"{k}={v}")
    return " ".join(parts) or None


def keyed(values):
    """(key, element) per element of a list: {identity} for records, [index] otherwise."""
    seen = {}
    for i, v in enumerate(values):
        name = identity(v)
        if name is None:
            yield f"[{i}]", v
            continue
        seen[name] = seen.get(name, 0) + 1
        yield "{" + name + (f" #{seen[name]}" if seen[name] > 1 else "") + "}", v


def flatten(value, path, out):
    if isinstance(value, dict):
        for k, v in value.items():
            if k not in VOLATILE:
                flatten(v, f"{path}.{k}" if path else k, out)
    elif isinstance(value, list):
        for key, v in keyed(value):
            flatten(v, f"{path}{key}", out)
    else:
        out[path] = value


def flatten_sample(values, every, path, out):
    """About one record in `every`, chosen by its key (not its position), so
    that an inserted record does not change which others are kept."""
    for key, v in keyed(values):
        if zlib.crc32(key.encode()) % every == 0:
            flatten(v, f"{path}{key}", out)


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
    # point) and one integral in 53 (by identity): the groups summarise all
    # integrals, the sample pins individual estimates without a 100 MB file
    flatten({k: run[k] for k in ("groups", "reference", "run")}, "run", records)
    flatten_sample(run["results"], 53, "run.results", records)
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
        flatten_sample(check.pop("results"), 53, f"check.{example}.results", records)
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


def record_prefixes(key):
    """The keys of the records that hold `key`, outermost first: each prefix
    that ends in a {identity} (identities hold no braces)."""
    return [key[:m.end()] for m in CLOSE.finditer(key)] if "{" in key else []


def whole_records(keys, other):
    """`keys` (values on one side only) as the outermost records the other
    side lacks entirely, plus single values added to or removed from records both have."""
    if not keys:
        return []
    present = {p for k in other for p in record_prefixes(k)}
    found = set()
    for k in keys:
        found.add(next((p for p in record_prefixes(k) if p not in present), k))
    return sorted(found)


def same_value(a, b, rtol):
    if isinstance(a, str) and isinstance(b, str):
        return same_string(a, b, rtol)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return same_number(a, b, rtol)
    return a == b


def rounding_bias(records, key):
    """The float-rounding bias bound the run derived for the integral whose
    estimate is `key` (its `bias`, less the model's documented tolerance,
    which bounds the model against the truth, not one device against
    another), or None where the record states none."""
    rec = key[:-len(".estimate")]
    bias = records.get(rec + ".bias")
    if not isinstance(bias, (int, float)) or isinstance(bias, bool):
        return None
    group = f"run.groups{{check={records.get(rec + '.check')} model={records.get(rec + '.model')}}}"
    tolerance, expected = records.get(group + ".tolerance", 0.0), records.get(rec + ".expected", 0.0)
    if isinstance(tolerance, (int, float)) and isinstance(expected, (int, float)):
        bias -= tolerance * abs(expected)
    return max(bias, records.get(rec + ".rounding_bound", 0.0) or 0.0)


def pooled_bias(records, key):
    """A pooled mean deviation's bias bound, for groups without a tolerance (bias_bound is then rounding alone)."""
    group = key[:-len(".pooled.mean_deviation")]
    if records.get(group + ".tolerance") != 0.0:
        return None
    return records.get(group + ".pooled.bias_bound")


def cross_device_bounds(before, after):
    """{key: bound} for the numbers two devices must still agree on: each
    estimate (and pooled mean deviation) lies within its derived rounding
    bias of the exact value of the same samples on either device, so the two
    differ by at most the sum of both biases. Every other number is a
    statistic of the device's own rounding (ulps, worst relative errors,
    standard errors of rounded values) and is compared in neither direction."""
    bounds = {}
    for key in before.keys() & after.keys():
        if key.startswith("run.results{") and key.endswith("}.estimate"):
            pair = rounding_bias(before, key), rounding_bias(after, key)
        elif key.startswith("run.groups{") and key.endswith("}.pooled.mean_deviation"):
            pair = pooled_bias(before, key), pooled_bias(after, key)
        else:
            continue
        if None not in pair:
            bounds[key] = pair[0] + pair[1]
    return bounds


def differences(before, after, rtol, bounds=None):
    """{'added': records, 'removed': records, 'changed': 'key: a -> b' lines}.
    `bounds` (another device): numbers are compared only where it names a
    derived bound, within that bound; strings by their words, integers and
    verdicts exactly. The device's own name is never a difference."""
    def same(k):
        a, b = before[k], after[k]
        if bounds is None:
            return same_value(a, b, rtol)
        if isinstance(a, float) and isinstance(b, float) and not (math.isnan(a) or math.isnan(b)):
            return k not in bounds or abs(a - b) <= bounds[k]
        return same_value(a, b, math.inf)

    keys_before, keys_after = before.keys() - {DEVICE_KEY}, after.keys() - {DEVICE_KEY}
    return {
        "added": whole_records(keys_after - keys_before, keys_before),
        "removed": whole_records(keys_before - keys_after, keys_after),
        "changed": [f"{k}: {before[k]!r} -> {after[k]!r}" for k in sorted(keys_before & keys_after) if not same(k)],
    }


def report(before, after, rtol, limit):
    """Prints the differences of two record sets; returns (exit code, differences)."""
    bounds = None
    if before.get(DEVICE_KEY) != after.get(DEVICE_KEY):
        # another CPU (another vector width, another builtin) rounds in other
        # last bits: what the numbers decide is compared exactly (verdicts,
        # counts, exit codes, the words of every message), estimates within
        # their derived rounding bounds, and the rest not
        bounds = cross_device_bounds(before, after)
        print(f"records: devices differ ({before.get(DEVICE_KEY)!r} vs {after.get(DEVICE_KEY)!r}): "
              f"comparing verdicts, counts and messages exactly and {len(bounds)} estimates within their "
              "derived rounding bounds")
    diff = differences(before, after, rtol, bounds)
    tol = "derived bounds" if bounds is not None else f"rtol {rtol:g}"
    print(f"records: {len(before)} values before, {len(after)} after: {len(diff['added'])} records added, "
          f"{len(diff['removed'])} removed, {len(diff['changed'])} values changed ({tol})")
    for kind in ("added", "removed", "changed"):
        for line in diff[kind][:limit]:
            print(f"  {kind}: {line}")
        if len(diff[kind]) > limit:
            print(f"  ... and {len(diff[kind]) - limit} more {kind}")
    return (1 if any(diff.values()) else 0), diff


def compare(before_path, after_path, rtol, limit):
    before, after = (json.load(gzip.open(p, "rt")) for p in (before_path, after_path))
    return report(before, after, rtol, limit)[0]


def inserted_record(records):
    """A copy of `records` with one run group inserted: a new model's copy of the first group."""
    first = next(p for k in sorted(records) if k.startswith("run.groups{") for p in record_prefixes(k)[:1])
    new = first.replace("model=", "model=inserted_", 1)
    out = dict(records)
    out.update({new + k[len(first):]: v for k, v in records.items() if k.startswith(first)})
    return out


def selftest(golden):
    """compare must fail on a changed verdict, a value moved by 1e-4, a lost
    record and an inserted one (reported as one record added, nothing
    changed), and pass a value moved within rounding; across two device
    names it must pass the same findings and fail a changed verdict, count,
    record or an estimate beyond its derived bound; flatten must key a
    list's records by identity, so an insertion shifts nothing."""
    base = json.load(gzip.open(golden, "rt"))
    verdict = next(k for k, v in base.items() if k.endswith(".verdict") and v == "pass")
    estimate = next(k for k, v in base.items() if k.endswith(".estimate") and isinstance(v, float) and v > 0)
    cases = {
        "a verdict changed": (lambda r: r.__setitem__(verdict, "FAIL"), 1, (0, 0, 1)),
        "an estimate moved by 1e-4": (lambda r: r.__setitem__(estimate, r[estimate] * (1 + 1e-4)), 1, (0, 0, 1)),
        "a record lost": (lambda r: r.pop(verdict), 1, (0, 1, 0)),
        "a record inserted": (lambda r: r.update(inserted_record(r)), 1, (1, 0, 0)),
        "an estimate moved by 1e-6 (rounding)": (lambda r: r.__setitem__(estimate, r[estimate] * (1 + 1e-6)), 0,
                                                 (0, 0, 0)),
    }
    # Another device (an AVX2 CPU against the golden's AVX-512 one): its name
    # is no difference; verdicts, counts and words still are; an estimate may
    # move within its derived rounding bound and not beyond; a statistic of
    # the device's own rounding (a stability region's max_ulps) may move.
    other = lambda r: r.__setitem__(DEVICE_KEY, "pthread-haswell-AMD EPYC | OpenCL 3.0 PoCL HSTR: pthread-haswell | x")
    bounded = next(k for k, v in sorted(base.items()) if k.startswith("run.results{") and k.endswith(".estimate")
                   and (rounding_bias(base, k) or 0) > 0)
    bias = rounding_bias(base, bounded)
    ulps = next(k for k, v in base.items() if k.endswith(".max_ulps") and isinstance(v, float) and v > 0)
    count = next(k for k, v in base.items() if k.endswith(".failures") and isinstance(v, int))

    def moved(key, by):
        return lambda r: (other(r), r.__setitem__(key, r[key] + by))

    cases.update({
        "another device, the same findings": (other, 0, (0, 0, 0)),
        "another device, a verdict changed": (lambda r: (other(r), r.__setitem__(verdict, "FAIL")), 1, (0, 0, 1)),
        "another device, a count changed": (moved(count, 1), 1, (0, 0, 1)),
        "another device, an estimate moved within its derived bound": (moved(bounded, 1.5 * bias), 0, (0, 0, 0)),
        "another device, an estimate moved beyond its derived bound": (moved(bounded, 2.5 * bias), 1, (0, 0, 1)),
        "another device, a rounding statistic moved": (moved(ulps, 3.0), 0, (0, 0, 0)),
        "another device, a record lost": (lambda r: (other(r), r.pop(verdict)), 1, (0, 1, 0)),
    })
    failed = 0
    for name, (change, want, counts) in cases.items():
        r = dict(base)  # values are scalars: a shallow copy is a copy
        change(r)
        got, diff = report(base, r, 1e-5, 3)
        got_counts = tuple(len(diff[k]) for k in ("added", "removed", "changed"))
        print(f"selftest: {name}: compare exits {got} (want {want}); added/removed/changed {got_counts} "
              f"(want {counts})")
        failed += got != want or got_counts != counts
    # flatten: a group inserted before others keys nothing else differently
    groups = [{"check": "energy", "model": m, "verdict": "pass", "params": {"a": 0.5, "worst_pair": "x"}}
              for m in ("b", "c")]
    old, new = {}, {}
    flatten({"groups": groups}, "run", old)
    flatten({"groups": [dict(groups[0], model="a")] + groups}, "run", new)
    diff = differences(old, new, 1e-5)
    ok = diff == {"added": ["run.groups{check=energy model=a params=a=0.5}"], "removed": [], "changed": []}
    print(f"selftest: flatten keys records by identity: {'ok' if ok else 'NO: ' + repr(diff)}")
    failed += not ok
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
