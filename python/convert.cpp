// numpy <-> adaptex conversions of the Python module (convert.h).
#include "convert.h"

#include <cmath>
#include <filesystem>
#include <string>

#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/core/union_find.h"
#include "adaptex/io/mesh_io.h"

namespace adaptex::python {

namespace {

enum class Kind { Floating, Integer, Byte };

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// \p obj as a numpy array (np.asarray) with \p ndim dimensions, \p last columns in its last one and
/// a dtype of kind \p kind. \p expected describes the shape in messages, e.g. "(#V, 3)".
py::array checked_array(py::handle obj, const char* fn, const char* name, Kind kind, int ndim, py::ssize_t last,
                        const char* expected) {
  static const char* const kinds[] = {"a floating-point", "an integer", "a uint8"};
  const std::string want = std::string(fn) + ": " + name + " must be " + kinds[static_cast<int>(kind)] +
                           " array of shape " + expected;
  py::array a = py::array::ensure(obj);
  if (!a) {
    PyErr_Clear();
    throw InvalidInputError(want + ", got " + std::string(py::str(py::type::handle_of(obj).attr("__name__"))));
  }
  const char k = a.dtype().kind();
  const bool kind_ok = kind == Kind::Floating  ? k == 'f'
                       : kind == Kind::Integer ? (k == 'i' || k == 'u')
                                               : (k == 'u' && a.dtype().itemsize() == 1);
  const bool shape_ok = a.ndim() == ndim && a.shape(ndim - 1) == last;
  if (!kind_ok || !shape_ok)
    throw InvalidInputError(want + ", got a " + std::string(py::str(a.dtype())) + " array of shape " + shape_text(a));
  return a;
}

/// Rows of an integer array as int64 (C order), each value checked to be in [0, bound).
py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> index_rows(py::handle obj, const char* fn,
                                                                                 const char* name, py::ssize_t bound,
                                                                                 const char* bound_name) {
  auto a = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(
      checked_array(obj, fn, name, Kind::Integer, 2, 3, "(#F, 3)"));
  const std::int64_t* p = a.data();
  for (py::ssize_t i = 0; i < a.size(); ++i)
    if (p[i] < 0 || p[i] >= bound)
      throw InvalidInputError(std::string(fn) + ": " + name + "[" + std::to_string(i / 3) + ", " +
                              std::to_string(i % 3) + "] = " + std::to_string(p[i]) + " is not a row of " +
                              bound_name + " (it has " + std::to_string(bound) + " rows)");
  return a;
}

py::array_t<double, py::array::c_style | py::array::forcecast> float_rows(py::handle obj, const char* fn,
                                                                          const char* name, int cols,
                                                                          const char* expected) {
  return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(
      checked_array(obj, fn, name, Kind::Floating, 2, cols, expected));
}

}  // namespace

TriMesh mesh_from_arrays(py::handle V, py::handle F, const char* fn) {
  const auto v = float_rows(V, fn, "V", 3, "(#V, 3)");
  const auto f = index_rows(F, fn, "F", v.shape(0), "V");
  TriMesh mesh;
  mesh.positions.resize(static_cast<size_t>(v.shape(0)));
  for (size_t i = 0; i < mesh.positions.size(); ++i) mesh.positions[i] = Vec3(v.at(i, 0), v.at(i, 1), v.at(i, 2));
  mesh.faces.resize(static_cast<size_t>(f.shape(0)));
  for (size_t i = 0; i < mesh.faces.size(); ++i)
    mesh.faces[i] = {static_cast<int>(f.at(i, 0)), static_cast<int>(f.at(i, 1)), static_cast<int>(f.at(i, 2))};
  ReadReport rep;
  const TriMesh checked = validate_mesh(mesh, fn, {}, &rep);
  const int changes = rep.dropped_degenerate_faces + rep.dropped_unreferenced_vertices + rep.split_pinched_vertices +
                      rep.flipped_faces + rep.dropped_duplicate_faces + rep.split_nonmanifold_vertices;
  if (changes > 0)
    throw InvalidInputError(std::string(fn) + ": (V, F) must be a valid mesh as adaptex.validate_mesh returns it (" +
                            (rep.warnings.empty() ? std::string("it changes it") : rep.warnings.front()) +
                            "): call V, F, _ = adaptex.validate_mesh(V, F) first");
  return mesh;
}

Parameterization param_from_arrays(const TriMesh& mesh, py::handle UV, py::handle FT, const char* fn) {
  const auto uv = float_rows(UV, fn, "UV", 2, "(#W, 2)");
  const auto ft = index_rows(FT, fn, "FT", uv.shape(0), "UV");
  const std::string where = std::string(fn) + ": ";
  if (ft.shape(0) != mesh.num_faces())
    throw InvalidInputError(where + "FT must have one row per row of F (" + std::to_string(mesh.num_faces()) +
                            "), got " + std::to_string(ft.shape(0)));
  Parameterization param;
  param.uv.resize(static_cast<size_t>(uv.shape(0)));
  for (size_t w = 0; w < param.uv.size(); ++w) {
    param.uv[w] = Vec2(uv.at(w, 0), uv.at(w, 1));
    if (!param.uv[w].allFinite()) throw InvalidInputError(where + "UV[" + std::to_string(w) + "] is not finite");
  }
  param.wedge_vertex.assign(param.uv.size(), -1);
  param.uv_faces.resize(mesh.faces.size());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int w = static_cast<int>(ft.at(f, k)), v = mesh.faces[f][k];
      param.uv_faces[f][k] = w;
      if (param.wedge_vertex[w] >= 0 && param.wedge_vertex[w] != v)
        throw InvalidInputError(where + "UV row " + std::to_string(w) + " is used with vertices " +
                                std::to_string(param.wedge_vertex[w]) + " and " + std::to_string(v) +
                                " (FT must give each UV row to one vertex)");
      param.wedge_vertex[w] = v;
    }
  for (size_t w = 0; w < param.uv.size(); ++w)
    if (param.wedge_vertex[w] < 0)
      throw InvalidInputError(where + "UV row " + std::to_string(w) + " is used by no face (FT must use every row)");
  // Charts: the faces connected through shared wedges, numbered in face order.
  UnionFind groups(param.num_wedges());
  for (const Face& t : param.uv_faces)
    for (int k = 1; k < 3; ++k) groups.unite(t[0], t[k]);
  std::vector<int> chart(param.uv.size(), -1);
  param.face_chart.reserve(mesh.faces.size());
  for (const Face& t : param.uv_faces) {
    int& c = chart[groups.find(t[0])];
    if (c < 0) c = param.num_charts++;
    param.face_chart.push_back(c);
  }
  return param;
}

