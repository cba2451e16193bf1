"""adaptex: signal-adaptive texture parameterization for painted meshes (docs/python.md).

Arrays follow libigl's conventions:

* ``V``  #V x 3 float64 vertex positions, ``F`` #F x 3 int32 triangles (rows of V);
* ``UV`` #W x 2 float64 texture coordinates, ``FT`` #F x 3 int32 (row f: the UV rows of face f's
  corners, like OBJ's ``f v/vt``);
* textures H x W x 4 uint8 RGBA, row 0 = v = 0 (the *bottom* of the picture, OBJ convention; use
  ``origin="lower"`` with matplotlib's imshow).

Inputs accept any floating-point dtype for V / UV and any integer dtype for F / FT. Errors are
``adaptex.Error`` subclasses: bad input raises ``InvalidInputError`` (a ``ValueError``; also
``TopologyError``), a file that cannot be read ``IoError`` (``ValueError`` and ``OSError``), one that
cannot be written ``OutputError`` (``OSError``). Long calls (unwrap, paint, adapt, reparam,
evaluate, shrink) release the GIL and take ``progress(phase, fraction)``: returning ``False`` cancels
the call with ``CancelledError``; Ctrl+C interrupts them with ``KeyboardInterrupt``.
``help(adaptex.adapt)`` lists every option keyword with its default.
"""
from ._version import __version__  # noqa: F401
from ._adaptex import (  # noqa: F401
    CancelledError,
    Error,
    InvalidInputError,
    IoError,
    OutputError,
    SolverError,
    TopologyError,
)
from ._functions import (  # noqa: F401
    adapt,
    adapt_methods,
    evaluate,
    evaluate_material,
    option_defaults,
    paint,
    read_image,
    read_mesh,
    read_textured_obj,
    reparam,
    shrink,
    stretch,
    unwrap,
    validate_mesh,
    write_image,
    write_obj,
)

__all__ = [name for name in dir() if not name.startswith("_")]
