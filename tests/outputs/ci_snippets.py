#!/usr/bin/env python3
"""CTest ci_snippets: the CI snippets of docs/ci/ are valid YAML with the
structure GitHub Actions and GitLab CI need (results/ uploaded and junit.xml
reported even when a check fails), and their mfv command lines run: each is
executed in a scratch folder with the snippet's variables pointed at the
repository's examples, and must exit 0 and write junit.xml.
Usage: ci_snippets.py MFV_BIN_DIR SOURCE_DIR"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

import yaml

BIN, SRC = sys.argv[1], sys.argv[2]
failures = []


def need(cond, what):
    if not cond:
        failures.append(what)


def mfv_lines(script):
    """The lines of a run:/script: block that call mfv."""
    text = "\n".join(script) if isinstance(script, list) else script
    return [line.strip() for line in text.splitlines() if re.match(r"\s*mfv\s", line)]


with open(os.path.join(SRC, "docs/ci/github-actions.yml")) as f:
    gh = yaml.safe_load(f)
with open(os.path.join(SRC, "docs/ci/gitlab-ci.yml")) as f:
    gl = yaml.safe_load(f)

# GitHub Actions: one job whose steps run mfv, upload results/, report junit
steps = [s for job in gh["jobs"].values() for s in job["steps"]]
gh_cmds = [c for s in steps if "run" in s for c in mfv_lines(s["run"])]
upload = [s for s in steps if s.get("uses", "").startswith("actions/upload-artifact")]
junit = [s for s in steps if "junit" in s.get("uses", "")]
need(upload and upload[0]["with"]["path"].rstrip("/") == "results" and upload[0].get("if") == "always()",
     "github: results/ is not uploaded always")
need(junit and "junit.xml" in junit[0]["with"]["report_paths"] and junit[0].get("if") == "always()",
     "github: junit.xml is not reported always")
need(any("run --scene" in c for c in gh_cmds) and any(c.startswith("mfv check") for c in gh_cmds),
     "github: needs both mfv run --scene and mfv check")

# GitLab CI: jobs extending .mfv, artifacts results/ always, junit reports
base = gl[".mfv"]
need(base["artifacts"]["when"] == "always" and "results/" in base["artifacts"]["paths"],
     "gitlab: results/ is not kept always")
gl_cmds = []
for name, job in gl.items():
    if isinstance(job, dict) and "script" in job:
        gl_cmds += mfv_lines(job["script"])
        need(job["artifacts"]["reports"]["junit"].endswith("junit.xml"), f"gitlab: {name} reports no junit.xml")
need(any("run --scene" in c for c in gl_cmds) and any(c.startswith("mfv check") for c in gl_cmds),
     "gitlab: needs both mfv run --scene and mfv check")
need(sorted(gh_cmds) == sorted(gl_cmds), "github and gitlab snippets run different mfv commands")

# Run the commands as the CI would, on the repository's examples.
with tempfile.TemporaryDirectory(prefix="mfv_ci_") as work:
    os.makedirs(os.path.join(work, "assets"))
    os.makedirs(os.path.join(work, "shaders"))
    shutil.copy(os.path.join(SRC, "tests/data/materials.json"), os.path.join(work, "assets/materials.json"))
    shutil.copy(os.path.join(SRC, "examples/brdf/ggx.cl"), os.path.join(work, "shaders/brdf.cl"))
    env = dict(os.environ, PATH=BIN + os.pathsep + os.environ["PATH"], MFV_SCENE="assets/materials.json",
               MFV_BRDF="shaders/brdf.cl", MFV_ARGS="--quiet --samples 1024")
    for cmd in gh_cmds:
        p = subprocess.run(["bash", "-c", cmd], cwd=work, env=env, capture_output=True, text=True)
        need(p.returncode == 0, f"{cmd}: exit {p.returncode}\n{p.stdout[-1500:]}{p.stderr[-1500:]}")
        out = re.search(r"--out (\S+)", cmd).group(1)
        need(os.path.isfile(os.path.join(work, out, "junit.xml")), f"{cmd}: no {out}/junit.xml")
        print(f"ran: {cmd} -> exit {p.returncode}")

for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
