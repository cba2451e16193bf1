"""The stroke file version 2 (docs/strokes.md, "Version 2: layered materials") against an
independent numpy implementation of its text: every blend mode and channel, masks, erasers, fills
and pen pressure, on surface samples."""
import json
import subprocess

import numpy as np
import pytest

import adaptex
from conftest import uv_sphere

BLENDS = ["normal", "multiply", "screen", "overlay", "add", "subtract"]
CHANNELS = {"base_color": slice(0, 3), "alpha": slice(3, 4), "roughness": slice(4, 5), "metallic": slice(5, 6),
            "height": slice(6, 7)}
DEFAULT_BACKGROUND = {"base_color": [1, 1, 1], "alpha": 1, "roughness": 0.5, "metallic": 0, "height": 0.5}


def falloff(t, h):
    s = np.clip((t - h) / max(1 - h, 1e-300), 0, 1)
    f = 1 - (3 * s ** 2 - 2 * s ** 3)
    return np.where(t <= h, 1.0, np.where(t >= 1, 0.0, f))


def curve(points, p):
    if not points:
        return np.ones_like(p)
    xs, ys = zip(*points)
    return np.interp(np.clip(p, 0, 1), xs, ys)


def coverage(stroke, P):
    """alpha(x) of a brush / erase / fill stroke at the points P (#P x 3)."""
    if stroke.get("type") == "fill":
        return np.full(len(P), stroke.get("opacity", 1.0))
    pressure = stroke.get("pressure", {})
    alpha = np.zeros(len(P))
    for d in stroke["dabs"]:
        p = d[3] if len(d) == 4 else 1.0
        r = stroke["radius"] * curve(pressure.get("radius"), np.array([p]))[0]
        o = stroke.get("opacity", 1.0) * curve(pressure.get("opacity"), np.array([p]))[0]
        if r <= 0:
            continue
        t = np.linalg.norm(P - np.asarray(d[:3]), axis=1) / r
        alpha = np.maximum(alpha, o * falloff(t, stroke.get("hardness", 0.5)))
    return alpha


def blend(mode, a, b):
    return {"normal": b, "multiply": a * b, "screen": 1 - (1 - a) * (1 - b),
            "overlay": np.where(a <= 0.5, 2 * a * b, 1 - 2 * (1 - a) * (1 - b)),
            "add": np.minimum(1, a + b), "subtract": np.maximum(0, a - b)}[mode]


def reference(doc, P):
    """The material of \\p doc at P (#P x 7), from the text of docs/strokes.md."""
    bg = dict(DEFAULT_BACKGROUND, **doc.get("background", {}))
    R = np.zeros((len(P), 7))
    for name, sl in CHANNELS.items():
        R[:, sl] = np.asarray(bg[name], float)
    for layer in doc["layers"]:
        if not layer.get("visible", True):
            continue
        L = np.zeros((len(P), 7))
        a = {name: np.zeros(len(P)) for name in CHANNELS}
        for s in layer["strokes"]:
            alpha = coverage(s, P)
            if s.get("type") == "erase":
                for name in s.get("channels", list(CHANNELS)):
                    a[name] = a[name] * (1 - alpha)
                continue
            for name, value in s["channels"].items():
                sl = CHANNELS[name]
                new_a = a[name] * (1 - alpha) + alpha
                num = L[:, sl] * (a[name] * (1 - alpha))[:, None] + np.asarray(value, float) * alpha[:, None]
                L[:, sl] = np.where(new_a[:, None] > 0, num / np.where(new_a > 0, new_a, 1)[:, None], 0)
                a[name] = new_a
        mask = layer.get("mask")
        M = np.ones(len(P))
        if mask is not None:
            M = np.full(len(P), mask.get("value", 1.0))
            for s in mask.get("strokes", []):
                value = mask.get("value", 1.0) if s.get("type") == "erase" else s["value"]
                alpha = coverage(s, P)
                M = M * (1 - alpha) + value * alpha
        for name, sl in CHANNELS.items():
            k = (a[name] * M * layer.get("opacity", 1.0))[:, None]
            R[:, sl] = R[:, sl] * (1 - k) + blend(layer.get("blend", "normal"), R[:, sl], L[:, sl]) * k
    return R


def sphere_samples(V, F, n, seed):
    rng = np.random.default_rng(seed)
    faces = rng.integers(0, len(F), n)
    s, t = np.sqrt(rng.uniform(size=n)), rng.uniform(size=n)
    bary = np.stack([1 - s, s * (1 - t)], axis=1)
    P = (bary[:, :1] * V[F[faces, 0]] + bary[:, 1:] * V[F[faces, 1]] +
         (1 - bary.sum(axis=1))[:, None] * V[F[faces, 2]])
    return faces, bary, P


