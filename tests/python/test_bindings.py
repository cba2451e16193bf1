"""Every binding of the Python module on meshes built in code (conftest.py), its errors and its
progress / cancel callbacks."""
import json
import threading
import time

import numpy as np
import pytest

import adaptex
from conftest import dot_strokes, grid, uv_sphere


def signed_areas(UV, FT):
    a, b, c = UV[FT[:, 0]], UV[FT[:, 1]], UV[FT[:, 2]]
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def test_write_and_read_mesh_round_trip(tmp_path, sphere):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F)
    adaptex.write_obj(tmp_path / "m.obj", V, F, UV, FT)
    V2, F2 = adaptex.read_mesh(tmp_path / "m.obj")
    assert V2.dtype == np.float64 and F2.dtype == np.int32
    assert np.array_equal(V2, V) and np.array_equal(F2, F)
    V3, F3, UV3, FT3 = adaptex.read_textured_obj(str(tmp_path / "m.obj"))
    assert np.array_equal(V3, V) and np.array_equal(F3, F)
    assert np.array_equal(UV3, UV) and np.array_equal(FT3, FT)


def test_validate_mesh_drops_a_degenerate_face():
    V, F = grid(2)
    F_bad = np.vstack([F, [[0, 1, 2]]])  # collinear corners: zero area
    with pytest.warns(UserWarning):
        V2, F2, report = adaptex.validate_mesh(V, F_bad)
    assert report["dropped_degenerate_faces"] == 1
    assert np.array_equal(F2, F) and np.array_equal(V2, V)
    with pytest.raises(adaptex.InvalidInputError, match="validate_mesh"):
        adaptex.unwrap(V, F_bad)


def test_unwrap_gives_a_layout_without_flips_in_the_unit_square(sphere):
    V, F = sphere
    UV, FT, report = adaptex.unwrap(V, F)
    assert UV.dtype == np.float64 and UV.shape[1] == 2
    assert FT.dtype == np.int32 and FT.shape == F.shape
    assert UV.min() >= 0.0 and UV.max() <= 1.0
    assert (signed_areas(UV, FT) > 0).all()
    assert report["genus"] == 0 and report["charts"] >= 1
    assert report["face_chart"].shape == (len(F),)
    assert report["gutter"] == pytest.approx(8 / 1024) and report["requested_gutter"] == report["gutter"]
    s = adaptex.stretch(V, F, UV, FT)
    assert s["flipped"] == 0 and s["degenerate"] == 0
    assert s["l2"] == pytest.approx(report["final_l2"], rel=1e-9)
    # face_l2 is normalized like l2: its area-weighted RMS over the faces is l2.
    area = 0.5 * np.linalg.norm(np.cross(V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]), axis=1)
    assert s["face_l2"].shape == (len(F),)
    assert np.sqrt((area * s["face_l2"] ** 2).sum() / area.sum()) == pytest.approx(s["l2"], rel=1e-9)


def test_unwrap_keywords_are_the_library_options(sphere):
    V, F = sphere
    defaults = adaptex.option_defaults()["unwrap"]
    assert defaults["weights"] in ("mean-value", "shape-preserving")
    assert isinstance(defaults["yoshizawa_max_iterations"], int)
    _, _, floater = adaptex.unwrap(V, F, yoshizawa_max_iterations=0, charts="single")
    assert floater["charts"] == 1 and floater["yoshizawa_iterations"] == 0
    assert floater["final_l2"] == floater["floater_l2"]
    _, _, full = adaptex.unwrap(V, F, charts="single")
    assert full["final_l2"] < floater["final_l2"]
    # None keeps the default: the same layout as without the keyword.
    UV1, _, _ = adaptex.unwrap(V, F, max_charts=None)
    UV2, _, _ = adaptex.unwrap(V, F)
    assert np.array_equal(UV1, UV2)
    with pytest.raises(TypeError, match="yoshizawa_max_iterations"):
        adaptex.unwrap(V, F, yoshizawa_iterations=3)
    with pytest.raises(adaptex.InvalidInputError, match="charts must be one of"):
        adaptex.unwrap(V, F, charts="many")
    with pytest.raises(adaptex.InvalidInputError, match="must be an int"):
        adaptex.unwrap(V, F, max_charts=2.5)
    # The chart-count order of auto (12 first by default, 4 for the fewest charts) reaches the library.
    assert defaults["probe_first_charts"] == 12
    with pytest.raises(adaptex.InvalidInputError, match="chart counts"):
        adaptex.unwrap(V, F, probe_first_charts=-1)


