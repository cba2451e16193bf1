"""PEP 517 build backend of the adaptex wheel (pyproject.toml): the project's CMake builds the Python
module and the CLI, and this file packs them. Standard library only, so that `pip install .` and
`python3 -m build --no-isolation` need nothing from the network (Debian 12's python3-pip /
python3-build, no build requirements to download).

The wheel holds the package `adaptex` (extension, __init__.py, _version.py) and the `adaptex`
command-line tool as a script (installed into the environment's bin/). Settings, as environment
variables or `--config-settings` keys:
- ADAPTEX_BUILD_DIR / build-dir: the CMake build folder (default: build-pip-<interpreter> in the
  source tree, kept between builds so that rebuilding is incremental);
- ADAPTEX_BUILD_JOBS / jobs: parallel build jobs (default: the number of CPUs);
- ADAPTEX_CMAKE_ARGS / cmake-args: extra arguments for the configure step (space-separated).
"""
import base64
import hashlib
import io
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import zipfile

SOURCE = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
NAME = "adaptex"
SUMMARY = "Signal-adaptive parameterization for painting on meshes: numpy bindings and the adaptex CLI"


def _version():
    with open(os.path.join(SOURCE, "VERSION")) as f:
        return f.read().strip()


def _setting(config_settings, key, env, default=None):
    if config_settings and config_settings.get(key):
        return config_settings[key]
    return os.environ.get(env) or default


def _tag():
    """The wheel tag of this interpreter: cpXY-cpXY-<platform>."""
    py = f"{sys.implementation.name[:2]}{sys.version_info.major}{sys.version_info.minor}"
    plat = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{py}-{py}-{plat}"


def _metadata():
    with open(os.path.join(SOURCE, "README.md"), encoding="utf-8") as f:
        readme = f.read()
    return (f"Metadata-Version: 2.1\nName: {NAME}\nVersion: {_version()}\nSummary: {SUMMARY}\n"
            "Requires-Python: >=3.9\nRequires-Dist: numpy\n"
            "Description-Content-Type: text/markdown\n\n" + readme)


def _dist_info():
    return f"{NAME}-{_version()}.dist-info"


def _write_dist_info(directory):
    path = os.path.join(directory, _dist_info())
    os.makedirs(path, exist_ok=True)
    with open(os.path.join(path, "METADATA"), "w", encoding="utf-8") as f:
        f.write(_metadata())
    return os.path.basename(path)


def _cmake_build(config_settings):
    """Configures and builds the module and the CLI; returns the build folder."""
    cache = sys.implementation.cache_tag
    build = os.path.abspath(_setting(config_settings, "build-dir", "ADAPTEX_BUILD_DIR",
                                     os.path.join(SOURCE, f"build-pip-{cache}")))
    jobs = str(_setting(config_settings, "jobs", "ADAPTEX_BUILD_JOBS", os.cpu_count() or 1))
    cmake = shutil.which("cmake")
    if cmake is None:
        raise RuntimeError("adaptex: cmake is not installed (Debian: scripts/setup.sh)")
    configure = [cmake, "-S", SOURCE, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 "-DADAPTEX_BUILD_TESTS=OFF", "-DADAPTEX_BUILD_BENCH=OFF", "-DADAPTEX_BUILD_STUDIO=OFF",
                 "-DADAPTEX_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"]
    if shutil.which("ninja") and not os.path.exists(os.path.join(build, "CMakeCache.txt")):
        configure += ["-G", "Ninja"]
    configure += shlex.split(_setting(config_settings, "cmake-args", "ADAPTEX_CMAKE_ARGS", ""))
    for cmd in (configure, [cmake, "--build", build, "--target", "adaptex_python", "adaptex_cli", "-j", jobs]):
        print("adaptex:", " ".join(cmd), file=sys.stderr, flush=True)
        subprocess.run(cmd, check=True, stdout=sys.stderr)
    return build


class _Wheel:
    """A wheel being written: files with their RECORD lines."""

    def __init__(self, path):
        self.zip = zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED)
        self.record = []

    def add(self, arcname, data, executable=False):
        info = zipfile.ZipInfo(arcname, date_time=(2005, 1, 1, 0, 0, 0))
        info.external_attr = (0o100755 if executable else 0o100644) << 16  # a regular file, and its mode
        info.compress_type = zipfile.ZIP_DEFLATED
        self.zip.writestr(info, data)
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        self.record.append(f"{arcname},sha256={digest},{len(data)}")

    def add_file(self, arcname, path, executable=False):
        with open(path, "rb") as f:
            self.add(arcname, f.read(), executable)

    def close(self, dist_info):
        self.record.append(f"{dist_info}/RECORD,,")
        self.zip.writestr(f"{dist_info}/RECORD", "\n".join(self.record) + "\n")
        self.zip.close()


def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    return _write_dist_info(metadata_directory)


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    build = _cmake_build(config_settings)
    package = os.path.join(build, "python", NAME)
    names = sorted(os.listdir(package))
    extensions = [n for n in names if n.startswith("_adaptex") and n.endswith(sysconfig.get_config_var("EXT_SUFFIX"))]
    if not extensions:
        raise RuntimeError(f"adaptex: the module was not built in {package}")
    cli = os.path.join(build, "apps", "cli", NAME)
    tag = _tag()
    wheel_name = f"{NAME}-{_version()}-{tag}.whl"
    wheel = _Wheel(os.path.join(wheel_directory, wheel_name))
    for n in [n for n in names if n.endswith(".py")] + extensions:
        wheel.add_file(f"{NAME}/{n}", os.path.join(package, n), executable=n in extensions)
    wheel.add_file(f"{NAME}-{_version()}.data/scripts/{NAME}", cli, executable=True)
    dist_info = _dist_info()
    wheel.add(f"{dist_info}/METADATA", _metadata().encode())
    wheel.add(f"{dist_info}/WHEEL", (f"Wheel-Version: 1.0\nGenerator: adaptex_backend\nRoot-Is-Purelib: false\n"
                                     f"Tag: {tag}\n").encode())
    wheel.close(dist_info)
    return wheel_name


def build_sdist(sdist_directory, config_settings=None):
    """The source tree without build folders, outputs or version control."""
    base = f"{NAME}-{_version()}"
    name = base + ".tar.gz"
    skip_top = {".git", "demo-output"}

    def keep(rel):
        top = rel.split(os.sep, 1)[0]
        return not (top in skip_top or top.startswith("build") or "__pycache__" in rel.split(os.sep))

    with tarfile.open(os.path.join(sdist_directory, name), "w:gz", format=tarfile.PAX_FORMAT) as tar:
        for root, dirs, files in os.walk(SOURCE):
            rel_root = os.path.relpath(root, SOURCE)
            dirs[:] = sorted(d for d in dirs if keep(os.path.normpath(os.path.join(rel_root, d))))
            for f in sorted(files):
                rel = os.path.normpath(os.path.join(rel_root, f))
                if keep(rel):
                    tar.add(os.path.join(root, f), arcname=os.path.join(base, rel), recursive=False)
        pkg_info = _metadata().encode()
        info = tarfile.TarInfo(os.path.join(base, "PKG-INFO"))
        info.size = len(pkg_info)
        tar.addfile(info, io.BytesIO(pkg_info))
    return name
