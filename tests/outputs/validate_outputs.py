#!/usr/bin/env python3
"""CTest output_schemas: runs every mfv command that writes JSON at a tiny
size into a temporary folder and validates each output against its schema in
schemas/ (python3-jsonschema), and each junit.xml against the structure CI
systems read (a time on every testcase and suite, xfail as <skipped message>,
names "MODEL x CHECK"), and that every plot comes as PNG and SVG.
Usage: validate_outputs.py MFV SOURCE_DIR"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import jsonschema

MFV, SRC = sys.argv[1], sys.argv[2]
failures = []


def run(args, expect=(0,)):
    p = subprocess.run([MFV, "--quiet"] + args, capture_output=True, text=True, cwd=SRC)
    if p.returncode not in expect:
        failures.append(f"mfv {' '.join(args)}: exit {p.returncode}\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    return p


def validate(path, schema_name):
    with open(os.path.join(SRC, "schemas", schema_name + ".schema.json")) as f:
        schema = json.load(f)
    try:
        with open(path) as f:
            doc = json.load(f)
        jsonschema.validate(doc, schema)
        print(f"ok {os.path.basename(os.path.dirname(path))}/{os.path.basename(path)} against {schema_name}")
    except Exception as e:  # noqa: BLE001 - every failure is reported, the test fails below
        failures.append(f"{path} against {schema_name}: {str(e)[:1500]}")


def check_junit(path, want_skipped):
    root = ET.parse(path).getroot()
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    if root.tag != "testsuites" or not suites:
        failures.append(f"{path}: root is {root.tag}, no testsuite")
    skipped = 0
    for s in suites:
        cases = s.findall("testcase")
        for attr in ("name", "tests", "failures", "time"):
            if s.get(attr) is None:
                failures.append(f"{path}: testsuite without {attr}")
        if int(s.get("tests", -1)) != len(cases):
            failures.append(f"{path}: tests={s.get('tests')} but {len(cases)} testcases")
        if int(s.get("failures", -1)) != sum(1 for c in cases if c.find("failure") is not None):
            failures.append(f"{path}: failures attribute does not count the <failure> elements")
        for c in cases:
            try:
                float(c.get("time"))
            except (TypeError, ValueError):
                failures.append(f"{path}: testcase {c.get('name')} has no numeric time")
            if c.get("classname") != "mfv.reference" and " × " not in c.get("name", ""):
                failures.append(f"{path}: testcase name {c.get('name')!r} is not 'MODEL × CHECK'")
            sk = c.find("skipped")
            if sk is not None:
                skipped += 1
                if not sk.get("message", "").startswith("expected failure: "):
                    failures.append(f"{path}: <skipped> without the reason in message")
        if int(s.get("skipped", -1)) != sum(1 for c in cases if c.find("skipped") is not None):
            failures.append(f"{path}: skipped attribute does not count the <skipped> elements")
    if want_skipped and skipped == 0:
        failures.append(f"{path}: an expected failure should be a <skipped> testcase")
    print(f"ok {path}: {skipped} skipped")
    return root


def check_plot_pairs(folder):
    """Every plot comes as PNG and SVG."""
    pngs = sorted(f for f in os.listdir(folder) if f.endswith(".png"))
    if not pngs:
        failures.append(f"{folder}: no PNG plots")
    for f in pngs:
        with open(os.path.join(folder, f), "rb") as img:
            if img.read(4) != b"\x89PNG":
                failures.append(f"{folder}/{f} is not a PNG")
        if not os.path.isfile(os.path.join(folder, f[:-4] + ".svg")):
            failures.append(f"{folder}/{f} has no SVG twin")


have_gnuplot = shutil.which("gnuplot") is not None

with tempfile.TemporaryDirectory(prefix="mfv_schemas_") as d:
    o = lambda name: os.path.join(d, name)  # noqa: E731
    # beckmann_ct82 must fail d_norm: an xfail, so junit.xml holds a <skipped>
    listing = run(["list", "--json"])
    with open(o("list.json"), "w") as f:
        f.write(listing.stdout)
    validate(o("list.json"), "mfv-list-1")
    run(["run", "--check", "d_norm", "furnace", "--model", "ggx/smith_ggx_correlated", "beckmann_ct82",
         "--samples", "512", "--out", o("run")])
    validate(o("run/results.json"), "mfv-run-1")
    check_junit(o("run/junit.xml"), want_skipped=True)
    run(["run", "--scene", "tests/data/materials.json", "--check", "d_norm", "furnace", "--samples", "512",
         "--out", o("scene")])
    validate(o("scene/results.json"), "mfv-run-1")
    root = check_junit(o("scene/junit.xml"), want_skipped=False)
    with open(os.path.join(SRC, "tests/data/materials.json")) as f:
        names = [m["name"] for m in json.load(f)["materials"]]
    if not any(n in c.get("name", "") for c in root.iter("testcase") for n in names):
        failures.append("scene junit.xml: no testcase names a material")
    run(["check", "--brdf", "examples/brdf/ggx.cl", "--check", "furnace", "--samples", "512", "--out", o("check")])
    validate(o("check/results.json"), "mfv-run-1")
    check_junit(o("check/junit.xml"), want_skipped=False)
    run(["energy", "--models", "ggx/smith_ggx_correlated", "lambert[", "--grid", "4x4", "--max-points", "1024",
         "--out", o("energy")])
    validate(o("energy/energy.json"), "mfv-energy-1")
    if have_gnuplot:
        check_plot_pairs(o("energy/plots"))
    run(["stability", "--only", "D ggx", "--terms-only", "--out", o("stability")])
    validate(o("stability/stability.json"), "mfv-stability-1")
    if have_gnuplot:
        check_plot_pairs(o("stability"))
    run(["agree", "--samples", "200", "--only", "ggx", "--out", o("agree")])
    validate(o("agree/agree.json"), "mfv-agree-1")
    run(["bench", "--integrand", "d_norm", "--integrals", "4", "--samples", "4096", "--ref-samples", "256",
         "--repeats", "1", "--out", o("bench")])
    validate(o("bench/bench.json"), "mfv-bench-1")
    run(["samplers", "--samples", "65536", "--bins", "16x32", "--device-only", "--plots", "--out", o("samplers")])
    validate(o("samplers/samplers.json"), "mfv-samplers-1")
    if have_gnuplot:
        check_plot_pairs(o("samplers/plots"))
    run(["convergence", "--case", "ggx:0.1:1", "--check", "d_norm", "--estimator", "mis", "--min-log2", "7",
         "--max-log2", "9", "--ref-max-log2", "8", "--replicates", "2", "--out", o("convergence")])
    validate(o("convergence/convergence.json"), "mfv-convergence-1")
    if have_gnuplot:
        check_plot_pairs(o("convergence/plots"))

for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