def test_paint_from_dict_and_from_file_agree(tmp_path, sphere, strokes):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=64)
    tex = adaptex.paint(V, F, UV, FT, strokes, size=64)
    assert tex.shape == (64, 64, 4) and tex.dtype == np.uint8
    (tmp_path / "s.json").write_text(json.dumps(strokes))
    assert np.array_equal(adaptex.paint(V, F, UV, FT, tmp_path / "s.json", size=64), tex)
    blank = adaptex.paint(V, F, UV, FT, {"format": "adaptex.strokes", "version": 1, "strokes": []}, size=64)
    assert not np.array_equal(blank, tex)
    assert (blank[..., :3][blank[..., 3] == 255] == 255).all()  # white background in the charts
    rect = adaptex.paint(V, F, UV, FT, strokes, width=32, height=16)
    assert rect.shape == (16, 32, 4)


def test_evaluate_is_exact_for_a_blank_texture_and_finds_missing_paint(sphere, strokes):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=64)
    empty = {"format": "adaptex.strokes", "version": 1, "strokes": []}
    blank = adaptex.paint(V, F, UV, FT, empty, size=64)
    assert adaptex.evaluate(V, F, UV, FT, blank, empty, samples=5000)["psnr"] == 200.0
    painted = adaptex.paint(V, F, UV, FT, strokes, size=64)
    good = adaptex.evaluate(V, F, UV, FT, painted, strokes, samples=20000, seed=5)
    bad = adaptex.evaluate(V, F, UV, FT, blank, strokes, samples=20000, seed=5)
    assert good["samples"] == 20000 and good["seed"] == 5
    assert good["psnr"] > bad["psnr"] + 3.0


def test_adapt_beats_the_fixed_layout_at_the_same_size(sphere, strokes):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=64)
    fixed = adaptex.paint(V, F, UV, FT, strokes, size=64)
    r = adaptex.adapt(V, F, UV, FT, strokes, texture_size=64)
    assert r["texture"].shape == (64, 64, 4)
    assert r["F"].shape == r["FT"].shape and r["V"].shape[1] == 3
    assert r["reports"]["count"] == 1 and r["reports"]["accepted"] == 1
    assert (signed_areas(r["UV"], r["FT"]) > 0).all()
    psnr_fixed = adaptex.evaluate(V, F, UV, FT, fixed, strokes, samples=100000)["psnr"]
    psnr_adapt = adaptex.evaluate(r["V"], r["F"], r["UV"], r["FT"], r["texture"], strokes, samples=100000)["psnr"]
    assert psnr_adapt > psnr_fixed + 0.5
    # mode="none" is plain painting on the given layout.
    none = adaptex.adapt(V, F, UV, FT, strokes, texture_size=64, mode="none")
    assert np.array_equal(none["texture"], fixed) and np.array_equal(none["UV"], UV)


def test_reparam_keeps_the_mesh_and_resizes_the_texture(sphere, strokes):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=128)
    tex = adaptex.paint(V, F, UV, FT, strokes, size=128)
    r = adaptex.reparam(V, F, UV, FT, tex, size=32, refine=False, mode="density-flow")
    assert np.array_equal(r["V"], V) and np.array_equal(r["F"], F)
    assert r["texture"].shape == (32, 32, 4) and r["UV"].shape[1] == 2
    assert r["UV"].min() >= 0.0 and r["UV"].max() <= 1.0
    assert (signed_areas(r["UV"], r["FT"]) > 0).all()
    assert r["report"]["accepted"] is True
    assert not np.array_equal(r["UV"], UV)
    refined = adaptex.reparam(V, F, UV, FT, tex, mode="density-flow")
    assert refined["texture"].shape == tex.shape and len(refined["F"]) >= len(F)
    with pytest.raises(adaptex.InvalidInputError, match="mode"):
        adaptex.reparam(V, F, UV, FT, tex, mode="none")


