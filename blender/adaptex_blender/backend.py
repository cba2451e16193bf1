"""How the add-on runs adaptex: the Python module `adaptex` where Blender's Python can import it,
otherwise the `adaptex` command-line tool. Both run in a background Job that reports progress and
can be cancelled. No bpy here (the work runs off Blender's main thread)."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

from . import meshdata


# How "make N× smaller" (the Adapt layout operator) runs: "shrink" (the artist's charts kept and
# repacked by the texture's detail, texels fitted to the original; the library measures both PSNRs)
# or "reparam" (signal-adaptive warp of the layout, then resampling; the add-on measures the PSNRs).
# Every backend has one smaller_by_<path> method per path.
MAKE_SMALLER = "shrink"


class Cancelled(Exception):
    """The user cancelled the job."""


class Job:
    """Runs fn(report) on a worker thread (start) or in the caller's (run); report(phase, fraction)
    records the progress and returns False once cancel() was called."""

    def __init__(self, fn):
        self.fn = fn
        self.phase, self.fraction = "starting", 0.0
        self.result = self.error = None
        self._cancel = threading.Event()
        self._thread = None

    def report(self, phase, fraction):
        self.phase, self.fraction = phase, float(fraction)
        return not self._cancel.is_set()

    def _run(self):
        try:
            self.result = self.fn(self.report)
        except BaseException as e:  # handed to the main thread, which reports it
            self.error = e

    def start(self):
        self._thread = threading.Thread(target=self._run, name="adaptex job", daemon=True)
        self._thread.start()

    def run(self):
        self._run()
        return self

    def cancel(self):
        self._cancel.set()

    @property
    def cancelled(self):
        return self._cancel.is_set()

    @property
    def done(self):
        return self._thread is None or not self._thread.is_alive()


def import_module(extra_path=""):
    """The adaptex module, or None. \\p extra_path: a folder holding the adaptex package (e.g. a build
    tree's python/ folder), tried when a plain import fails."""
    try:
        import adaptex
        return adaptex
    except ImportError:
        pass
    if extra_path and os.path.isdir(os.path.join(extra_path, "adaptex")):
        sys.path.insert(0, extra_path)
        try:
            import adaptex
            return adaptex
        except ImportError:
            sys.path.remove(extra_path)
    return None


def installed():
    """(module folder, CLI) where `cmake --install` put adaptex, recorded in the add-on's zip
    (_install.py, blender/make_zip.py); empty strings for a zip made without them."""
    try:
        from . import _install
    except ImportError:
        return "", ""
    return _install.MODULE_DIR, _install.CLI


def find_cli(path=""):
    """Path of the adaptex CLI: \\p path, else $ADAPTEX_CLI, else `adaptex` on PATH, else the
    installed one; None if none."""
    for candidate in (path, os.environ.get("ADAPTEX_CLI", "")):
        if candidate and os.path.isfile(candidate) and os.access(candidate, os.X_OK):
            return candidate
    on_path = shutil.which("adaptex")
    if on_path:
        return on_path
    cli = installed()[1]
    return cli if cli and os.path.isfile(cli) and os.access(cli, os.X_OK) else None


class Backend:
    """What both backends do the same way on top of their unwrap() and reparam()."""

    def make_smaller(self, V, F, UV, FT, texture, size, report):
        """The painted texture at size x size on a new layout: a dict with UV, FT, texture (H x W x 4
        uint8, or the path of a PNG for the CLI) and, where the path measures them, psnr and
        psnr_plain (dB against the original, of the result and of plain downsizing)."""
        return getattr(self, "smaller_by_" + MAKE_SMALLER)(V, F, UV, FT, texture, size, report)

    def smaller_by_reparam(self, V, F, UV, FT, texture, size, report):
        UV2, FT2, tex2 = self.reparam(V, F, UV, FT, texture, size, report)
        return {"UV": UV2, "FT": FT2, "texture": tex2}

    def smaller_by_shrink(self, V, F, UV, FT, texture, size, report):
        r = self.shrink(V, F, UV, FT, texture, size, report)
        return {"UV": r["UV"], "FT": r["FT"], "texture": r["texture"], "psnr": float(r["psnr"]),
                "psnr_plain": float(r["psnr_downsized"])}


class ModuleBackend(Backend):
    """Calls the Python module (GIL released, progress callback)."""
    name = "Python module"

    def __init__(self, module):
        self.m = module

    def unwrap(self, V, F, report):
        try:
            UV, FT, _ = self.m.unwrap(V, F, progress=report)
        except self.m.CancelledError:
            raise Cancelled() from None
        return UV, FT

    def reparam(self, V, F, UV, FT, texture, size, report):
        try:
            r = self.m.reparam(V, F, UV, FT, texture, size=size, refine=False, progress=report)
        except self.m.CancelledError:
            raise Cancelled() from None
        return r["UV"], r["FT"], r["texture"]

    def shrink(self, V, F, UV, FT, texture, size, report):
        """adaptex.shrink: dict with UV, FT, texture and the library's psnr / psnr_downsized."""
        try:
            r = self.m.shrink(V, F, UV, FT, texture, size=size, progress=report)
        except self.m.CancelledError:
            raise Cancelled() from None
        if len(r["FT"]) != len(F):
            raise RuntimeError("adaptex changed the triangles of the mesh; clean the mesh up first (Mesh > Clean Up)")
        return {"UV": r["UV"], "FT": r["FT"], "texture": r["texture"], "psnr": r["report"]["psnr"],
                "psnr_downsized": r["report"]["psnr_downsized"]}


def write_obj(path, V, F, UV=None, FT=None):
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V.tolist())
        if UV is None:
            f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F.tolist())
        else:
            f.writelines(f"vt {u!r} {v!r}\n" for u, v in UV.tolist())
            f.writelines(f"f {a + 1}/{p + 1} {b + 1}/{q + 1} {c + 1}/{r + 1}\n"
                         for (a, b, c), (p, q, r) in zip(F.tolist(), FT.tolist()))


