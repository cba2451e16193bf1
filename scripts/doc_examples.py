#!/usr/bin/env python3
"""Runs the Python examples of the docs, so that they cannot rot (ctest: docs_examples).

An example is a ```python block right after the line `<!-- example -->` in README.md or
docs/python.md. Each runs in a scratch folder holding `demo-output/`, written first by
`adaptex demo` (what the quick start's scripts/demo.sh writes). Then:
- a line "It printed `...`" after the block gives the numbers the example prints: each must be
  within --tolerance of what it prints now (PSNRs in dB: 0.1 by default);
- a picture `![...](images/NAME.png)` after the block, NAME.png being a file the example wrote, must
  be in docs/images; --update-images copies the new one there (this is how the doc pictures are made).

usage: doc_examples.py --cli ADAPTEX [--module DIR] [--tolerance DB] [--update-images] [--keep DIR]
Exit codes: 0 all examples ran and match, 1 a mismatch or a failure, 77 matplotlib or numpy missing.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
DOCS = ["README.md", os.path.join("docs", "python.md")]
NUMBER = re.compile(r"-?\d+(?:\.\d+)?")


def examples(doc):
    """(code, expected numbers or None, pictures) of every marked block of \\p doc."""
    text = open(os.path.join(ROOT, doc), encoding="utf-8").read()
    found = []
    for m in re.finditer(r"<!-- example -->\n```python\n(.*?)```\n", text, re.S):
        rest = text[m.end():]
        nxt = rest.find("<!-- example -->")
        rest = rest if nxt < 0 else rest[:nxt]
        rest = rest.split("\n## ", 1)[0]  # up to the next section
        printed = re.search(r"printed `([^`]*)`", rest)
        pictures = re.findall(r"!\[[^\]]*\]\((?:docs/)?images/([^)]+\.png)\)", rest)
        found.append((m.group(1), NUMBER.findall(printed.group(1)) if printed else None, pictures))
    return found


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", required=True)
    ap.add_argument("--module", default="")
    ap.add_argument("--tolerance", type=float, default=0.1)
    ap.add_argument("--update-images", action="store_true")
    ap.add_argument("--keep", default="")
    a = ap.parse_args()
    for name, package in (("numpy", "python3-numpy"), ("matplotlib", "python3-matplotlib")):
        try:
            __import__(name)
        except ImportError:
            print(f"SKIP: {name} is not installed for {sys.executable} (Debian package {package}; scripts/setup.sh)")
            sys.exit(77)
    env = dict(os.environ, MPLBACKEND="Agg")
    if a.module:
        env["PYTHONPATH"] = os.path.abspath(a.module) + os.pathsep + env.get("PYTHONPATH", "")
    failures = 0
    with tempfile.TemporaryDirectory(prefix="adaptex-docs-") as tmp:
        work = a.keep or tmp
        os.makedirs(work, exist_ok=True)
        subprocess.run([os.path.abspath(a.cli), "-q", "demo", "-o", "demo-output"], cwd=work, check=True, stdout=subprocess.DEVNULL)
        for doc in DOCS:
            for k, (code, expected, pictures) in enumerate(examples(doc)):
                label = f"{doc} example {k + 1}"
                r = subprocess.run([sys.executable, "-c", code], cwd=work, env=env, capture_output=True, text=True)
                if r.returncode != 0:
                    print(f"FAIL {label}: exit {r.returncode}\n{r.stderr[-3000:]}")
                    failures += 1
                    continue
                got = NUMBER.findall(r.stdout)
                if expected is not None:
                    ok = len(got) == len(expected) and all(
                        abs(float(x) - float(y)) <= a.tolerance for x, y in zip(got, expected))
                    print(f"{'ok  ' if ok else 'FAIL'} {label}: prints {r.stdout.strip()}, the doc says "
                          f"{', '.join(expected)} (tolerance {a.tolerance})")
                    failures += not ok
                else:
                    print(f"ok   {label}: ran")
                for picture in pictures:
                    made = os.path.join(work, picture)
                    if not os.path.exists(made):
                        continue
                    target = os.path.join(ROOT, "docs", "images", picture)
                    if a.update_images:
                        shutil.copyfile(made, target)
                        print(f"     {label}: wrote docs/images/{picture}")
                    elif not os.path.exists(target):
                        print(f"FAIL {label}: docs/images/{picture} is missing (run with --update-images)")
                        failures += 1
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