def test_shrink_keeps_the_mesh_and_every_map_and_never_loses_to_downsizing(sphere, strokes):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=128)
    tex = adaptex.paint(V, F, UV, FT, strokes, size=128)
    flat = np.full((64, 64, 4), (128, 128, 255, 255), np.uint8)
    r = adaptex.shrink(V, F, UV, FT, {"base_color": tex, "normal": flat}, size=32)
    assert np.array_equal(r["V"], V) and np.array_equal(r["F"], F) and np.array_equal(r["FT"], FT)
    assert set(r["maps"]) == {"base_color", "normal"} and r["maps"]["normal"].shape == (32, 32, 4)
    assert np.array_equal(r["texture"], r["maps"]["base_color"])
    assert r["UV"].min() >= 0.0 and r["UV"].max() <= 1.0
    assert r["report"]["psnr"] >= r["report"]["psnr_downsized"]
    assert r["report"]["after"]["flipped"] == 0
    # reparam's default is the same shrink.
    d = adaptex.reparam(V, F, UV, FT, tex, size=32)
    assert d["UV"].tobytes() == adaptex.shrink(V, F, UV, FT, tex, size=32)["UV"].tobytes()
    with pytest.raises(adaptex.InvalidInputError, match="size"):
        adaptex.shrink(V, F, UV, FT, tex, size=4)


def test_stretch_of_an_isometric_and_of_a_mirrored_layout():
    V, F = grid(4)
    UV, FT = V[:, :2].copy(), F.copy()
    s = adaptex.stretch(V, F, UV, FT)
    assert s["l2"] == pytest.approx(1.0) and s["flipped"] == 0
    mirrored = UV.copy()
    mirrored[:, 0] = 1.0 - mirrored[:, 0]
    assert adaptex.stretch(V, F, mirrored, FT)["flipped"] == len(F)


def test_images_round_trip(tmp_path):
    rng = np.random.default_rng(1)
    tex = rng.integers(0, 256, size=(5, 7, 4), dtype=np.uint8)
    adaptex.write_image(tmp_path / "t.png", tex)
    assert np.array_equal(adaptex.read_image(tmp_path / "t.png"), tex)


# ---- errors -------------------------------------------------------------------------------------

def test_a_wrong_array_is_a_value_error_naming_it(sphere, strokes):
    V, F = sphere
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=32)
    tex = adaptex.paint(V, F, UV, FT, strokes, size=32)
    good = dict(V=V, F=F, UV=UV, FT=FT, texture=tex)
    bad = [
        ("V", V[:, :2], "shape"), ("V", V.astype(np.int32), "floating-point"), ("V", V[:, 0], "shape"),
        ("F", F[:, :2], "shape"), ("F", F.astype(np.float64), "integer"), ("F", F + len(V), "not a row of V"),
        ("UV", UV[:, :1], "shape"), ("UV", (UV * 100).astype(np.int64), "floating-point"),
        ("FT", FT[:-1], "one row per row of F"), ("FT", FT.astype(np.float32), "integer"),
        ("FT", FT[:, ::-1][:, :2], "shape"),
        ("texture", tex[..., :3], "shape"), ("texture", tex.astype(np.float32), "uint8"),
        ("texture", tex.astype(np.uint16), "uint8"), ("texture", "not an array", "uint8"),
    ]
    for name, value, what in bad:
        args = dict(good, **{name: value})
        with pytest.raises(adaptex.InvalidInputError, match=what) as e:
            adaptex.reparam(args["V"], args["F"], args["UV"], args["FT"], args["texture"], size=16)
        assert isinstance(e.value, ValueError) and name in str(e.value), (name, str(e.value))


