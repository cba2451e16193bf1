"""Runs the headless Blender test of the add-on (blender_addon_test.py) with one backend.
Exits 77 (ctest SKIP) with a message when blender (or, for MODULE, the Python module) is absent.

usage: run_blender.py BACKEND(MODULE|CLI) MODULE_DIR CLI [SCRIPT (default blender_addon_test.py)]"""
import os
import shutil
import subprocess
import sys
import tempfile
import zipfile


def main():
    which, module_dir, cli = sys.argv[1:4]
    script = sys.argv[4] if len(sys.argv) > 4 else "blender_addon_test.py"
    blender = shutil.which("blender")
    if blender is None:
        print("SKIP: blender is not installed (Debian package blender; scripts/setup.sh)")
        sys.exit(77)
    if which == "MODULE" and not os.path.isdir(os.path.join(module_dir, "adaptex")):
        print("SKIP: the Python module was not built; the CLI backend is tested by blender_addon_cli")
        sys.exit(77)
    here = os.path.dirname(os.path.abspath(__file__))
    addon = os.path.join(here, "..", "..", "blender", "adaptex_blender")
    with tempfile.TemporaryDirectory(prefix="adaptex-blender-") as tmp:
        zip_path = os.path.join(tmp, "adaptex_blender.zip")
        with zipfile.ZipFile(zip_path, "w") as z:
            for name in sorted(os.listdir(addon)):
                if name.endswith(".py"):
                    z.write(os.path.join(addon, name), "adaptex_blender/" + name)
        env = dict(os.environ, BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"),
                   BLENDER_USER_CONFIG=os.path.join(tmp, "config"))
        env.pop("PYTHONPATH", None)  # the add-on must find the module through its preferences
        cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1",
               "--python", os.path.join(here, script), "--", zip_path, which, module_dir, cli, tmp]
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        print(r.stdout[-6000:], r.stderr[-4000:])
        ok = r.returncode == 0 and ("ADAPTEX_BLENDER_OK " + which) in r.stdout
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
