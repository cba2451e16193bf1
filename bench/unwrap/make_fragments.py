#!/usr/bin/env python3
"""Writes the coarse-fragment meshes of docs/bench_unwrap.md ("Not tuned on") as OFF files into DIR:
tests/param/scan_fixtures.h's crumpled_patch / flat_patch (same LCG) with other seeds and sizes than
the tests'. Usage: make_fragments.py DIR"""
import os
import sys

M = 0xFFFFFFFF


def crumpled(nx, ny, size, amp, origin, seed):
    verts, faces = [], []
    st = (seed * 2654435761 + 12345) & M
    for j in range(ny + 1):
        for i in range(nx + 1):
            st = (st * 1664525 + 1013904223) & M
            r = (st >> 8) / float(1 << 24)
            border = i == 0 or j == 0 or i == nx or j == ny
            z = 0.0 if border else amp * (2 * r - 1)
            verts.append((origin[0] + size * i / nx, origin[1] + size * j / ny, origin[2] + z))
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            b, c = a + 1, a + nx + 1
            faces += [(a, b, c + 1), (a, c + 1, c)]
    return verts, faces


def flat(n, size, origin):
    return crumpled(n, n, size, 0.0, origin, 0)


def write(path, parts):
    verts, faces = [], []
    for v, f in parts:
        o = len(verts)
        verts += v
        faces += [(a + o, b + o, c + o) for a, b, c in f]
    with open(path, "w") as fh:
        fh.write("OFF\n%d %d 0\n" % (len(verts), len(faces)))
        fh.writelines("%.17g %.17g %.17g\n" % p for p in verts)
        fh.writelines("3 %d %d %d\n" % t for t in faces)


def main():
    out = sys.argv[1]
    squares = lambda n, side, x0, step, cols: [flat(1, side, (x0 + step * (k % cols), step * (k // cols), 0)) for k in range(n)]
    write(os.path.join(out, "coarse_s7.off"), [crumpled(5, 5, 5.0, 7.0, (0, 0, 0), 7), flat(50, 5.0, (0, 7, 0))] + squares(60, 0.35, 7, 0.6, 10))
    write(os.path.join(out, "coarse_s3.off"), [crumpled(3, 6, 3.0, 4.0, (0, 0, 0), 3), crumpled(4, 4, 2.0, 3.0, (4, 0, 0), 5),
                                               flat(30, 3.0, (0, 5, 0))] + squares(36, 0.25, 8, 0.4, 6))
    write(os.path.join(out, "rough_s11.off"), [crumpled(3, 4, 1.2, 2.5, (1.8 * (k % 4), 1.8 * (k // 4), 0), k + 11) for k in range(12)] +
          [flat(48, 9.0, (0, 8, 0))])
    write(os.path.join(out, "rough_s31.off"), [crumpled(5, 3, 1.5, 2.0, (2.0 * (k % 4), 2.0 * (k // 4), 0), k + 31) for k in range(8)] +
          [flat(36, 6.0, (0, 7, 0))])
    for s in (2, 4, 6, 8, 10):
        write(os.path.join(out, "coarseA_s%d.off" % s), [crumpled(4, 4, 4.0, 6.0, (0, 0, 0), s), flat(40, 4.0, (0, 6, 0))] + squares(40, 0.3, 6, 0.5, 8))
        write(os.path.join(out, "coarseB_s%d.off" % s), [crumpled(3, 6, 3.0, 4.0, (0, 0, 0), s), crumpled(4, 4, 2.0, 3.0, (4, 0, 0), s + 1),
                                                         flat(30, 3.0, (0, 5, 0))] + squares(36, 0.25, 8, 0.4, 6))


if __name__ == "__main__":
    main()