def test_library_errors_map_to_python_types(tmp_path, sphere):
    V, F = sphere
    with pytest.raises(adaptex.IoError) as e:
        adaptex.read_mesh(tmp_path / "missing.obj")
    assert isinstance(e.value, OSError) and isinstance(e.value, ValueError) and "missing.obj" in str(e.value)
    (tmp_path / "a_file").write_text("not a folder")
    before = sorted(p.name for p in tmp_path.iterdir())
    with pytest.raises(OSError) as e:
        adaptex.write_image(tmp_path / "a_file" / "t.png", np.zeros((2, 2, 4), np.uint8))
    assert isinstance(e.value, adaptex.OutputError) and not isinstance(e.value, ValueError)
    with pytest.raises(adaptex.OutputError):
        adaptex.write_obj(tmp_path / "a_file" / "m.obj", V, F)
    assert sorted(p.name for p in tmp_path.iterdir()) == before  # no partial or temporary file left
    # An existing file is replaced only by a complete one: a bad array leaves it untouched.
    (tmp_path / "keep.png").write_bytes(b"old")
    with pytest.raises(adaptex.InvalidInputError):
        adaptex.write_image(tmp_path / "keep.png", np.zeros((2, 2, 3), np.uint8))
    assert (tmp_path / "keep.png").read_bytes() == b"old"
    fan_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1]], dtype=float)
    fan_F = np.array([[0, 1, 2], [1, 0, 3], [0, 1, 4]])
    with pytest.raises(adaptex.TopologyError) as e:
        adaptex.unwrap(fan_V, fan_F)
    assert isinstance(e.value, ValueError)
    with pytest.raises(adaptex.InvalidInputError, match="radius"):
        adaptex.paint(V, F, *adaptex.unwrap(V, F)[:2],
                      {"format": "adaptex.strokes", "version": 1, "strokes": [{"color": [0, 0, 0], "radius": -1,
                                                                               "dabs": [[0, 0, 1]]}]}, size=8)
    with pytest.raises(adaptex.InvalidInputError, match="strokes must be a path or a dict"):
        adaptex.paint(V, F, *adaptex.unwrap(V, F)[:2], 42, size=8)


# ---- progress, cancel, GIL ----------------------------------------------------------------------

def test_progress_reports_phases_and_a_false_return_cancels(sphere, strokes):
    V, F = sphere
    seen = []
    UV, FT, _ = adaptex.unwrap(V, F, progress=lambda phase, f: seen.append((phase, f)))
    phases = {p for p, _ in seen}
    assert {"cut", "pack"} <= phases and all(0.0 <= f <= 1.0 for _, f in seen)
    with pytest.raises(adaptex.CancelledError):
        adaptex.unwrap(V, F, progress=lambda phase, f: False)
    calls = []

    def stop_after_3(phase, fraction):
        calls.append(phase)
        return len(calls) < 3

    with pytest.raises(adaptex.CancelledError):
        adaptex.adapt(V, F, UV, FT, strokes, texture_size=32, progress=stop_after_3)
    assert len(calls) == 3  # nothing is called once cancelled
    tex = adaptex.paint(V, F, UV, FT, strokes, size=32)
    with pytest.raises(adaptex.CancelledError):
        adaptex.paint(V, F, UV, FT, strokes, size=32, progress=lambda p, f: f < 0.5)
    with pytest.raises(adaptex.CancelledError):
        adaptex.reparam(V, F, UV, FT, tex, progress=lambda p, f: False)
    fractions = []
    done = adaptex.evaluate(V, F, UV, FT, tex, strokes, samples=200000,
                            progress=lambda p, f: fractions.append((p, f)))
    assert done["samples"] == 200000
    assert {p for p, _ in fractions} == {"eval"} and len(fractions) > 10
    assert fractions[0][1] == 0.0 and fractions[-1][1] == 1.0
    assert all(a[1] <= b[1] for a, b in zip(fractions, fractions[1:]))
    halfway = []
    with pytest.raises(adaptex.CancelledError):
        adaptex.evaluate(V, F, UV, FT, tex, strokes, samples=200000,
                         progress=lambda p, f: halfway.append(f) or f < 0.5)
    assert 0.5 <= halfway[-1] < 1.0  # stopped at the first report past half way


def test_an_exception_in_the_callback_cancels_and_propagates(sphere):
    V, F = sphere

    class Stop(Exception):
        pass

    def boom(phase, fraction):
        raise Stop(phase)

    with pytest.raises(Stop):
        adaptex.unwrap(V, F, progress=boom)


def test_long_calls_release_the_gil():
    V, F = uv_sphere(96, 48)
    strokes = dot_strokes(count=200)
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=256)
    entered, done = threading.Event(), threading.Event()
    ticks = 0

    def work():
        entered.set()
        adaptex.adapt(V, F, UV, FT, strokes, texture_size=256)
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    entered.wait()
    start = time.perf_counter()
    while not done.is_set() and worker.is_alive():
        ticks += 1  # pure Python: runs only while the worker does not hold the GIL
    elapsed = time.perf_counter() - start
    worker.join()
    assert done.is_set()
    # The main thread kept running while adapt() computed. With the GIL held it would get its first
    # turn only after adapt() returned (no progress callback is given), with done about to be set.
    assert elapsed > 0.05 and ticks > 10000, (elapsed, ticks)