def read_obj_layout(path, F):
    """(UV, FT) of an OBJ written by the CLI for the triangles \\p F (checked to be unchanged)."""
    import numpy as np
    uv, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("vt "):
                uv.append([float(x) for x in line.split()[1:3]])
            elif line.startswith("f "):
                faces.append([[int(x) - 1 for x in c.split("/")[:2]] for c in line.split()[1:4]])
    corners = np.array(faces, dtype=np.int64).reshape(-1, 3, 2)
    if corners.shape[0] != len(F) or not np.array_equal(corners[:, :, 0], F):
        raise RuntimeError("the adaptex CLI changed the mesh (degenerate or duplicate faces?); "
                           "clean the mesh up first (Mesh > Clean Up)")
    return np.array(uv, dtype=np.float64), corners[:, :, 1].astype(np.int32)


def cli_error(stderr, code):
    """The CLI's error line as the add-on's user should read it: without the "adaptex: error:" prefix,
    and the temporary files the add-on wrote named as what they hold."""
    line = stderr.splitlines()[-1] if stderr else f"adaptex exited with {code}"
    line = line.removeprefix("adaptex: error: ")
    tmp = re.escape(tempfile.gettempdir().rstrip(os.sep)) + r"/adaptex-[^/\s]+/"
    return re.sub(tmp + r"in\.obj", "the mesh", re.sub(tmp + r"in\.png", "the image", line))


