"""The Python module gives the same results as the `adaptex` CLI on the same input: bit-equal UVs,
identical texture bytes, the same PSNR."""
import json
import subprocess

import numpy as np
import pytest

import adaptex


def run(cli, *args):
    r = subprocess.run([cli, "-q", *map(str, args)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stdout


@pytest.fixture
def files(tmp_path, sphere, strokes):
    V, F = sphere
    adaptex.write_obj(tmp_path / "ball.obj", V, F)
    (tmp_path / "s.json").write_text(json.dumps(strokes))
    return tmp_path


def test_unwrap_equals_the_cli(cli, files, sphere):
    V, F = sphere
    run(cli, "unwrap", files / "ball.obj", "-o", files / "u.obj")
    _, F2, UV2, FT2 = adaptex.read_textured_obj(files / "u.obj")
    UV, FT, _ = adaptex.unwrap(V, F)
    assert np.array_equal(F2, F)
    assert UV.tobytes() == UV2.tobytes() and np.array_equal(FT, FT2)


@pytest.mark.parametrize("mode", ["density-flow", "none"])
def test_paint_equals_the_cli(cli, files, sphere, strokes, mode):
    V, F = sphere
    out = files / ("p-" + mode)
    run(cli, "paint", files / "ball.obj", "--strokes", files / "s.json", "--size", 64, "--adapt", mode, "-o", out)
    V2, F2, UV2, FT2 = adaptex.read_textured_obj(out / "ball.obj")
    png = adaptex.read_image(out / "ball.png")
    UV, FT, _ = adaptex.unwrap(V, F, texture_size=64)
    r = adaptex.adapt(V, F, UV, FT, files / "s.json", texture_size=64, mode=mode)
    assert np.array_equal(r["V"], V2) and np.array_equal(r["F"], F2)
    assert r["UV"].tobytes() == UV2.tobytes() and np.array_equal(r["FT"], FT2)
    assert r["texture"].tobytes() == png.tobytes()
    if mode == "none":
        assert adaptex.paint(V, F, UV, FT, strokes, size=64).tobytes() == png.tobytes()


def test_reparam_and_eval_equal_the_cli(cli, files, sphere):
    V, F = sphere
    run(cli, "paint", files / "ball.obj", "--strokes", files / "s.json", "--size", 96, "--adapt", "none",
        "-o", files / "p")
    V1, F1, UV1, FT1 = adaptex.read_textured_obj(files / "p" / "ball.obj")
    tex = adaptex.read_image(files / "p" / "ball.png")
    run(cli, "reparam", files / "p" / "ball.obj", files / "p" / "ball.png", "--size", 48, "-o", files / "r")
    V2, F2, UV2, FT2 = adaptex.read_textured_obj(files / "r" / "ball.obj")
    r = adaptex.reparam(V1, F1, UV1, FT1, tex, size=48)
    assert np.array_equal(r["V"], V2) and np.array_equal(r["F"], F2)
    assert r["UV"].tobytes() == UV2.tobytes() and np.array_equal(r["FT"], FT2)
    assert r["texture"].tobytes() == adaptex.read_image(files / "r" / "ball.png").tobytes()
    e = json.loads(run(cli, "eval", files / "r" / "ball.obj", files / "r" / "ball.png", files / "s.json",
                       "--samples", 30000, "--seed", 7))
    mine = adaptex.evaluate(r["V"], r["F"], r["UV"], r["FT"], r["texture"], files / "s.json", samples=30000, seed=7)
    assert mine["psnr"] == e["psnr"] and mine["mse"] == e["mse"]
