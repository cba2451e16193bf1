"""The exported .glb files pass the Khronos glTF Validator (npm gltf-validator) with 0 errors and 0
warnings: a layered material (stroke file version 2: baseColor, metallicRoughness, normal, with the
TANGENT attribute its normal map was baked for) and a version 1 paint.
Exits 77 (ctest SKIP) with a message when node or the validator is missing (scripts/setup.sh installs
it under ~/.cache/adaptex/npm).

usage: gltf_validate.py ADAPTEX_CLI
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile


def skip(message):
    print("SKIP: " + message)
    sys.exit(77)


def sphere_obj(path, slices=32, stacks=16):
    lines = ["v 0 0 1"]
    for i in range(1, stacks):
        t = math.pi * i / stacks
        for j in range(slices):
            p = 2 * math.pi * j / slices
            lines.append(f"v {math.sin(t) * math.cos(p):.9f} {math.sin(t) * math.sin(p):.9f} {math.cos(t):.9f}")
    lines.append("v 0 0 -1")
    ring = lambda i, j: 2 + (i - 1) * slices + j % slices  # noqa: E731 (1-based OBJ index)
    bottom = 2 + (stacks - 1) * slices
    for j in range(slices):
        lines.append(f"f 1 {ring(1, j)} {ring(1, j + 1)}")
        for i in range(1, stacks - 1):
            a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
            lines += [f"f {a} {b} {c}", f"f {a} {c} {d}"]
        lines.append(f"f {ring(stacks - 1, j)} {bottom} {ring(stacks - 1, j + 1)}")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    cli = sys.argv[1]
    node = shutil.which("node")
    npm_dir = os.environ.get("ADAPTEX_NPM_DIR") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "adaptex", "npm")
    validator = os.path.join(npm_dir, "node_modules", "gltf-validator")
    if not node:
        skip("node is not installed")
    if not os.path.isdir(validator):
        skip(f"the npm package gltf-validator is not in {npm_dir} (scripts/setup.sh installs it)")
    with tempfile.TemporaryDirectory() as tmp:
        mesh = os.path.join(tmp, "s.obj")
        sphere_obj(mesh)
        run = lambda *args: subprocess.run([cli, *args], check=True, capture_output=True, text=True)  # noqa: E731
        run("strokes", "generate", mesh, "--kind", "material", "--seed", "3", "-o", os.path.join(tmp, "m.json"))
        run("paint", mesh, "--strokes", os.path.join(tmp, "m.json"), "--size", "128", "-o", os.path.join(tmp, "mat"))
        run("strokes", "generate", mesh, "--kind", "mixed", "-o", os.path.join(tmp, "v1.json"))
        run("paint", mesh, "--strokes", os.path.join(tmp, "v1.json"), "--size", "128", "--adapt", "none", "-o",
            os.path.join(tmp, "v1"))
        script = ("const v = require(process.argv[1]); const fs = require('fs');"
                  "v.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])))"
                  ".then(r => console.log(JSON.stringify(r.issues)))"
                  ".catch(e => { console.error(String(e)); process.exit(1); });")
        failed = False
        for name in ("mat", "v1"):
            glb = os.path.join(tmp, name, "s.glb")
            out = subprocess.run([node, "-e", script, validator, glb], check=True, capture_output=True, text=True)
            issues = json.loads(out.stdout)
            errors = [m for m in issues.get("messages", []) if m.get("severity") == 0]
            for m in issues.get("messages", []):
                if m.get("severity") == 1:
                    print(f"  warning {m.get('code')}: {m.get('message')}")
            print(f"{name}: {issues['numErrors']} errors, {issues['numWarnings']} warnings, "
                  f"{issues['numInfos']} infos")
            for m in errors:
                print(f"  error {m.get('code')}: {m.get('message')} at {m.get('pointer')}")
            failed |= issues["numErrors"] != 0 or issues["numWarnings"] != 0
    print("some .glb file has validator errors or warnings" if failed else "both .glb files: 0 errors, 0 warnings")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