def random_dabs(rng, count, pressure):
    pts = rng.normal(size=(count, 3))
    pts /= np.linalg.norm(pts, axis=1, keepdims=True)
    return [list(map(float, p)) + ([float(rng.uniform())] if pressure else []) for p in pts]


def every_mode_document(seed=11):
    """One layer per blend mode, each painting every channel, with masks, erasers and pressure."""
    rng = np.random.default_rng(seed)

    def channels():
        return {"base_color": [float(x) for x in rng.uniform(size=3)], "alpha": float(rng.uniform()),
                "roughness": float(rng.uniform()), "metallic": float(rng.uniform()), "height": float(rng.uniform())}

    layers = []
    for k, mode in enumerate(BLENDS):
        strokes = [{"type": "fill", "channels": {"roughness": float(rng.uniform())}, "opacity": 0.5}]
        for _ in range(4):
            strokes.append({"type": "brush", "channels": channels(), "radius": float(rng.uniform(0.3, 0.8)),
                            "hardness": float(rng.uniform()), "opacity": float(rng.uniform(0.5, 1)),
                            "pressure": {"radius": [[0, 0.3], [1, 1]], "opacity": [[0, 0.2], [0.6, 1], [1, 1]]},
                            "dabs": random_dabs(rng, 3, pressure=True)})
        strokes.append({"type": "erase", "channels": ["height", "base_color"], "radius": 0.4, "hardness": 0.7,
                        "opacity": 0.8, "dabs": random_dabs(rng, 2, pressure=False)})
        layer = {"name": mode, "opacity": float(rng.uniform(0.6, 1)), "blend": mode, "strokes": strokes}
        if k % 2 == 1:
            layer["mask"] = {"value": 0.2, "strokes": [
                {"value": 1, "radius": 0.9, "hardness": 0.2, "dabs": random_dabs(rng, 2, pressure=False)},
                {"type": "erase", "radius": 0.3, "hardness": 1, "dabs": random_dabs(rng, 1, pressure=False)}]}
        layers.append(layer)
    layers.append({"name": "hidden", "visible": False, "strokes": [{"type": "fill", "channels": channels()}]})
    return {"format": "adaptex.strokes", "version": 2,
            "background": {"base_color": [0.2, 0.4, 0.6], "roughness": 0.7}, "layers": layers}


def test_every_blend_mode_and_channel_matches_the_reference():
    V, F = uv_sphere()
    doc = every_mode_document()
    faces, bary, P = sphere_samples(V, F, 20000, seed=5)
    got = adaptex.evaluate_material(V, F, doc, faces, bary)
    want = reference(doc, P)
    assert got.shape == (len(P), 7)
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)
    # The document is not trivial: every channel varies over the sphere.
    assert (np.ptp(got, axis=0) > 0.05).all()


def test_version1_file_is_its_base_colour(strokes, sphere):
    V, F = sphere
    faces, bary, P = sphere_samples(V, F, 5000, seed=2)
    got = adaptex.evaluate_material(V, F, strokes, faces, bary)
    v2 = {"format": "adaptex.strokes", "version": 2,
          "background": {"base_color": strokes["background"]},
          "layers": [{"strokes": [{"channels": {"base_color": s["color"]}, "radius": s["radius"],
                                   "hardness": s["hardness"], "dabs": s["dabs"]} for s in strokes["strokes"]]}]}
    np.testing.assert_allclose(got, reference(v2, P), rtol=0, atol=1e-9)
    assert np.all(got[:, 4] == 0.5)  # untouched roughness keeps the default


def test_generated_material_matches_the_reference(cli, tmp_path):
    V, F = uv_sphere()
    adaptex.write_obj(tmp_path / "s.obj", V, F)
    subprocess.run([cli, "strokes", "generate", str(tmp_path / "s.obj"), "--kind", "material", "--seed", "4", "-o",
                    str(tmp_path / "m.json")], check=True, capture_output=True)
    doc = json.loads((tmp_path / "m.json").read_text())
    faces, bary, P = sphere_samples(V, F, 4000, seed=9)
    np.testing.assert_allclose(adaptex.evaluate_material(V, F, tmp_path / "m.json", faces, bary), reference(doc, P),
                               rtol=0, atol=1e-9)


def test_bad_documents_raise_one_clear_error(sphere):
    V, F = sphere
    doc = every_mode_document()
    doc["layers"][0]["blend"] = "dodge"
    with pytest.raises(adaptex.InvalidInputError, match="layer 0: \"blend\" must be one of"):
        adaptex.evaluate_material(V, F, doc, [0], [[0.3, 0.3]])
    with pytest.raises(adaptex.InvalidInputError, match="faces\\[0\\] out of range"):
        adaptex.evaluate_material(V, F, every_mode_document(), [len(F)], [[0.3, 0.3]])
    with pytest.raises(adaptex.InvalidInputError, match="bary\\[0\\] is not finite"):
        adaptex.evaluate_material(V, F, every_mode_document(), [0], [[float("nan"), 0.3]])
