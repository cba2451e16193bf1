"""Runs the pytest suite of the Python module (ctest: python_module_*). Exits 77 (ctest SKIP) with
a message when the module was not built or numpy / pytest are missing.

usage: run.py MODULE_DIR TEST_FILE [pytest args...]
"""
import os
import sys


def skip(message):
    print("SKIP: " + message)
    sys.exit(77)


def main():
    module_dir, test_file = sys.argv[1], sys.argv[2]
    for name, package in (("pytest", "python3-pytest"), ("numpy", "python3-numpy")):
        try:
            __import__(name)
        except ImportError:
            skip(f"{name} is not installed for {sys.executable} (Debian package {package}; scripts/setup.sh)")
    if not os.path.isdir(os.path.join(module_dir, "adaptex")):
        skip("the Python module was not built (configure with Python 3 development files and pybind11: "
             "Debian python3-dev python3-pybind11, or -DADAPTEX_PYTHON=ON)")
    sys.path.insert(0, module_dir)
    os.environ["PYTHONPATH"] = module_dir + os.pathsep + os.environ.get("PYTHONPATH", "")
    import pytest

    here = os.path.dirname(os.path.abspath(__file__))
    sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", "--rootdir", here,
                          os.path.join(here, test_file)] + sys.argv[3:]))


if __name__ == "__main__":
    main()
