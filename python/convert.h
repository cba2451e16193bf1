#pragma once
/// \file convert.h
/// numpy <-> adaptex conversions of the Python module, libigl style (docs/python.md):
/// V #V x 3 float64, F #F x 3 int32, UV #W x 2 float64, FT #F x 3 int32 (row f: the UV rows of the
/// corners of face f), textures H x W x 4 uint8 with row 0 = v = 0 (the bottom of the picture,
/// OBJ convention, as adaptex and Blender store images). Inputs accept any floating-point dtype for
/// V / UV and any integer dtype for F / FT (values checked); a texture must be uint8.
/// Every check throws InvalidInputError (Python: adaptex.InvalidInputError, a ValueError) naming
/// the function and the argument.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include "adaptex/core/image.h"
#include "adaptex/core/mesh.h"
#include "adaptex/core/parameterization.h"
#include "adaptex/paint/material_strokes.h"
#include "adaptex/paint/strokes.h"

namespace adaptex::python {

namespace py = pybind11;

/// The mesh of (V, F). It must be as validate_mesh() returns it (no degenerate face, no unused
/// vertex, no pinched vertex, consistent winding): the outputs are then parallel to the inputs.
/// \throw InvalidInputError wrong shape / dtype, an index out of range, or a mesh validate_mesh() rejects
///        or would change (TopologyError for non-manifold edges)
TriMesh mesh_from_arrays(py::handle V, py::handle F, const char* fn);
/// The layout (UV, FT) of \p mesh: wedge w is row w of UV; every wedge must be used by some face
/// and with one vertex only; charts are the groups of faces sharing wedges (as read_textured_obj).
/// \throw InvalidInputError wrong shape / dtype, a non-finite UV, an index out of range, FT not
///        parallel to F, a wedge unused or used with two vertices
Parameterization param_from_arrays(const TriMesh& mesh, py::handle UV, py::handle FT, const char* fn);
/// The image of an H x W x 4 uint8 array (row 0 = v = 0).
/// \throw InvalidInputError wrong shape / dtype, a side outside [1, kMaxTextureSize]
ImageRGBA8 image_from_array(py::handle texture, const char* fn, const char* name);
/// A stroke file from a path (str or os.PathLike: read_strokes) or a dict in the adaptex.strokes
/// format (docs/strokes.md; decal images relative to the current directory). Unknown-field warnings
/// become Python UserWarnings.
/// \throw InvalidInputError / IoError as read_strokes / parse_strokes, or another type
StrokeFile strokes_from_object(py::handle strokes, const char* fn);
/// The same for a file of version 1 or 2 (read_material_strokes / parse_material_strokes).
MaterialStrokeFile material_strokes_from_object(py::handle strokes, const char* fn);

py::array_t<double> vertices_array(const TriMesh& mesh);        ///< #V x 3 float64
py::array_t<std::int32_t> faces_array(const std::vector<Face>& faces);  ///< #F x 3 int32
py::array_t<double> uv_array(const Parameterization& param);    ///< #W x 2 float64
py::array_t<std::uint8_t> image_array(const ImageRGBA8& image); ///< H x W x 4 uint8
/// A JSON value as Python objects (dict, list, float, ...).
py::object json_to_python(const nlohmann::json& value);
/// A report of report_json.h as a dict in its key order; numbers stay numbers (inf and nan too,
/// where JSON text would write null).
py::dict report_dict(const nlohmann::ordered_json& report);
/// Python warnings (UserWarning) for \p lines.
void warn_all(const std::vector<std::string>& lines);

}  // namespace adaptex::python
