"""The functions of the adaptex package: thin wrappers of the extension (_adaptex) that carry real
signatures and numpy-style docstrings. The option keywords, their defaults and the names an enum
keyword accepts come from the library itself (option_defaults()), so help() always shows the
library's current defaults."""
import inspect

from . import _adaptex

_ARRAYS = """    V : (#V, 3) array_like of float
        Vertex positions (any floating-point dtype; float64 is used).
    F : (#F, 3) array_like of int
        Triangles: rows of ``V``, counter-clockwise from the front. ``(V, F)`` must be a mesh as
        :func:`validate_mesh` returns it."""
_LAYOUT = """    UV : (#W, 2) array_like of float
        Texture coordinates of the wedges.
    FT : (#F, 3) array_like of int
        Row f: the ``UV`` rows of face f's corners (OBJ's ``f v/vt``)."""
_STROKES = """    strokes : str, os.PathLike or dict
        A stroke file (docs/strokes.md), as a path or as the parsed dict. Unknown fields are
        reported as ``UserWarning``."""
_TEXTURE = """    texture : (H, W, 4) array_like of uint8
        RGBA texture; row 0 is v = 0, the bottom of the picture."""
_PROGRESS = """    progress : callable or None, default None
        ``progress(phase: str, fraction: float)`` is called as the work advances (from any thread,
        with the GIL held); returning ``False`` cancels the call with :class:`CancelledError`, and
        an exception it raises cancels it and is re-raised. Ctrl+C (``KeyboardInterrupt``) stops
        the call at its next progress report with or without a callback."""
_OPTIONS = """    **options
        The option keywords listed under Other Parameters. A keyword left out, or given as
        ``None``, keeps the library's default."""
_RAISES_INPUT = """    InvalidInputError
        An array of the wrong shape or dtype, a bad option value, a mesh the operation rejects.
    TypeError
        An unknown keyword (the message lists the known ones)."""
_RAISES_LONG = _RAISES_INPUT + """
    CancelledError
        ``progress`` returned ``False``.
    KeyboardInterrupt
        Ctrl+C during the call."""
_STRUCTS = {
    "unwrap": "UnwrapOptions (include/adaptex/param/unwrap.h)",
    "adapt": "PaintSessionOptions and its AdaptOptions (include/adaptex/adapt/session.h, adapt.h)",
    "reparam": "AdaptOptions (include/adaptex/adapt/adapt.h)",
    "paint": "PainterOptions (include/adaptex/paint/painter.h)",
    "evaluate": "EvalOptions (include/adaptex/paint/eval.h)",
}


def _type_name(default, choices):
    if choices:
        return "{" + ", ".join(repr(c) for c in choices) + "}"
    return type(default).__name__


def _with_options(group):
    """Gives the wrapped function the option keywords of \\p group in its signature and docstring."""

    def decorate(fn):
        defaults = _adaptex.option_defaults()[group]
        choices = _adaptex._option_choices()[group]
        signature = inspect.signature(fn)
        params = [p for p in signature.parameters.values() if p.kind != inspect.Parameter.VAR_KEYWORD]
        explicit = {p.name for p in params}
        lines = ["", "    Other Parameters", "    ----------------",
                 f"    The fields of {_STRUCTS[group]},", "    under the same names:"]
        for name, default in defaults.items():
            if name in explicit:
                continue
            params.append(inspect.Parameter(name, inspect.Parameter.KEYWORD_ONLY, default=default))
            lines.append(f"    {name} : {_type_name(default, choices.get(name))}, default {default!r}")
        fn.__signature__ = signature.replace(parameters=params)
        fn.__doc__ = fn.__doc__.rstrip() + "\n" + "\n".join(lines) + "\n"
        return fn

    return decorate


def read_mesh(path, *, repair=False):
    """Read a triangle mesh.

    Parameters
    ----------
    path : str or os.PathLike
        OBJ, OFF, PLY, STL or glTF/GLB file.
    repair : bool, default False
        Repair what can be repaired (drop degenerate and duplicate faces, split non-manifold and
        pinched vertices) instead of rejecting the file.

    Returns
    -------
    V : (#V, 3) ndarray of float64
    F : (#F, 3) ndarray of int32

    Raises
    ------
    IoError
        The file cannot be read, is corrupt or is not a valid mesh (also ``OSError``).
    """
    return _adaptex.read_mesh(path, repair=repair)


def validate_mesh(V, F, *, repair=False):
    """Validate (and with ``repair``, repair) a mesh given as arrays, as :func:`read_mesh` does.

    Parameters
    ----------
{arrays}
    repair : bool, default False
        Repair instead of rejecting.

    Returns
    -------
    V : (#V, 3) ndarray of float64
    F : (#F, 3) ndarray of int32
        The mesh with degenerate faces and unused vertices dropped, pinched vertices split and the
        winding made consistent.
    report : dict
        What was changed: ``dropped_degenerate_faces``, ``dropped_unreferenced_vertices``,
        ``dropped_duplicate_faces``, ``split_nonmanifold_vertices``, ``split_pinched_vertices``,
        ``flipped_faces``, ``welded_vertices`` (the keys of ``adaptex unwrap --report``'s ``repair``).

    Raises
    ------
{raises}
    """
    return _adaptex.validate_mesh(V, F, repair=repair)


