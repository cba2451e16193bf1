"""The package as a user meets it: signatures and numpy-style docstrings that list every option with
its default, Ctrl+C during a long call, write functions that never create folders, the version."""
import inspect
import os
import pydoc
import signal
import subprocess
import sys

import numpy as np
import pytest

import adaptex
from conftest import grid

HERE = os.path.dirname(os.path.abspath(__file__))
GROUPS = ("unwrap", "adapt", "reparam", "paint", "evaluate")


@pytest.mark.parametrize("name", GROUPS)
def test_help_lists_every_option_keyword_with_its_default(name):
    fn = getattr(adaptex, name)
    defaults = adaptex.option_defaults()[name]
    params = inspect.signature(fn).parameters
    text = pydoc.render_doc(fn, renderer=pydoc.plaintext)
    for key, default in defaults.items():
        assert params[key].kind == inspect.Parameter.KEYWORD_ONLY and params[key].default == default, key
        assert f"{key}={default!r}" in text, key  # the signature help() prints
        assert f"\n    {key} : " in fn.__doc__, key
    assert "Other Parameters" in fn.__doc__
    assert "KeyboardInterrupt" in fn.__doc__


def test_the_enum_keywords_list_their_names():
    assert "mode : {'none', 'single', 'two-stage', 'density-flow'}, default 'density-flow'" in adaptex.adapt.__doc__
    assert "schedule : {'end', 'each-stroke'}, default 'end'" in adaptex.adapt.__doc__
    assert "charts : {'auto', 'single'}, default 'auto'" in adaptex.unwrap.__doc__


@pytest.mark.parametrize("name", sorted(n for n in adaptex.__all__ if inspect.isfunction(getattr(adaptex, n))))
def test_every_function_has_named_arguments_and_numpy_sections(name):
    fn = getattr(adaptex, name)
    signature = inspect.signature(fn)
    assert "handle" not in str(signature) and "kwargs" not in str(signature)
    doc = fn.__doc__
    assert doc.split("\n")[0].strip(), "a one-line summary first"
    sections = [s for s in ("Parameters\n    ----------", "Returns\n    -------", "Raises\n    ------") if s in doc]
    assert sections, name
    for p in signature.parameters.values():
        if "Parameters\n    ----------" in doc and p.name not in adaptex.option_defaults().get(name, {}):
            assert f"\n    {p.name} : " in doc or f"\n    {p.name}\n" in doc, (name, p.name)
    for placeholder in ("{arrays}", "{layout}", "{strokes}", "{texture}", "{progress}", "{options}", "{raises"):
        assert placeholder not in doc, (name, placeholder)


def test_the_version_is_the_projects():
    with open(os.path.join(HERE, "..", "..", "VERSION")) as f:
        assert adaptex.__version__ == f.read().strip()


def test_write_functions_do_not_create_folders(tmp_path):
    V, F = grid(2)
    for path in (tmp_path / "missing" / "m.obj", tmp_path / "a" / "b" / "m.obj"):
        with pytest.raises(adaptex.OutputError, match="does not exist") as e:
            adaptex.write_obj(path, V, F)
        assert str(path) in str(e.value)
    with pytest.raises(adaptex.OutputError, match="does not exist"):
        adaptex.write_image(tmp_path / "missing" / "t.png", np.zeros((2, 2, 4), np.uint8))
    assert sorted(p.name for p in tmp_path.iterdir()) == []
    adaptex.write_obj(tmp_path / "m.obj", V, F)  # an existing folder still works
    assert (tmp_path / "m.obj").is_file()


CHILD = """
import sys, time
sys.path.insert(0, {here!r})
import adaptex
from conftest import dot_strokes, uv_sphere
V, F = uv_sphere(128, 64)
strokes = dot_strokes(count=400)
UV, FT, _ = adaptex.unwrap(V, F, texture_size=512)
print("calling", flush=True)
try:
    adaptex.adapt(V, F, UV, FT, strokes, texture_size=512, schedule="each-stroke", min_gain_db=0)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
"""


def test_ctrl_c_interrupts_a_long_call_without_a_callback():
    # 400 each-stroke re-parameterizations at 512² take minutes; Ctrl+C one second in must stop them.
    child = subprocess.Popen([sys.executable, "-c", CHILD.format(here=HERE)], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True, env=os.environ.copy())
    try:
        assert child.stdout.readline().strip() == "calling"
        try:
            child.wait(timeout=1.0)
        except subprocess.TimeoutExpired:
            pass
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=120)
    finally:
        if child.poll() is None:
            child.kill()
            child.communicate()
    assert "interrupted" in out and "finished" not in out, (out, err[-2000:])
    assert child.returncode == 0, err[-2000:]


def test_adapt_methods_come_from_the_registry():
    methods = adaptex.adapt_methods()
    assert list(methods)[:4] == ["none", "single", "two-stage", "density-flow"]
    assert all(isinstance(d, str) and d for d in methods.values())
    assert adaptex._adaptex._option_choices()["adapt"]["mode"] == list(methods)
    assert adaptex._adaptex._option_choices()["reparam"]["mode"] == ["shrink"] + list(methods)
