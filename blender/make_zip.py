#!/usr/bin/env python3
"""Makes the add-on's zip: one zip that Blender 3.x installs as an add-on (bl_info) and Blender
4.2+ as an extension (blender_manifest.toml in its folder). The version in both is the project's
VERSION file. With --cli / --module-dir (what `cmake --install` passes), the zip also records where
the CLI and the Python module were installed, so that the add-on finds them with no configuration.

usage: make_zip.py OUT.zip [--cli PATH] [--module-dir DIR]"""
import argparse
import os
import re
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
ADDON = os.path.join(HERE, "adaptex_blender")
FILES = ["__init__.py", "backend.py", "meshdata.py", "blender_manifest.toml"]


def version():
    with open(os.path.join(HERE, "..", "VERSION")) as f:
        return f.read().strip()


def stamped(name, text, v):
    """\\p text of the add-on's file \\p name with the version \\p v written in."""
    if name == "__init__.py":
        parts = ", ".join(str(int(x)) for x in v.split("."))
        text, n = re.subn(r'("version": )\([0-9, ]*\)', rf"\g<1>({parts})", text, count=1)
    elif name == "blender_manifest.toml":
        text, n = re.subn(r'(?m)^version = "[^"]*"', f'version = "{v}"', text, count=1)
    else:
        return text
    if n != 1:
        raise SystemExit(f"make_zip.py: no version to write in {name}")
    return text


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--cli", default="")
    ap.add_argument("--module-dir", default="")
    a = ap.parse_args()
    v = version()
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    tmp = a.out + ".tmp"
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for name in FILES:
            with open(os.path.join(ADDON, name), encoding="utf-8") as f:
                z.writestr("adaptex_blender/" + name, stamped(name, f.read(), v))
        if a.cli or a.module_dir:
            z.writestr("adaptex_blender/_install.py",
                       '"""Where `cmake --install` put adaptex (written by blender/make_zip.py)."""\n'
                       f"CLI = {a.cli!r}\nMODULE_DIR = {a.module_dir!r}\n")
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
