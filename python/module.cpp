// The Python module `adaptex` (docs/python.md): pybind11 bindings of the library's main entry
// points on numpy arrays. Long calls run without the GIL and take a progress callback
// progress(phase: str, fraction: float) -> bool; returning False (or raising) cancels the call,
// which then raises adaptex.CancelledError (or the callback's exception).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <exception>
#include <optional>
#include <thread>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/adapt_report.h"
#include "adaptex/adapt/method.h"
#include "adaptex/adapt/report_json.h"
#include "adaptex/adapt/shrink.h"
#include "adaptex/adapt/shrink_report.h"
#include "adaptex/adapt/session.h"
#include "adaptex/adapt/texture_update.h"
#include "adaptex/core/atomic_output.h"
#include "adaptex/core/errors.h"
#include "adaptex/core/limits.h"
#include "adaptex/io/image_io.h"
#include "adaptex/io/mesh_io.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/material_signal.h"
#include "adaptex/paint/painter.h"
#include "adaptex/paint/texel_map.h"
#include "adaptex/param/stretch.h"
#include "adaptex/param/unwrap.h"
#include "convert.h"
#include "module.h"
#include "options.h"

namespace adaptex::python {

namespace {

/// The Python progress callback of one call, and Ctrl+C. The C++ callback it hands to the library may
/// be called from any thread while the GIL is released: it takes the GIL to call Python. On the thread
/// that called adaptex it also runs Python's signal handlers, so Ctrl+C (KeyboardInterrupt) stops a
/// long call at its next progress report, with or without a Python callback.
class Progress {
 public:
  explicit Progress(py::object callback) : callback_(std::move(callback)), caller_(std::this_thread::get_id()) {}
  /// The library's callback.
  ProgressCallback callback() {
    return [this](std::string_view phase, double fraction) { return call(phase, fraction); };
  }
  /// Reports progress between the steps of a binding (strokes). \throw CancelledError when cancelled
  void step(std::string_view phase, double fraction) {
    if (!call(phase, fraction)) throw CancelledError();
  }
  /// Runs \p fn without the GIL; a cancel caused by an exception (the callback's, or
  /// KeyboardInterrupt) re-raises it.
  template <class Fn>
  auto run(Fn&& fn) -> decltype(fn()) {
    try {
      py::gil_scoped_release release;
      return fn();
    } catch (const CancelledError&) {
      if (error_) std::rethrow_exception(error_);
      throw;
    }
  }

