"""Meshes built in code with numpy for the Python tests and the Blender test (no pytest import:
Blender's Python loads this file too)."""
import math

import numpy as np


def uv_sphere(slices=24, stacks=12):
    """Closed genus-0 UV sphere of radius 1: V #V x 3 float64, F #F x 3 int32 (CCW from outside)."""
    V = [(0.0, 0.0, 1.0)]
    for i in range(1, stacks):
        th = math.pi * i / stacks
        for j in range(slices):
            ph = 2 * math.pi * j / slices
            V.append((math.sin(th) * math.cos(ph), math.sin(th) * math.sin(ph), math.cos(th)))
    V.append((0.0, 0.0, -1.0))
    ring = lambda i, j: 1 + i * slices + j % slices  # noqa: E731
    F = [(0, ring(0, j), ring(0, j + 1)) for j in range(slices)]
    for i in range(stacks - 2):
        for j in range(slices):
            F += [(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)), (ring(i, j), ring(i + 1, j + 1), ring(i, j + 1))]
    last = len(V) - 1
    F += [(last, ring(stacks - 2, j + 1), ring(stacks - 2, j)) for j in range(slices)]
    return np.array(V, dtype=np.float64), np.array(F, dtype=np.int32)


def grid(n=8):
    """Flat square [0,1]^2 at z = 0, n x n quads split in two: a disk."""
    xs = np.linspace(0.0, 1.0, n + 1)
    V = np.array([(x, y, 0.0) for y in xs for x in xs])
    F = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            F += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    return V, np.array(F, dtype=np.int32)
