#!/usr/bin/env python3
"""Byte-for-byte comparison of two adaptex builds' outputs (paint, reparam, unwrap).

    python3 bench/adapt/compare_outputs.py BASELINE_ADAPTEX NEW_ADAPTEX [--meshes DIR] [--work DIR]
                                           [--quick] [--keep]

Runs the same commands with both binaries and compares every output file:
- `adaptex paint` with every method (density-flow, two-stage, single, none), --reparam end and
  each-stroke, and density-flow with --no-refine; at 128² (each-stroke) and 256² (end);
- `adaptex reparam` of a painted OBJ + PNG with every method (and density-flow --no-refine), on a
  one-chart and a multi-chart layout;
- `adaptex unwrap` (OBJ, --report JSON, --layout PNG, and --charts single).
Meshes: code-built ones (this script writes a plane, a torus and a sphere as OBJ; `adaptex demo`'s
trefoil) and, with --meshes (default /work/shared/meshes when present), venus.off, triceratops.off and
spot.obj. Strokes come from the NEW binary's `adaptex strokes generate` (a contract both builds read).

OBJ, MTL, PNG and GLB files are compared byte for byte; report.json and the unwrap report after removing
timings (keys starting with "time", ending in "_ms" or "_per_s"). Where files differ, the script
prints the largest UV difference (OBJ `vt`), and for PNGs the number of differing texel channels and
their largest difference, against the tolerance of the refactoring issue: UVs within 1e-12 and texels
within 1/255 in at most 0.01 % of them. Exit code 0 when every output is identical, 1 otherwise.

Later changes on main that are intended to change outputs (compare a branch against its own merge
base, not across them): the `reparam` command's re-packing of chart layouts (the real-assets work),
and the GLB exporter's sampler and padding. Before those, every case matched the build fa3a81b.
"""
import argparse
import json
import math
import os
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

UV_TOL = 1e-12
TEXEL_TOL = 1  # in 1/255
TEXEL_SHARE = 1e-4  # 0.01 %


def write_obj(path, verts, faces):
    with open(path, "w") as f:
        for v in verts:
            f.write("v %.9f %.9f %.9f\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


def plane(n=24):
    verts = [(i / n, j / n, 0.05 * math.sin(3 * i / n) * math.cos(2 * j / n)) for j in range(n + 1) for i in range(n + 1)]
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 1, a + n + 2
            faces += [(a, b, d), (a, d, c)]
    return verts, faces


def torus(nu=40, nv=20, r1=1.0, r2=0.35):
    verts = []
    for i in range(nu):
        u = 2 * math.pi * i / nu
        for j in range(nv):
            v = 2 * math.pi * j / nv
            verts.append(((r1 + r2 * math.cos(v)) * math.cos(u), (r1 + r2 * math.cos(v)) * math.sin(u), r2 * math.sin(v)))
    faces = []
    for i in range(nu):
        for j in range(nv):
            a, b = i * nv + j, ((i + 1) % nu) * nv + j
            c, d = i * nv + (j + 1) % nv, ((i + 1) % nu) * nv + (j + 1) % nv
            faces += [(a, b, d), (a, d, c)]
    return verts, faces


def sphere(nu=32, nv=16):
    verts = [(0.0, 0.0, 1.0)]
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            verts.append((math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)))
    verts.append((0.0, 0.0, -1.0))
    south = len(verts) - 1
    ring = lambda j, i: 1 + (j - 1) * nu + i % nu
    faces = [(0, ring(1, i), ring(1, i + 1)) for i in range(nu)]
    for j in range(1, nv - 1):
        for i in range(nu):
            a, b, c, d = ring(j, i), ring(j, i + 1), ring(j + 1, i), ring(j + 1, i + 1)
            faces += [(a, c, d), (a, d, b)]
    faces += [(ring(nv - 1, i), south, ring(nv - 1, i + 1)) for i in range(nu)]
    return verts, faces


def png_pixels(path):
    """(width, height, channels, bytes) of an 8-bit non-interlaced PNG (what stb writes)."""
    data = open(path, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(path + ": not a PNG")
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or interlace:
                raise ValueError(path + ": only 8-bit non-interlaced PNGs are compared")
            ch = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * ch
    out = bytearray(stride * h)
    prev = bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - ch] if x >= ch else 0
            b = prev[x]
            c = prev[x - ch] if x >= ch else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return w, h, ch, bytes(out)


