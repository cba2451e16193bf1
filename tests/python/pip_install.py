"""`pip install .` in a fresh virtual environment, offline (PIP_NO_INDEX=1), then the installed
package and CLI: adaptex.__version__ and `adaptex --version` are the VERSION file's, and a call
works from outside the source tree. Exits 77 (ctest SKIP) when the interpreter cannot make a venv
with pip (Debian: python3-venv).

usage: pip_install.py PYTHON SOURCE_DIR BUILD_DIR [CMAKE_ARGS]"""
import os
import subprocess
import sys
import tempfile


def main():
    python, source, build = sys.argv[1:4]
    cmake_args = sys.argv[4] if len(sys.argv) > 4 else ""
    with open(os.path.join(source, "VERSION")) as f:
        version = f.read().strip()
    with tempfile.TemporaryDirectory(prefix="adaptex-pip-") as tmp:
        venv = os.path.join(tmp, "venv")
        r = subprocess.run([python, "-m", "venv", "--system-site-packages", venv], capture_output=True, text=True)
        if r.returncode != 0 or not os.path.exists(os.path.join(venv, "bin", "pip")):
            print("SKIP: cannot make a venv with pip (Debian package python3-venv):", r.stderr[-500:])
            sys.exit(77)
        env = dict(os.environ, PIP_NO_INDEX="1", ADAPTEX_BUILD_DIR=build, ADAPTEX_CMAKE_ARGS=cmake_args)
        env.pop("PYTHONPATH", None)
        r = subprocess.run([os.path.join(venv, "bin", "pip"), "install", "."], cwd=source, env=env,
                           capture_output=True, text=True)
        print(r.stdout[-3000:], r.stderr[-3000:])
        assert r.returncode == 0, "pip install . failed"
        check = ("import adaptex, numpy as np\n"
                 "print(adaptex.__version__)\n"
                 "V = np.array([[1,0,0],[-1,0,0],[0,1,0],[0,-1,0],[0,0,1],[0,0,-1]], float)\n"
                 "F = np.array([[0,2,4],[2,1,4],[1,3,4],[3,0,4],[2,0,5],[1,2,5],[3,1,5],[0,3,5]])\n"
                 "UV, FT, report = adaptex.unwrap(V, F)\n"
                 "print(adaptex.stretch(V, F, UV, FT)['flipped'], adaptex.__file__)\n")
        r = subprocess.run([os.path.join(venv, "bin", "python"), "-c", check], cwd=tmp, env=env,
                           capture_output=True, text=True)
        print(r.stdout, r.stderr[-2000:])
        assert r.returncode == 0, "the installed module does not work"
        lines = r.stdout.split("\n")
        assert lines[0] == version, f"adaptex.__version__ is {lines[0]!r}, VERSION says {version!r}"
        flipped, path = lines[1].split(" ", 1)
        assert flipped == "0"
        assert path.startswith(venv), f"imported {path}, not the venv's package"
        r = subprocess.run([os.path.join(venv, "bin", "adaptex"), "--version"], capture_output=True, text=True)
        assert r.returncode == 0 and r.stdout.strip() == f"adaptex {version}", (r.stdout, r.stderr)
    print("pip install: OK", version)


if __name__ == "__main__":
    main()