class CliBackend(Backend):
    """Runs the `adaptex` CLI in a subprocess (terminated on cancel)."""
    name = "adaptex CLI"

    def __init__(self, path):
        self.path = path

    def _run(self, args, report, phases):
        with tempfile.TemporaryFile(mode="w+") as err:
            proc = subprocess.Popen([self.path, *args], stdout=subprocess.DEVNULL, stderr=err,
                                    stdin=subprocess.DEVNULL)
            while proc.poll() is None:
                err.seek(0)
                seen = [p for p in phases if (": " + p) in err.read()]
                if not report(seen[-1] if seen else "start", len(seen) / (len(phases) + 1)):
                    proc.terminate()
                    proc.wait()
                    raise Cancelled()
                time.sleep(0.05)
            err.seek(0)
            text = err.read().strip()
        if proc.returncode != 0:
            raise RuntimeError(cli_error(text, proc.returncode))

    def unwrap(self, V, F, report):
        with tempfile.TemporaryDirectory(prefix="adaptex-") as tmp:
            write_obj(os.path.join(tmp, "in.obj"), V, F)
            out = os.path.join(tmp, "out.obj")
            self._run(["unwrap", os.path.join(tmp, "in.obj"), "-o", out], report,
                      ["cut", "floater", "yoshizawa", "augment", "pack"])
            return read_obj_layout(out, F)

    def shrink(self, V, F, UV, FT, texture, size, report):
        """As ModuleBackend.shrink, through `adaptex reparam --adapt shrink` (the same code; its
        report.json holds both PSNRs); the texture is the path of the result's PNG (read it with
        meshdata.read_png, which removes the temporary folder)."""
        tmp = tempfile.mkdtemp(prefix="adaptex-")
        try:
            write_obj(os.path.join(tmp, "in.obj"), V, F, UV, FT)
            meshdata.write_png(os.path.join(tmp, "in.png"), texture)
            out = os.path.join(tmp, "out")
            self._run(["reparam", os.path.join(tmp, "in.obj"), os.path.join(tmp, "in.png"), "--adapt", "shrink",
                       "--size", str(size), "--name", "out", "-o", out], report,
                      ["islands", "error model", "pack", "warp", "texels", "fit solve", "evaluate"])
            UV2, FT2 = read_obj_layout(os.path.join(out, "out.obj"), F)
            with open(os.path.join(out, "report.json")) as f:
                rep = json.load(f)["shrink"]
            return {"UV": UV2, "FT": FT2, "texture": os.path.join(out, "out.png"), "psnr": rep["psnr"],
                    "psnr_downsized": rep["psnr_downsized"]}
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise

    def reparam(self, V, F, UV, FT, texture, size, report):
        """As ModuleBackend.reparam, but the texture is returned as the path of a PNG in a
        temporary folder (read it with meshdata.read_png on Blender's main thread, which removes it)."""
        tmp = tempfile.mkdtemp(prefix="adaptex-")
        try:
            write_obj(os.path.join(tmp, "in.obj"), V, F, UV, FT)
            meshdata.write_png(os.path.join(tmp, "in.png"), texture)
            out = os.path.join(tmp, "out")
            self._run(["reparam", os.path.join(tmp, "in.obj"), os.path.join(tmp, "in.png"), "--no-refine",
                       "--size", str(size), "--name", "out", "-o", out], report, ["reparam"])
            UV2, FT2 = read_obj_layout(os.path.join(out, "out.obj"), F)
            return UV2, FT2, os.path.join(out, "out.png")
        except BaseException:
            shutil.rmtree(tmp, ignore_errors=True)
            raise


def choose(preference="AUTO", module_path="", cli_path=""):
    """The backend to use: the module where importable (unless CLI is asked for), else the CLI.
    \\throw RuntimeError neither is available."""
    if preference != "CLI":
        module = import_module(module_path) or import_module(installed()[0])
        if module is not None:
            return ModuleBackend(module)
        if preference == "MODULE":
            raise RuntimeError("the adaptex Python module cannot be imported (set its folder in the add-on's preferences)")
    cli = find_cli(cli_path)
    if cli is None:
        raise RuntimeError("neither the adaptex Python module nor the adaptex CLI was found "
                           "(set one in the add-on's preferences)")
    return CliBackend(cli)
