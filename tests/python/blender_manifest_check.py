"""Checks the Blender 4.2+ extension manifest (blender/adaptex_blender/blender_manifest.toml) against
the rules of Blender's manifest schema 1.0.0, as `blender --command extension validate` would (no
Blender >= 4.2 here: Debian 12 has 3.4), and the add-on zip blender/make_zip.py makes: the manifest
in the add-on's folder, the VERSION file's version in the manifest and in bl_info.

usage: blender_manifest_check.py [ZIP]   (ZIP: a zip made by make_zip.py, also checked)"""
import ast
import os
import re
import sys
import tomllib
import zipfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
ADDON_TAGS = {"3D View", "Add Curve", "Add Mesh", "Animation", "Bake", "Camera", "Compositing", "Development",
              "Game Engine", "Geometry Nodes", "Grease Pencil", "Import-Export", "Lighting", "Material",
              "Modeling", "Mesh", "Node", "Object", "Paint", "Pipeline", "Physics", "Render", "Rigging",
              "Scene", "Sculpt", "Sequencer", "System", "Text Editor", "Tracking", "User Interface", "UV"}
PERMISSIONS = {"files", "network", "clipboard", "camera", "microphone"}
SEMVER = re.compile(r"^(0|[1-9]\d*)\.(0|[1-9]\d*)\.(0|[1-9]\d*)$")


def fail(what):
    print("FAIL:", what)
    sys.exit(1)


def check(cond, what):
    if not cond:
        fail(what)


def text_rule(value, what, limit):
    check(isinstance(value, str) and value.strip() == value and 0 < len(value) <= limit, f"{what}: 1-{limit} chars")
    check(value[-1] not in ".!?,;:", f"{what} must not end with punctuation: {value!r}")


def check_manifest(m, version):
    required = {"schema_version": str, "id": str, "version": str, "name": str, "tagline": str, "maintainer": str,
                "type": str, "blender_version_min": str, "license": list}
    for key, kind in required.items():
        check(isinstance(m.get(key), kind), f"{key}: missing or not a {kind.__name__}")
    known = set(required) | {"website", "tags", "blender_version_max", "copyright", "platforms", "wheels",
                             "permissions", "build"}
    check(set(m) <= known, f"unknown keys {set(m) - known}")
    check(m["schema_version"] == "1.0.0", m["schema_version"])
    check(m["id"].isidentifier() and not m["id"].startswith("_") and m["id"].lower() == m["id"], f"id {m['id']!r}")
    check(SEMVER.match(m["version"]) and m["version"] == version, f"version {m['version']} (VERSION: {version})")
    text_rule(m["name"], "name", 64)
    text_rule(m["tagline"], "tagline", 64)
    check(m["type"] == "add-on", m["type"])
    parts = m["blender_version_min"].split(".")
    check(len(parts) == 3 and all(p.isdigit() for p in parts) and tuple(map(int, parts)) >= (4, 2, 0),
          f"blender_version_min {m['blender_version_min']} (extensions start at 4.2.0)")
    check(m["license"] and all(isinstance(x, str) and x.startswith("SPDX:") for x in m["license"]), m["license"])
    check(set(m.get("tags", [])) <= ADDON_TAGS, f"tags not in Blender's list: {set(m.get('tags', [])) - ADDON_TAGS}")
    for key, reason in m.get("permissions", {}).items():
        check(key in PERMISSIONS, f"permission {key}")
        text_rule(reason, f"permission {key}'s reason", 64)
    build = m.get("build", {})
    check(set(build) <= {"paths", "paths_exclude_pattern"}, f"build keys {set(build)}")
    check(all(isinstance(p, str) for p in build.get("paths_exclude_pattern", [])), "paths_exclude_pattern")


def bl_info_version(source):
    for node in ast.parse(source).body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "bl_info":
            return ".".join(map(str, ast.literal_eval(node.value)["version"]))
    fail("no bl_info")


def main():
    with open(os.path.join(ROOT, "VERSION")) as f:
        version = f.read().strip()
    addon = os.path.join(ROOT, "blender", "adaptex_blender")
    with open(os.path.join(addon, "blender_manifest.toml"), "rb") as f:
        check_manifest(tomllib.load(f), version)
    with open(os.path.join(addon, "__init__.py"), encoding="utf-8") as f:
        check(bl_info_version(f.read()) == version, "bl_info's version is not VERSION's")
    if len(sys.argv) > 1:
        with zipfile.ZipFile(sys.argv[1]) as z:
            names = z.namelist()
            check({"adaptex_blender/__init__.py", "adaptex_blender/blender_manifest.toml"} <= set(names), names)
            check(all(n.startswith("adaptex_blender/") for n in names), "one folder in the zip")
            check_manifest(tomllib.loads(z.read("adaptex_blender/blender_manifest.toml").decode()), version)
            check(bl_info_version(z.read("adaptex_blender/__init__.py").decode()) == version, "zip's bl_info")
    print("blender manifest: OK", version)


if __name__ == "__main__":
    main()