def read_textured_obj(path):
    """Read an OBJ with texture coordinates (``vt``, ``f v/vt``).

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    V : (#V, 3) ndarray of float64
    F : (#F, 3) ndarray of int32
    UV : (#W, 2) ndarray of float64
    FT : (#F, 3) ndarray of int32

    Raises
    ------
    IoError
        The file cannot be read, or has no usable texture coordinates.
    """
    return _adaptex.read_textured_obj(path)


def write_obj(path, V, F, UV=None, FT=None):
    """Write an OBJ (``v``, ``vt``, ``f v/vt``) at round-trip precision, all or nothing.

    The file is written under a temporary name and renamed on success. The folder must exist: it is
    never created.

    Parameters
    ----------
    path : str or os.PathLike
{arrays}
{layout}
        Give both ``UV`` and ``FT``, or neither.

    Raises
    ------
    OutputError
        The folder does not exist, or the file cannot be written (also ``OSError``).
{raises}
    """
    return _adaptex.write_obj(path, V, F, UV, FT)


def read_image(path):
    """Read a PNG.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    texture : (H, W, 4) ndarray of uint8
        RGBA; row 0 is v = 0, the bottom row of the PNG.

    Raises
    ------
    IoError
        The file cannot be read or is not a valid PNG.
    """
    return _adaptex.read_image(path)


def write_image(path, texture):
    """Write a texture as a PNG (row 0 of ``texture`` is the bottom row), all or nothing.

    Parameters
    ----------
    path : str or os.PathLike
        The folder must exist: it is never created.
{texture}

    Raises
    ------
    OutputError
        The folder does not exist, or the file cannot be written.
    InvalidInputError
        ``texture`` is not an (H, W, 4) uint8 array.
    """
    return _adaptex.write_image(path, texture)


def unwrap(V, F, *, progress=None, texture_size=None, padding=None, **options):
    """Cut the mesh to disks, parameterize and pack them (``adaptex unwrap``).

    Parameters
    ----------
{arrays}
{progress}
    texture_size : int or None, default None
        With ``padding``: leave the gutter between charts that a texture of this size needs, as
        ``adaptex paint --size`` does (default: the options' own gutter).
    padding : int or None, default None
        Seam padding in texels of ``texture_size``.
{options}

    Returns
    -------
    UV : (#W, 2) ndarray of float64
    FT : (#F, 3) ndarray of int32
    report : dict
        ``components``, ``genus``, ``boundary_loops``, ``charts``, ``cut_length``,
        ``augmentations``, ``yoshizawa_iterations``, ``floater_l2``, ``floater_linf``,
        ``final_l2``, ``final_linf``, ``coverage``, ``effective_texel_share``, ``gutter`` and
        ``requested_gutter`` (the gap between charts kept and asked for, fractions of the unit
        square: many charts are packed with a narrower one), ``time`` (seconds
        per phase: cut, segment, floater, yoshizawa, augment, layouts, pack, total; the names of
        ``adaptex unwrap --report``) and ``face_chart`` (#F).

    Raises
    ------
{raises_long}
    """
    return _adaptex.unwrap(V, F, progress=progress, texture_size=texture_size, padding=padding, **options)


def paint(V, F, UV, FT, strokes, *, progress=None, size=None, **options):
    """Paint strokes exactly on a fixed layout.

    Parameters
    ----------
{arrays}
{layout}
{strokes}
{progress}
    size : int or None, default None
        Texture width and height (default: the options' ``width`` and ``height``).
{options}

    Returns
    -------
    texture : (H, W, 4) ndarray of uint8

    Raises
    ------
{raises_long}
    """
    return _adaptex.paint(V, F, UV, FT, strokes, progress=progress, size=size, **options)


def adapt(V, F, UV, FT, strokes, *, progress=None, **options):
    """Paint strokes and re-parameterize the mesh by them (what ``adaptex paint`` does after its unwrap).

    Parameters
    ----------
{arrays}
{layout}
        The initial layout, e.g. from :func:`unwrap`.
{strokes}
{progress}
{options}

    Returns
    -------
    dict
        ``V``, ``F``: the mesh (with refinement, the refined mesh: same surface, more faces);
        ``UV``, ``FT``: the adapted layout; ``texture``: (H, W, 4) uint8, the strokes painted on
        it; ``reports``: the re-parameterizations, as in ``adaptex paint``'s report.json.

    Raises
    ------
{raises_long}
    """
    return _adaptex.adapt(V, F, UV, FT, strokes, progress=progress, **options)