ImageRGBA8 image_from_array(py::handle texture, const char* fn, const char* name) {
  const auto a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(
      checked_array(texture, fn, name, Kind::Byte, 3, 4, "(H, W, 4)"));
  const py::ssize_t h = a.shape(0), w = a.shape(1);
  if (h < 1 || w < 1 || h > kMaxTextureSize || w > kMaxTextureSize)
    throw InvalidInputError(std::string(fn) + ": " + name + " must be 1 to " + std::to_string(kMaxTextureSize) +
                            " texels on a side, got " + std::to_string(h) + " x " + std::to_string(w));
  ImageRGBA8 img(static_cast<int>(w), static_cast<int>(h));
  std::copy(a.data(), a.data() + a.size(), img.data.begin());
  return img;
}

namespace {

/// Reads \p strokes (a dict or a path) with \p from_text / \p from_path.
template <class File, class FromText, class FromPath>
File stroke_file_from_object(py::handle strokes, const char* fn, FromText from_text, FromPath from_path) {
  File file;
  if (py::isinstance<py::dict>(strokes)) {
    const std::string text = py::str(py::module_::import("json").attr("dumps")(strokes));
    file = from_text(text, std::string(fn) + ": strokes", std::filesystem::current_path());
  } else if (py::isinstance<py::str>(strokes) || py::hasattr(strokes, "__fspath__")) {
    file = from_path(std::filesystem::path(py::str(py::module_::import("os").attr("fspath")(strokes))));
  } else {
    throw InvalidInputError(std::string(fn) + ": strokes must be a path or a dict in the adaptex.strokes format "
                            "(docs/strokes.md), got " +
                            std::string(py::str(py::type::handle_of(strokes).attr("__name__"))));
  }
  warn_all(file.warnings);
  return file;
}

}  // namespace

StrokeFile strokes_from_object(py::handle strokes, const char* fn) {
  return stroke_file_from_object<StrokeFile>(strokes, fn, parse_strokes,
                                             [](const std::filesystem::path& p) { return read_strokes(p); });
}

MaterialStrokeFile material_strokes_from_object(py::handle strokes, const char* fn) {
  return stroke_file_from_object<MaterialStrokeFile>(
      strokes, fn, parse_material_strokes, [](const std::filesystem::path& p) { return read_material_strokes(p); });
}

namespace {

/// An n x N array of \p rows (each indexable by [0, N): Vec3, Vec2, Face).
template <class Out, py::ssize_t N, class Row>
py::array_t<Out> rows_array(const std::vector<Row>& rows) {
  py::array_t<Out> out({static_cast<py::ssize_t>(rows.size()), N});
  auto r = out.template mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (py::ssize_t k = 0; k < N; ++k) r(i, k) = static_cast<Out>(rows[static_cast<size_t>(i)][k]);
  return out;
}

}  // namespace

py::array_t<double> vertices_array(const TriMesh& mesh) { return rows_array<double, 3>(mesh.positions); }
py::array_t<std::int32_t> faces_array(const std::vector<Face>& faces) { return rows_array<std::int32_t, 3>(faces); }
py::array_t<double> uv_array(const Parameterization& param) { return rows_array<double, 2>(param.uv); }

py::array_t<std::uint8_t> image_array(const ImageRGBA8& image) {
  py::array_t<std::uint8_t> out({py::ssize_t{image.height}, py::ssize_t{image.width}, py::ssize_t{4}});
  std::copy(image.data.begin(), image.data.end(), out.mutable_data());
  return out;
}

py::object json_to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

namespace {

py::object to_python(const nlohmann::ordered_json& v) {
  switch (v.type()) {
    case nlohmann::ordered_json::value_t::object: {
      py::dict d;
      for (const auto& [key, value] : v.items()) d[py::str(key)] = to_python(value);
      return d;
    }
    case nlohmann::ordered_json::value_t::array: {
      py::list l;
      for (const auto& value : v) l.append(to_python(value));
      return l;
    }
    case nlohmann::ordered_json::value_t::boolean: return py::bool_(v.get<bool>());
    case nlohmann::ordered_json::value_t::number_integer: return py::int_(v.get<std::int64_t>());
    case nlohmann::ordered_json::value_t::number_unsigned: return py::int_(v.get<std::uint64_t>());
    case nlohmann::ordered_json::value_t::number_float: return py::float_(v.get<double>());
    case nlohmann::ordered_json::value_t::string: return py::str(v.get<std::string>());
    default: return py::none();
  }
}

}  // namespace

py::dict report_dict(const nlohmann::ordered_json& report) { return to_python(report).cast<py::dict>(); }

void warn_all(const std::vector<std::string>& lines) {
  for (const std::string& w : lines)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();
}

}  // namespace adaptex::python
