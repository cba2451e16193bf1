"""Meshes and strokes built in code for the Python module's tests (no data files)."""
import os
import shutil

import numpy as np
import pytest

from shapes import grid, uv_sphere  # noqa: F401 (test files import them from here)


def dot_strokes(count=40, seed=3):
    """Small hard dots on the upper cap of the unit sphere (detail in one region), as a dict."""
    rng = np.random.default_rng(seed)
    strokes = []
    for _ in range(count):
        p = rng.normal(size=3)
        p[2] = abs(p[2]) * 3.0
        p /= np.linalg.norm(p)
        strokes.append({"color": [float(c) for c in rng.uniform(0.0, 1.0, 3)], "radius": 0.04,
                        "hardness": 0.9, "dabs": [[float(x) for x in p]]})
    return {"format": "adaptex.strokes", "version": 1, "background": [1.0, 1.0, 1.0], "strokes": strokes}


@pytest.fixture
def sphere():
    return uv_sphere()


@pytest.fixture
def strokes():
    return dot_strokes()


@pytest.fixture
def cli():
    """Path of the built `adaptex` CLI (ctest sets ADAPTEX_CLI), else the test is skipped."""
    path = os.environ.get("ADAPTEX_CLI") or shutil.which("adaptex")
    if not path or not os.path.exists(path):
        pytest.skip("the adaptex CLI was not found (ctest sets ADAPTEX_CLI)")
    return path