def obj_uvs(path):
    return [tuple(float(x) for x in l.split()[1:3]) for l in open(path) if l.startswith("vt ")]


def strip_timings(j):
    if isinstance(j, dict):
        return {k: strip_timings(v) for k, v in j.items()
                if not (k.startswith("time") or k.endswith("_ms") or k.endswith("_per_s"))}
    if isinstance(j, list):
        return [strip_timings(v) for v in j]
    return j


def json_diff(a, b, path=""):
    """First few differing leaves of two JSON values."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = []
        for k in sorted(set(a) | set(b)):
            out += json_diff(a.get(k), b.get(k), path + "/" + k)
        return out
    if isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += json_diff(x, y, "%s[%d]" % (path, i))
        return out
    return [] if a == b else ["%s: %r != %r" % (path, a, b)]


def compare_file(a, b):
    """None if equal, else a one-line description of the difference and whether it is in tolerance."""
    name = os.path.basename(a)
    if name.endswith(".json"):
        ja, jb = strip_timings(json.load(open(a))), strip_timings(json.load(open(b)))
        if ja == jb:
            return None
        return "report differs: " + "; ".join(json_diff(ja, jb)[:4]), False
    da, db = open(a, "rb").read(), open(b, "rb").read()
    if da == db:
        return None
    if name.endswith(".obj"):
        ua, ub = obj_uvs(a), obj_uvs(b)
        if len(ua) != len(ub):
            return "OBJ differs: %d vs %d UVs" % (len(ua), len(ub)), False
        m = max((abs(x - y) for p, q in zip(ua, ub) for x, y in zip(p, q)), default=0.0)
        return "OBJ differs: UV max abs diff %.3g" % m, m <= UV_TOL
    if name.endswith(".png"):
        wa, ha, ca, pa = png_pixels(a)
        wb, hb, cb, pb = png_pixels(b)
        if (wa, ha, ca) != (wb, hb, cb):
            return "PNG differs in size", False
        diffs = [abs(x - y) for x, y in zip(pa, pb) if x != y]
        share = len(diffs) / max(1, len(pa))
        return ("PNG differs: %d of %d channels (%.4f %%), max diff %d/255" %
                (len(diffs), len(pa), 100 * share, max(diffs)), max(diffs) <= TEXEL_TOL and share <= TEXEL_SHARE)
    return "%s differs (%d vs %d bytes)" % (name, len(da), len(db)), False


def run(binary, args, cwd):
    r = subprocess.run([binary] + args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return r.returncode, r.stderr.strip().splitlines()[-1:] if r.returncode else []


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("baseline")
    ap.add_argument("new")
    ap.add_argument("--meshes", default="/work/shared/meshes", help="shared meshes (skipped when absent)")
    ap.add_argument("--work", help="work directory (default: a temporary one, removed at the end)")
    ap.add_argument("--quick", action="store_true", help="code-built meshes only")
    ap.add_argument("--keep", action="store_true", help="keep the work directory")
    a = ap.parse_args()
    base, new = os.path.realpath(a.baseline), os.path.realpath(a.new)
    work = os.path.realpath(a.work) if a.work else tempfile.mkdtemp(prefix="adaptex-compare-")
    os.makedirs(work, exist_ok=True)
    inp = os.path.join(work, "in")
    os.makedirs(inp, exist_ok=True)

    meshes = {}
    for name, (v, f) in {"plane": plane(), "torus": torus(), "sphere": sphere()}.items():
        meshes[name] = os.path.join(inp, name + ".obj")
        write_obj(meshes[name], v, f)
    rc, err = run(new, ["demo", "-o", os.path.join(inp, "demo"), "--samples", "1000"], inp)
    if rc == 0 and os.path.exists(os.path.join(inp, "demo", "trefoil.obj")):
        meshes["trefoil"] = os.path.join(inp, "demo", "trefoil.obj")
    if not a.quick and os.path.isdir(a.meshes):
        for m in ["venus.off", "triceratops.off", "spot.obj"]:
            if os.path.exists(os.path.join(a.meshes, m)):
                meshes[m.split(".")[0]] = os.path.join(a.meshes, m)
    elif not a.quick:
        print("note: %s not found, shared meshes skipped" % a.meshes)

    strokes = {}
    for name, path in meshes.items():
        strokes[name] = os.path.join(inp, name + ".json")
        rc, err = run(new, ["strokes", "generate", path, "--kind", "mixed", "--seed", "1", "--count", "12",
                            "-o", strokes[name]], inp)
        if rc:
            sys.exit("strokes generate failed on %s: %s" % (name, err))

    cases = []  # (label, args with {OUT} for the output path)
    methods = ["density-flow", "two-stage", "single", "none"]
    for name, path in meshes.items():
        for m in methods:
            cases.append(("paint %s %s end" % (name, m),
                          ["paint", path, "--strokes", strokes[name], "--size", "256", "--adapt", m, "-o", "{OUT}"]))
            if m != "none":
                cases.append(("paint %s %s each-stroke" % (name, m),
                              ["paint", path, "--strokes", strokes[name], "--size", "128", "--adapt", m,
                               "--reparam", "each-stroke", "-o", "{OUT}"]))
        cases.append(("paint %s density-flow end --no-refine" % name,
                      ["paint", path, "--strokes", strokes[name], "--size", "256", "--no-refine", "-o", "{OUT}"]))
        cases.append(("paint %s density-flow each-stroke --no-refine" % name,
                      ["paint", path, "--strokes", strokes[name], "--size", "128", "--reparam", "each-stroke",
                       "--no-refine", "-o", "{OUT}"]))
        cases.append(("unwrap %s" % name, ["unwrap", path, "-o", "{OUT}/u.obj", "--report", "{OUT}/u.json",
                                            "--layout", "{OUT}/u.png"]))
        cases.append(("unwrap %s --charts single" % name, ["unwrap", path, "-o", "{OUT}/u.obj", "--charts", "single"]))

    # reparam: a painted layout (paint --adapt none) of a one-chart and of a multi-chart mesh.
    src = {}
    for name in ["plane", "torus", "sphere", "venus", "spot"]:
        if name not in meshes:
            continue
        d = os.path.join(inp, "painted_" + name)
        rc, err = run(base, ["paint", meshes[name], "--strokes", strokes[name], "--size", "256", "--adapt", "none",
                             "--name", name, "-o", d], inp)
        if rc:
            sys.exit("paint --adapt none failed on %s: %s" % (name, err))
        src[name] = (os.path.join(d, name + ".obj"), os.path.join(d, name + ".png"))
    for name, (obj, png) in src.items():
        for m in methods[:3]:
            cases.append(("reparam %s %s" % (name, m), ["reparam", obj, png, "--adapt", m, "-o", "{OUT}"]))
        cases.append(("reparam %s density-flow --no-refine" % name,
                      ["reparam", obj, png, "--no-refine", "-o", "{OUT}"]))

    identical = tolerated = differ = failed = 0
    for k, (label, args) in enumerate(cases):
        outs = []
        codes = []
        for tag, binary in (("base", base), ("new", new)):
            out = os.path.join(work, "case%03d_%s" % (k, tag))
            shutil.rmtree(out, ignore_errors=True)
            os.makedirs(out)
            rc, err = run(binary, [x.replace("{OUT}", out) for x in args], work)
            codes.append((rc, err))
            outs.append(out)
        if codes[0][0] != codes[1][0]:
            print("DIFFER  %s: exit codes %d vs %d %s" % (label, codes[0][0], codes[1][0], codes[1][1]))
            differ += 1
            continue
        if codes[0][0] != 0:
            print("FAILED  %s: both exit %d: %s" % (label, codes[0][0], codes[0][1]))
            failed += 1
            continue
        files_a = sorted(os.listdir(outs[0]))
        files_b = sorted(os.listdir(outs[1]))
        notes, ok = [], True
        if files_a != files_b:
            notes.append("file sets differ: %s vs %s" % (files_a, files_b))
            ok = False
        for f in files_a:
            if f in files_b:
                d = compare_file(os.path.join(outs[0], f), os.path.join(outs[1], f))
                if d:
                    notes.append(f + ": " + d[0])
                    ok = ok and d[1]
        if not notes:
            identical += 1
            print("same    %s (%d files)" % (label, len(files_a)))
        elif ok:
            tolerated += 1
            print("TOLER.  %s: %s" % (label, " | ".join(notes)))
        else:
            differ += 1
            print("DIFFER  %s: %s" % (label, " | ".join(notes)))
    print("%d cases: %d identical, %d within tolerance, %d differ, %d failed in both" %
          (len(cases), identical, tolerated, differ, failed))
    if not a.keep and not a.work:
        shutil.rmtree(work, ignore_errors=True)
    sys.exit(0 if differ == 0 and failed == 0 else 1)


if __name__ == "__main__":
    main()