def reparam(V, F, UV, FT, texture, *, progress=None, size=None, padding=None, **options):
    """Make a textured mesh's texture smaller on a better layout (``adaptex reparam``).

    With ``mode='shrink'`` (the default) this is :func:`shrink` of the one texture; the other
    modes re-parameterize by the texture's signal and resample it onto the new layout.

    Parameters
    ----------
{arrays}
{layout}
{texture}
        Painted on ``(UV, FT)``.
{progress}
    size : int or None, default None
        Width and height of the new texture (default: the input's).
    padding : int or None, default None
        Seam padding of the new texture in texels (default: the painter's).
{options}

    Returns
    -------
    dict
        ``V``, ``F``, ``UV``, ``FT``, ``texture`` (as :func:`adapt`) and ``report``: the
        shrink's or the re-parameterization's report. ``refine=False`` keeps the mesh (the
        shrink always keeps it).

    Raises
    ------
{raises_long}
    """
    return _adaptex.reparam(V, F, UV, FT, texture, progress=progress, size=size, padding=padding, **options)


def shrink(V, F, UV, FT, maps, *, progress=None, size=256):
    """Shrink a textured mesh's maps onto the artist's atlas, repacked by detail (``adaptex shrink``).

    The artist's charts stay charts; charts that share texels (mirrors, overlaps) move together;
    every island gets texels by the error model of the maps and the islands are repacked into the
    square; every map is fitted to the original on the new layout. Plain downsizing is a candidate,
    so the result is never worse than it on the measure (docs/shrink.md).

    Parameters
    ----------
{arrays}
{layout}
    maps : (H, W, 4) array_like of uint8, or dict of str to such arrays
        The texture, or ``{{slot: texture}}`` for every map of the material (``'base_color'``,
        ``'normal'``, ``'roughness'``, ...); the first is the measured one. Painted on ``(UV, FT)``.
{progress}
    size : int, default 256
        Width and height of every output map.

    Returns
    -------
    dict
        ``V``, ``F``, ``FT`` (the input's), ``UV`` (the new layout), ``texture`` (the first map),
        ``maps`` (``{{slot: map}}``) and ``report``: the PSNR of the result and of plain
        downsizing, the candidates, flips and shared texels before and after.

    Raises
    ------
{raises_long}
    """
    return _adaptex.shrink(V, F, UV, FT, maps, progress=progress, size=size)


def evaluate(V, F, UV, FT, texture, strokes, *, progress=None, **options):
    """PSNR of a texture against the exact stroke signal (``adaptex eval``).

    Parameters
    ----------
{arrays}
{layout}
{texture}
{strokes}
{progress}
{options}

    Returns
    -------
    dict
        ``mse``, ``psnr`` (dB), ``samples``, ``seed``.

    Raises
    ------
{raises_long}
    """
    return _adaptex.evaluate(V, F, UV, FT, texture, strokes, progress=progress, **options)


def stretch(V, F, UV, FT):
    """Stretch of a layout (Sander et al.; 1 is ideal).

    Parameters
    ----------
{arrays}
{layout}

    Returns
    -------
    dict
        ``l2``, ``linf``, ``area_distortion``, ``angle_distortion``, ``flipped``, ``degenerate``
        and ``face_l2`` (#F, the L2 stretch of every face).

    Raises
    ------
{raises}
    """
    return _adaptex.stretch(V, F, UV, FT)


def evaluate_material(V, F, strokes, faces, bary):
    """Every channel of a stroke file, version 1 or 2 (layers, masks, blend modes, pressure), at
    surface points: the exact painted material (docs/strokes.md, "Version 2").

    Parameters
    ----------
{arrays}
{strokes}
    faces : (#P,) array_like of int
        The face of each point.
    bary : (#P, 2) array_like of float
        Barycentric coordinates (b0, b1) of each point: the point is
        ``b0 V[F[f, 0]] + b1 V[F[f, 1]] + (1 - b0 - b1) V[F[f, 2]]``.

    Returns
    -------
    (#P, 7) ndarray of float64
        Columns r, g, b (base colour), alpha, roughness, metallic, height, each in [0, 1].

    Raises
    ------
{raises}
    """
    return _adaptex.evaluate_material(V, F, strokes, faces, bary)


def option_defaults():
    """The library's default of every option keyword.

    Returns
    -------
    dict
        ``{function: {keyword: default}}`` for ``unwrap``, ``adapt``, ``reparam``, ``paint`` and
        ``evaluate``.
    """
    return _adaptex.option_defaults()


def adapt_methods():
    """The registered adaptation methods: the names the ``mode`` keyword of :func:`adapt` and
    :func:`reparam` accepts (``reparam`` also takes ``"shrink"``), read from the library's registry.

    Returns
    -------
    dict
        ``{name: one-line description}``, ``"none"`` first, then the built-in methods, then those
        registered later.
    """
    return _adaptex.adapt_methods()


def _fill(fn):
    fn.__doc__ = fn.__doc__.format(arrays=_ARRAYS, layout=_LAYOUT, strokes=_STROKES, texture=_TEXTURE,
                                   progress=_PROGRESS, options=_OPTIONS, raises=_RAISES_INPUT,
                                   raises_long=_RAISES_LONG)


for _fn in (validate_mesh, write_obj, write_image, unwrap, paint, adapt, reparam, shrink, evaluate,
            evaluate_material, stretch):
    _fill(_fn)
for _fn in (unwrap, paint, adapt, reparam, evaluate):
    _with_options(_fn.__name__)(_fn)
