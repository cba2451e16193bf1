"""`cmake --install BUILD --prefix P` (its cli, python and blender components) into a scratch folder, then the headless Blender test of the add-on
(blender_addon_test.py) with the zip the install produced, no preferences set, the adaptex CLI not on
PATH and no PYTHONPATH: the add-on must find the installed module (and CLI) by itself. Exits 77 (ctest
SKIP) with a message when blender or the module is absent.

usage: run_blender_installed.py BUILD_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile


def main():
    build = sys.argv[1]
    blender = shutil.which("blender")
    if blender is None:
        print("SKIP: blender is not installed (Debian package blender; scripts/setup.sh)")
        sys.exit(77)
    here = os.path.dirname(os.path.abspath(__file__))
    with tempfile.TemporaryDirectory(prefix="adaptex-installed-") as tmp:
        prefix = os.path.join(tmp, "prefix")
        for component in ("cli", "python", "blender"):  # what the add-on uses (the same rules as a full install)
            r = subprocess.run(["cmake", "--install", build, "--prefix", prefix, "--component", component],
                               capture_output=True, text=True)
            print(r.stdout[-2000:], r.stderr[-2000:])
            assert r.returncode == 0, "cmake --install failed"
        zip_path = os.path.join(prefix, "share", "adaptex", "adaptex_blender.zip")
        cli = os.path.join(prefix, "bin", "adaptex")
        assert os.path.isfile(zip_path) and os.access(cli, os.X_OK), (zip_path, cli)
        modules = [d for d, _, files in os.walk(prefix) if os.path.basename(d) == "adaptex" and "__init__.py" in files]
        if not modules:
            print("SKIP: the Python module is not part of this build (ADAPTEX_PYTHON off)")
            sys.exit(77)
        # Nothing points at the install: no adaptex on PATH, no ADAPTEX_CLI, no PYTHONPATH.
        path = [d for d in os.environ.get("PATH", "").split(os.pathsep)
                if d and not os.path.exists(os.path.join(d, "adaptex"))]
        env = dict(os.environ, PATH=os.pathsep.join(path), BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"),
                   BLENDER_USER_CONFIG=os.path.join(tmp, "config"))
        for k in ("PYTHONPATH", "ADAPTEX_CLI"):
            env.pop(k, None)
        cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
               os.path.join(here, "blender_addon_test.py"), "--", zip_path, "INSTALLED", "", cli, tmp]
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        print(r.stdout[-6000:], r.stderr[-4000:])
        sys.exit(0 if r.returncode == 0 and "ADAPTEX_BLENDER_OK MODULE" in r.stdout else 1)


if __name__ == "__main__":
    main()