 private:
  bool call(std::string_view phase, double fraction) {
    if (cancelled_) return false;
    const bool on_caller = std::this_thread::get_id() == caller_;
    if (callback_.is_none() && !on_caller) return true;
    py::gil_scoped_acquire gil;
    try {
      // Python runs signal handlers on the main thread only; elsewhere this returns 0.
      if (on_caller && PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (callback_.is_none()) return true;
      const py::object r = callback_(py::str(phase.data(), phase.size()), fraction);
      if (r.is_none() || PyObject_IsTrue(r.ptr()) == 1) return true;
    } catch (const py::error_already_set&) {
      error_ = std::current_exception();
    }
    cancelled_ = true;
    return false;
  }

  py::object callback_;
  std::thread::id caller_;
  std::atomic<bool> cancelled_{false};
  std::exception_ptr error_;  ///< Written under the GIL.
};

py::dict unwrap_report_dict(const UnwrapReport& r, const Parameterization& p) {
  py::dict d = report_dict(unwrap_report_json(r));
  d["face_chart"] = py::array_t<int>(static_cast<py::ssize_t>(p.face_chart.size()), p.face_chart.data());
  return d;
}

std::filesystem::path fspath(py::handle path) {
  return std::filesystem::path(py::str(py::module_::import("os").attr("fspath")(path)));
}

/// \p path for a write: its folder must exist (the write functions never create folders).
/// \throw OutputError naming the file and the missing folder
std::filesystem::path output_path(py::handle path) {
  const std::filesystem::path p = fspath(path);
  const std::filesystem::path dir = p.parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    throw OutputError(p.string() + ": cannot write: folder " + dir.string() + " does not exist");
  return p;
}

py::tuple py_read_mesh(py::handle path, bool repair) {
  ReadOptions ro;
  ro.repair = repair;
  ReadReport rep;
  const TriMesh mesh = read_mesh(fspath(path), ro, &rep);
  warn_all(rep.warnings);
  return py::make_tuple(vertices_array(mesh), faces_array(mesh.faces));
}

py::tuple py_validate_mesh(py::handle V, py::handle F, bool repair) {
  // The arrays' shapes and indices are checked, then the library's own validation runs unchanged.
  TriMesh mesh;
  {
    const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(V);
    const auto f = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(F);
    if (!v || !f || v.ndim() != 2 || v.shape(1) != 3 || f.ndim() != 2 || f.shape(1) != 3)
      throw InvalidInputError("validate_mesh: V must be (#V, 3) numbers and F (#F, 3) integers");
    for (py::ssize_t i = 0; i < v.shape(0); ++i) mesh.positions.emplace_back(v.at(i, 0), v.at(i, 1), v.at(i, 2));
    for (py::ssize_t i = 0; i < f.shape(0); ++i) {
      Face t;
      for (int k = 0; k < 3; ++k) {
        const std::int64_t x = f.at(i, k);
        if (x < 0 || x >= v.shape(0)) throw InvalidInputError("validate_mesh: F has an index out of range");
        t[static_cast<size_t>(k)] = static_cast<int>(x);
      }
      mesh.faces.push_back(t);
    }
  }
  ReadOptions ro;
  ro.repair = repair;
  ReadReport rep;
  const TriMesh out = validate_mesh(std::move(mesh), "validate_mesh", ro, &rep);
  warn_all(rep.warnings);
  return py::make_tuple(vertices_array(out), faces_array(out.faces), report_dict(read_report_json(rep)));
}

py::tuple py_read_textured_obj(py::handle path) {
  ReadReport rep;
  const TexturedMesh tm = read_textured_obj(fspath(path), {}, &rep);
  warn_all(rep.warnings);
  return py::make_tuple(vertices_array(tm.mesh), faces_array(tm.mesh.faces), uv_array(tm.param),
                        faces_array(tm.param.uv_faces));
}

void py_write_obj(py::handle path, py::handle V, py::handle F, py::handle UV, py::handle FT) {
  const TriMesh mesh = mesh_from_arrays(V, F, "write_obj");
  if (UV.is_none() != FT.is_none()) throw InvalidInputError("write_obj: give both UV and FT, or neither");
  std::optional<Parameterization> param;
  if (!UV.is_none()) param = param_from_arrays(mesh, UV, FT, "write_obj");
  AtomicOutput out;  // a failed write leaves nothing behind (and never a truncated earlier file)
  write_obj(out.add(output_path(path)), mesh, param ? &*param : nullptr);
  out.commit();
}

py::tuple py_unwrap(py::handle V, py::handle F, py::object progress, std::optional<int> texture_size,
                    std::optional<int> padding, py::kwargs kwargs) {
  const TriMesh mesh = mesh_from_arrays(V, F, "unwrap");
  UnwrapOptions options;
  set_options(options, kwargs, "unwrap");
  if (texture_size || padding)
    options = unwrap_options_for_texture(texture_size.value_or(PainterOptions{}.width),
                                         padding.value_or(PainterOptions{}.padding), options);
  Progress p(std::move(progress));
  options.progress = p.callback();
  const UnwrapResult r = p.run([&] { return unwrap(mesh, options); });
  return py::make_tuple(uv_array(r.param), faces_array(r.param.uv_faces), unwrap_report_dict(r.report, r.param));
}

py::array_t<std::uint8_t> py_paint(py::handle V, py::handle F, py::handle UV, py::handle FT, py::handle strokes,
                                   py::object progress, std::optional<int> size, py::kwargs kwargs) {
  const TriMesh mesh = mesh_from_arrays(V, F, "paint");
  const Parameterization param = param_from_arrays(mesh, UV, FT, "paint");
  const StrokeFile file = strokes_from_object(strokes, "paint");
  PainterOptions options;
  set_options(options, kwargs, "paint");
  if (size) options.width = options.height = *size;
  Progress p(std::move(progress));
  const ImageRGBA8 texture = p.run([&] {
    Painter painter(mesh, param, options, file.background);
    const size_t n = file.strokes.size();
    for (size_t k = 0; k < n; ++k) {
      p.step("paint", static_cast<double>(k) / static_cast<double>(n));
      painter.paint_stroke(file.strokes[k]);
    }
    p.step("paint", 1.0);
    return painter.texture();
  });
  return image_array(texture);
}

py::dict result_dict(const TriMesh& mesh, const Parameterization& param, const ImageRGBA8& texture) {
  py::dict d;
  d["V"] = vertices_array(mesh);
  d["F"] = faces_array(mesh.faces);
  d["UV"] = uv_array(param);
  d["FT"] = faces_array(param.uv_faces);
  d["texture"] = image_array(texture);
  return d;
}

py::dict py_adapt(py::handle V, py::handle F, py::handle UV, py::handle FT, py::handle strokes, py::object progress,
                  py::kwargs kwargs) {
  TriMesh mesh = mesh_from_arrays(V, F, "adapt");
  Parameterization param = param_from_arrays(mesh, UV, FT, "adapt");
  const StrokeFile file = strokes_from_object(strokes, "adapt");
  PaintSessionOptions options;
  set_options(options, kwargs, "adapt");
  Progress p(std::move(progress));
  options.adapt.progress = p.callback();
  struct Out {
    TriMesh mesh;
    Parameterization param;
    ImageRGBA8 texture;
    nlohmann::json reports;
  };
  const Out out = p.run([&] {
    PaintSession session(std::move(mesh), std::move(param), options, file.background);
    const size_t n = file.strokes.size();
    for (size_t k = 0; k < n; ++k) {
      p.step("paint", static_cast<double>(k) / static_cast<double>(n));
      session.add_stroke(file.strokes[k]);
    }
    p.step("paint", 1.0);
    session.finish();
    return Out{session.mesh(), session.param(), session.texture(), adapt_reports_json(session.reports())};
  });
  py::dict d = result_dict(out.mesh, out.param, out.texture);
  d["reports"] = json_to_python(out.reports);
  return d;
}

/// The atlas-preserving shrink (adapt/shrink.h) of \p maps (slot -> image) on (mesh, param):
/// dict(V, F, UV, FT, texture = the first map, maps = {slot: image}, report).
py::dict shrink_dict(const TriMesh& mesh, const Parameterization& param, const std::vector<ShrinkMap>& maps,
                     int size, py::object progress, const char* fn) {
  if (size < 8 || size > kMaxTextureSize)
    throw InvalidInputError(std::string(fn) + ": size must be in [8, " + std::to_string(kMaxTextureSize) + "]");
  ShrinkOptions options;
  options.size = size;
  Progress p(std::move(progress));
  options.progress = p.callback();
  const ShrinkResult r = p.run([&] { return shrink_textured_mesh(mesh, param, maps, options); });
  py::dict d = result_dict(mesh, r.param, r.maps[0]);
  py::dict out_maps;
  std::vector<std::string> slots;
  for (size_t m = 0; m < maps.size(); ++m) {
    out_maps[py::str(maps[m].slot)] = image_array(r.maps[m]);
    slots.push_back(maps[m].slot);
  }
  d["maps"] = out_maps;
  d["report"] = json_to_python(nlohmann::json::parse(shrink_report_json(r, slots).dump()));
  return d;
}

py::dict py_shrink(py::handle V, py::handle F, py::handle UV, py::handle FT, py::handle maps, py::object progress,
                   int size) {
  const TriMesh mesh = mesh_from_arrays(V, F, "shrink");
  const Parameterization param = param_from_arrays(mesh, UV, FT, "shrink");
  std::vector<ShrinkMap> in;
  if (py::isinstance<py::dict>(maps)) {
    for (const auto& [slot, image] : py::reinterpret_borrow<py::dict>(maps)) {
      const std::string name = py::str(slot);
      in.push_back({name, image_from_array(image, "shrink", name.c_str()), map_kind_of_slot(name)});
    }
  } else {
    in.push_back({"base_color", image_from_array(maps, "shrink", "maps"), MapKind::Color});
  }
  if (in.empty()) throw InvalidInputError("shrink: maps is empty");
  return shrink_dict(mesh, param, in, size, std::move(progress), "shrink");
}

py::dict py_reparam(py::handle V, py::handle F, py::handle UV, py::handle FT, py::handle texture, py::object progress,
                    std::optional<int> size, std::optional<int> padding, py::kwargs kwargs) {
  const TriMesh mesh = mesh_from_arrays(V, F, "reparam");
  const Parameterization param = param_from_arrays(mesh, UV, FT, "reparam");
  const ImageRGBA8 tex = image_from_array(texture, "reparam", "texture");
  // The default, as `adaptex reparam`: the shrink (the artist's charts kept; refine is moot there).
  if (!kwargs.contains("mode") || py::str(kwargs["mode"]).cast<std::string>() == "shrink") {
    return shrink_dict(mesh, param, {{"base_color", tex, MapKind::Color}}, size.value_or(std::max(tex.width, tex.height)),
                       std::move(progress), "reparam");
  }
  AdaptOptions options;
  set_options(options, kwargs, "reparam");
  if (options.mode == AdaptMode::None) {
    std::vector<std::string> names{"shrink"};
    for (const AdaptMethodInfo* m : adapt_methods())
      if (m->make) names.push_back(m->name);
    throw InvalidInputError("reparam: mode must be " + or_list(names));
  }
  if (size && (*size < 1 || *size > kMaxTextureSize))
    throw InvalidInputError("reparam: size must be in [1, " + std::to_string(kMaxTextureSize) + "]");
  const int pad = padding.value_or(PainterOptions{}.padding);
  Progress p(std::move(progress));
  options.progress = p.callback();
  struct Out {
    AdaptResult res;
    ImageRGBA8 texture;
  };
  // Resample mode (thesis §3.7.3), as `adaptex reparam`: the new texture samples the old one through
  // the old UVs of the same surface point.
  const Out out = p.run([&] {
    const TexelMap old_map = build_texel_map(mesh, param, tex.width, tex.height);
    AdaptResult res = adapt_parameterization(mesh, param, tex, old_map, options);
    const TriMesh& out_mesh = res.refined_mesh ? *res.refined_mesh : mesh;
    const Parameterization& old_layout = res.refined_mesh ? *res.refined_layout : param;
    const TexelMap new_map = build_texel_map(out_mesh, res.param, size.value_or(tex.width), size.value_or(tex.height));
    ImageRGBA8 new_tex = resample_texture(old_layout, tex, new_map, pad);
    return Out{std::move(res), std::move(new_tex)};
  });
  py::dict d = result_dict(out.res.refined_mesh ? *out.res.refined_mesh : mesh, out.res.param, out.texture);
  d["report"] = json_to_python(nlohmann::json(out.res.report));
  return d;
}

py::dict py_evaluate(py::handle V, py::handle F, py::handle UV, py::handle FT, py::handle texture, py::handle strokes,
                     py::object progress, py::kwargs kwargs) {
  const TriMesh mesh = mesh_from_arrays(V, F, "evaluate");
  const Parameterization param = param_from_arrays(mesh, UV, FT, "evaluate");
  const ImageRGBA8 tex = image_from_array(texture, "evaluate", "texture");
  const StrokeFile file = strokes_from_object(strokes, "evaluate");
  EvalOptions options;
  set_options(options, kwargs, "evaluate");
  if (options.samples < 1) throw InvalidInputError("evaluate: samples must be >= 1");
  Progress p(std::move(progress));
  options.progress = p.callback();
  const EvalResult r = p.run([&] { return evaluate_texture(mesh, param, tex, file, options); });
  return report_dict(eval_result_json(r));
}

/// Every channel of a stroke file (version 1 or 2) at surface points: #P x 7 float64.
py::array_t<double> py_evaluate_material(py::handle V, py::handle F, py::handle strokes, py::handle faces,
                                         py::handle bary) {
  const TriMesh mesh = mesh_from_arrays(V, F, "evaluate_material");
  const MaterialStrokeFile file = material_strokes_from_object(strokes, "evaluate_material");
  const auto fa = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(faces);
  const auto ba = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(bary);
  if (!fa || fa.ndim() != 1) throw InvalidInputError("evaluate_material: faces must be a 1-D integer array");
  if (!ba || ba.ndim() != 2 || ba.shape(1) != 2 || ba.shape(0) != fa.shape(0))
    throw InvalidInputError("evaluate_material: bary must be a #P x 2 array (b0, b1), #P = len(faces)");
  std::vector<SurfacePoint> points(static_cast<size_t>(fa.shape(0)));
  const auto f = fa.unchecked<1>();
  const auto b = ba.unchecked<2>();
  for (py::ssize_t k = 0; k < fa.shape(0); ++k) {
    if (f(k) < 0 || f(k) >= mesh.num_faces())
      throw InvalidInputError("evaluate_material: faces[" + std::to_string(k) + "] out of range");
    if (!std::isfinite(b(k, 0)) || !std::isfinite(b(k, 1)))
      throw InvalidInputError("evaluate_material: bary[" + std::to_string(k) + "] is not finite");
    points[static_cast<size_t>(k)] = SurfacePoint{static_cast<int>(f(k)), b(k, 0), b(k, 1)};
  }
  const std::vector<MaterialValue> values = [&] {
    py::gil_scoped_release release;
    return evaluate_material(mesh, file, points);
  }();
  py::array_t<double> out({static_cast<py::ssize_t>(values.size()), static_cast<py::ssize_t>(kMaterialComponents)});
  auto o = out.mutable_unchecked<2>();
  for (size_t k = 0; k < values.size(); ++k)
    for (int c = 0; c < kMaterialComponents; ++c) o(static_cast<py::ssize_t>(k), c) = values[k][c];
  return out;
}

py::dict py_stretch(py::handle V, py::handle F, py::handle UV, py::handle FT) {
  const TriMesh mesh = mesh_from_arrays(V, F, "stretch");
  const Parameterization param = param_from_arrays(mesh, UV, FT, "stretch");
  const StretchStats s = measure_stretch(mesh, param);
  const std::vector<double> face = face_l2_stretch(mesh, param);
  py::dict d = report_dict(stretch_json(s));
  d["face_l2"] = py::array_t<double>(static_cast<py::ssize_t>(face.size()), face.data());
  return d;
}

/// adaptex's exception hierarchy (core/errors.h) as Python classes: bad input is a ValueError, a file
/// that cannot be read or written an OSError.
void register_errors(py::module_& m) {
  auto make = [&m](const char* name, std::vector<py::handle> bases, const char* doc) -> PyObject* {
    py::tuple b(bases.size());
    for (size_t i = 0; i < bases.size(); ++i) b[i] = py::reinterpret_borrow<py::object>(bases[i]);
    const std::string full = std::string("adaptex.") + name;
    py::object cls = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(full.c_str(), doc, b.ptr(), nullptr));
    if (!cls) throw py::error_already_set();
    m.attr(name) = cls;
    return cls.release().ptr();  // kept for the life of the process (no destructor after Py_Finalize)
  };
  static PyObject *error, *invalid, *topology, *io, *output, *solver, *cancelled;
  error = make("Error", {PyExc_RuntimeError}, "Base of every adaptex error.");
  invalid = make("InvalidInputError", {error, PyExc_ValueError}, "Invalid input: arrays, options, file content.");
  topology = make("TopologyError", {invalid}, "A mesh topology the operation cannot handle (non-manifold, ...).");
  io = make("IoError", {invalid, PyExc_OSError}, "An input file could not be read, or is corrupt.");
  output = make("OutputError", {error, PyExc_OSError}, "An output file could not be written.");
  solver = make("SolverError", {error}, "A numerical solver failed.");
  cancelled = make("CancelledError", {error}, "The call was cancelled by its progress callback.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const CancelledError& e) {
      PyErr_SetString(cancelled, e.what());
    } catch (const TopologyError& e) {
      PyErr_SetString(topology, e.what());
    } catch (const IoError& e) {
      PyErr_SetString(io, e.what());
    } catch (const InvalidInputError& e) {
      PyErr_SetString(invalid, e.what());
    } catch (const OutputError& e) {
      PyErr_SetString(output, e.what());
    } catch (const SolverError& e) {
      PyErr_SetString(solver, e.what());
    } catch (const Error& e) {
      PyErr_SetString(error, e.what());
    }
  });
}

py::dict py_adapt_methods() {
  py::dict d;
  for (const AdaptMethodInfo* m : adapt_methods()) d[py::str(m->name)] = py::str(m->description);
  return d;
}

}  // namespace

void define_module(py::module_& m) {
  m.doc() = "adaptex: signal-adaptive texture parameterization (docs/python.md)";
  register_errors(m);
  m.def("read_mesh", &py_read_mesh, py::arg("path"), py::kw_only(), py::arg("repair") = false,
        "read_mesh(path, *, repair=False) -> (V, F): V #V x 3 float64, F #F x 3 int32 (OBJ, OFF, PLY, STL, glTF/GLB).");
  m.def("validate_mesh", &py_validate_mesh, py::arg("V"), py::arg("F"), py::kw_only(), py::arg("repair") = false,
        "validate_mesh(V, F, *, repair=False) -> (V, F, report): the mesh as read_mesh returns it (degenerate faces "
        "and unused vertices dropped, pinched vertices split, winding made consistent).");
  m.def("read_textured_obj", &py_read_textured_obj, py::arg("path"),
        "read_textured_obj(path) -> (V, F, UV, FT): an OBJ with vt and f v/vt (UV #W x 2 float64, FT #F x 3 int32).");
  m.def("write_obj", &py_write_obj, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("UV") = py::none(),
        py::arg("FT") = py::none(), "write_obj(path, V, F, UV=None, FT=None): v / vt / f v/vt at round-trip precision; all or nothing "
        "(written under a temporary name, renamed on success; the folder must exist).");
  m.def("read_image", [](py::handle path) { return image_array(adaptex::read_image(fspath(path))); }, py::arg("path"),
        "read_image(path) -> texture H x W x 4 uint8, row 0 = v = 0 (the bottom row of the PNG).");
  m.def("write_image", [](py::handle path, py::handle texture) {
          const adaptex::ImageRGBA8 image = image_from_array(texture, "write_image", "texture");
          adaptex::AtomicOutput out;  // as write_obj: all or nothing
          adaptex::write_png(out.add(output_path(path)), image);
          out.commit();
        }, py::arg("path"), py::arg("texture"), "write_image(path, texture): PNG (row 0 of texture = bottom row); all or nothing, as write_obj.");
  m.def("unwrap", &py_unwrap, py::arg("V"), py::arg("F"), py::kw_only(), py::arg("progress") = py::none(),
        py::arg("texture_size") = py::none(), py::arg("padding") = py::none(),
        "unwrap(V, F, *, progress=None, texture_size=None, padding=None, **options) -> (UV, FT, report): cut, "
        "parameterize and pack (UnwrapOptions fields as keywords, option_defaults()['unwrap']); texture_size / "
        "padding set the gutter for that texture as `adaptex paint --size --padding` does.");
  m.def("paint", &py_paint, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FT"), py::arg("strokes"),
        py::kw_only(), py::arg("progress") = py::none(), py::arg("size") = py::none(),
        "paint(V, F, UV, FT, strokes, *, progress=None, size=None, width=, height=, padding=) -> texture H x W x 4 "
        "uint8: the strokes (path or dict) painted exactly on the layout (UV, FT).");
  m.def("adapt", &py_adapt, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FT"), py::arg("strokes"),
        py::kw_only(), py::arg("progress") = py::none(),
        "adapt(V, F, UV, FT, strokes, *, progress=None, **options) -> dict(V, F, UV, FT, texture, reports): paints "
        "the strokes and re-parameterizes by them (PaintSession; `adaptex paint` after its unwrap). Options: "
        "PaintSessionOptions and AdaptOptions fields (texture_size, padding, schedule, update, mode, refine, ...). "
        "With refinement V and F are the refined mesh (same surface).");
  m.def("reparam", &py_reparam, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FT"), py::arg("texture"),
        py::kw_only(), py::arg("progress") = py::none(), py::arg("size") = py::none(), py::arg("padding") = py::none(),
        "reparam(V, F, UV, FT, texture, *, progress=None, size=None, padding=None, **options) -> dict(V, F, UV, FT, "
        "texture, report): as `adaptex reparam`, a size x size texture (default: the input's size). By default "
        "(mode='shrink') the shrink below; the other modes (adapt_methods(), none excepted) re-parameterize by the "
        "texture's signal and resample it, with AdaptOptions fields as keywords (refine=False keeps the mesh).");
  m.def("shrink", &py_shrink, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FT"), py::arg("maps"),
        py::kw_only(), py::arg("progress") = py::none(), py::arg("size") = 256,
        "shrink(V, F, UV, FT, maps, *, progress=None, size=256) -> dict(V, F, UV, FT, texture, maps, report): "
        "the artist's charts kept, charts sharing texels moved together, repacked by the textures' detail into "
        "size x size maps fitted to the originals (as `adaptex shrink`). maps: an image (H x W x 4 uint8) or a "
        "dict {slot: image} ('base_color', 'normal', 'roughness', ...; the first is the measured one). report: "
        "PSNR of the result and of plain downsizing, candidates, flips, shared texels before/after.");
  m.def("evaluate", &py_evaluate, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FT"), py::arg("texture"),
        py::arg("strokes"), py::kw_only(), py::arg("progress") = py::none(),
        "evaluate(V, F, UV, FT, texture, strokes, *, progress=None, samples=, seed=) -> dict(mse, psnr, samples, "
        "seed): the texture against the exact stroke signal, as `adaptex eval`.");
  m.def("evaluate_material", &py_evaluate_material, py::arg("V"), py::arg("F"), py::arg("strokes"), py::arg("faces"),
        py::arg("bary"),
        "evaluate_material(V, F, strokes, faces, bary) -> #P x 7 float64: every channel (r, g, b, alpha, roughness, "
        "metallic, height) of a stroke file of version 1 or 2 (path or dict) at the points "
        "b0 V[F[f,0]] + b1 V[F[f,1]] + (1 - b0 - b1) V[F[f,2]] (docs/strokes.md).");
  m.def("stretch", &py_stretch, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("FT"),
        "stretch(V, F, UV, FT) -> dict(l2, linf, area_distortion, angle_distortion, flipped, degenerate, face_l2 #F).");
  m.def("option_defaults", &option_defaults,
        "option_defaults() -> {function: {keyword: default}}: the library's defaults of every option keyword.");
  m.def("_option_choices", &option_choices, "{function: {keyword: [names]}}: the names each enum keyword accepts.");
  m.def("adapt_methods", &py_adapt_methods,
        "adapt_methods() -> {name: description}: the registered adaptation methods (the `mode` keyword), none first.");
}

}  // namespace adaptex::python
