// Keyword arguments -> the library's option structs (options.h).
#include "options.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "adaptex/core/errors.h"

namespace adaptex::python {

namespace {

/// One keyword: its name, how to set it from a Python value and how to read its current value.
template <class Opt>
struct Field {
  std::string name;
  std::function<void(Opt&, py::handle, const std::string& where)> set;
  std::function<py::object(const Opt&)> get;
  std::vector<std::string> choices;  ///< An enum's names (empty for other types).
};

template <class T>
T cast_value(py::handle value, const std::string& where) {
  // No silent bool <-> number conversion: True is not 1 texel, 1 is not True.
  const bool is_bool = py::isinstance<py::bool_>(value);
  if constexpr (std::is_same_v<T, bool>) {
    if (is_bool) return value.cast<bool>();
  } else {
    if (!is_bool) {
      try {
        return value.cast<T>();
      } catch (const py::cast_error&) {
      }
    }
  }
  const char* want = std::is_same_v<T, bool> ? "a bool" : std::is_floating_point_v<T> ? "a number" : "an int";
  throw InvalidInputError(where + " must be " + want + ", got " +
                          std::string(py::str(py::type::handle_of(value).attr("__name__"))));
}

template <class Opt, class T>
Field<Opt> member(const char* name, T Opt::*m) {
  return {name, [m](Opt& o, py::handle v, const std::string& where) { o.*m = cast_value<T>(v, where); },
          [m](const Opt& o) { return py::cast(o.*m); }};
}

/// An enum keyword given by name: \p names lists (name, value) pairs; the first name of a value is
/// the one read back.
template <class Opt, class E>
Field<Opt> enum_member(const char* name, E Opt::*m, std::vector<std::pair<std::string, E>> names) {
  auto set = [m, names](Opt& o, py::handle v, const std::string& where) {
    const std::string s = py::isinstance<py::str>(v) ? v.cast<std::string>() : std::string();
    std::string known;
    for (const auto& [n, e] : names) {
      if (n == s) {
        o.*m = e;
        return;
      }
      known += (known.empty() ? "" : ", ") + n;
    }
    throw InvalidInputError(where + " must be one of " + known + ", got " + std::string(py::repr(v)));
  };
  auto get = [m, names](const Opt& o) -> py::object {
    for (const auto& [n, e] : names)
      if (e == o.*m) return py::str(n);
    return py::none();
  };
  std::vector<std::string> choices;
  for (const auto& [n, e] : names) choices.push_back(n);
  return {name, set, get, choices};
}

/// An enum keyword named by the enum's table (core/enum_names.h; aliases are not offered).
template <class Opt, class E>
Field<Opt> enum_member(const char* name, E Opt::*m) {
  std::vector<std::pair<std::string, E>> names;
  for (const EnumName<E>& n : enum_names<E>())
    if (!n.alias) names.emplace_back(n.name, n.value);
  return enum_member(name, m, std::move(names));
}

/// The fields of \p Inner reached through the member \p m of \p Outer (PaintSessionOptions::adapt).
template <class Outer, class Inner>
std::vector<Field<Outer>> nested(const std::vector<Field<Inner>>& inner, Inner Outer::*m) {
  std::vector<Field<Outer>> out;
  for (const Field<Inner>& f : inner)
    out.push_back({f.name, [m, set = f.set](Outer& o, py::handle v, const std::string& w) { set(o.*m, v, w); },
                   [m, get = f.get](const Outer& o) { return get(o.*m); }, f.choices});
  return out;
}

const std::vector<Field<UnwrapOptions>>& unwrap_fields() {
  using O = UnwrapOptions;
  static const std::vector<Field<O>> fields = {
      enum_member("weights", &O::weights),
      member("mean_value_max_faces", &O::mean_value_max_faces),
      member("yoshizawa_eta", &O::yoshizawa_eta),
      member("yoshizawa_max_iterations", &O::yoshizawa_max_iterations),
      member("max_augmentations", &O::max_augmentations),
      member("augment_yoshizawa_iterations", &O::augment_yoshizawa_iterations),
      member("augment_face_budget", &O::augment_face_budget),
      member("augment_time_budget", &O::augment_time_budget),
      member("augment_min_improvement", &O::augment_min_improvement),
      member("chart_padding", &O::chart_padding),
      enum_member("charts", &O::charts),
      member("min_texel_share", &O::min_texel_share),
      member("max_charts", &O::max_charts),
      member("single_probe_l2", &O::single_probe_l2),
      member("probe_first_charts", &O::probe_first_charts),
      member("chart_normal_weight", &O::chart_normal_weight),
      member("gutter_texels", &O::gutter_texels),
      member("gutter_texture_size", &O::gutter_texture_size),
  };
  return fields;
}

const std::vector<Field<ThesisOptions>>& thesis_fields() {
  using O = ThesisOptions;
  static const std::vector<Field<O>> fields = {
      member("coarse_grid", &O::coarse_grid),
      member("fine_grid", &O::fine_grid),
      member("alpha", &O::alpha),
      member("geometry_scale", &O::geometry_scale),
      member("beta", &O::beta),
      member("min_weight", &O::min_weight),
      member("use_geometry_stretch", &O::use_geometry_stretch),
      member("slide_boundary", &O::slide_boundary),
      member("epsilon_texels", &O::epsilon_texels),
      member("max_iterations", &O::max_iterations),
      member("fine_max_iterations", &O::fine_max_iterations),
  };
  return fields;
}

const std::vector<Field<DensityFlowMethodOptions>>& density_flow_fields() {
  using O = DensityFlowMethodOptions;
  static const std::vector<Field<O>> fields = {member("chart_gutter_texels", &O::chart_gutter_texels)};
  return fields;
}

/// Refinement's keywords keep their flat names: refine, refine_tolerance_texels, ...
const std::vector<Field<WarpRefineOptions>>& refine_fields() {
  using O = WarpRefineOptions;
  static const std::vector<Field<O>> fields = {
      member("refine", &O::enabled),
      member("refine_tolerance_texels", &O::tolerance_texels),
      member("refine_max_levels", &O::max_levels),
      member("refine_max_face_factor", &O::max_face_factor),
  };
  return fields;
}

/// The keywords of AdaptOptions are flat (the names of the nested structs' fields).
/// Built per call: `mode` offers the methods registered so far (adapt/method.h).
std::vector<Field<AdaptOptions>> adapt_fields() {
  using O = AdaptOptions;
  return [] {
    std::vector<std::pair<std::string, AdaptMode>> modes;
    for (AdaptMode m : adapt_modes()) modes.emplace_back(to_string(m), m);
    std::vector<Field<O>> f = {enum_member("mode", &O::mode, modes)};
    for (auto& t : nested(thesis_fields(), &O::thesis)) f.push_back(std::move(t));
    f.push_back(member("geometry_safeguard", &O::geometry_safeguard));
    for (auto& d : nested(density_flow_fields(), &O::density_flow)) f.push_back(std::move(d));
    for (auto& r : nested(refine_fields(), &O::refine)) f.push_back(std::move(r));
    return f;
  }();
}

std::vector<Field<PaintSessionOptions>> session_fields() {
  using O = PaintSessionOptions;
  return [] {
    std::vector<Field<O>> f = {
        member("texture_size", &O::texture_size),
        member("padding", &O::padding),
        enum_member("schedule", &O::schedule),
        enum_member("update", &O::update),
        member("safeguard", &O::safeguard),
        member("safeguard_samples", &O::safeguard_samples),
        member("safeguard_seed", &O::safeguard_seed),
        member("safeguard_margin", &O::safeguard_margin),
        member("surface_cache", &O::surface_cache),
        member("surface_cache_coverage", &O::surface_cache_coverage),
        member("min_gain_db", &O::min_gain_db),
    };
    for (auto& a : nested(adapt_fields(), &O::adapt)) f.push_back(std::move(a));
    return f;
  }();
}

const std::vector<Field<PainterOptions>>& painter_fields() {
  using O = PainterOptions;
  static const std::vector<Field<O>> fields = {member("width", &O::width), member("height", &O::height),
                                               member("padding", &O::padding)};
  return fields;
}

const std::vector<Field<EvalOptions>>& eval_fields() {
  using O = EvalOptions;
  static const std::vector<Field<O>> fields = {member("samples", &O::samples), member("seed", &O::seed)};
  return fields;
}

template <class Opt>
void apply(Opt& options, const py::dict& kwargs, const char* fn, const std::vector<Field<Opt>>& fields) {
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key);
    const Field<Opt>* field = nullptr;
    for (const Field<Opt>& f : fields)
      if (f.name == name) field = &f;
    if (!field) {
      std::string known;
      for (const Field<Opt>& f : fields) known += (known.empty() ? "" : ", ") + f.name;
      throw py::type_error(std::string(fn) + "() got an unexpected keyword argument '" + name + "' (options: " +
                           known + ")");
    }
    if (!value.is_none()) field->set(options, value, std::string(fn) + ": " + name);
  }
}

template <class Opt>
py::dict defaults(const std::vector<Field<Opt>>& fields) {
  const Opt o{};
  py::dict d;
  for (const Field<Opt>& f : fields) d[py::str(f.name)] = f.get(o);
  return d;
}

template <class Opt>
py::dict choices(const std::vector<Field<Opt>>& fields) {
  py::dict d;
  for (const Field<Opt>& f : fields)
    if (!f.choices.empty()) {
      py::list names;
      for (const std::string& c : f.choices) names.append(py::str(c));
      d[py::str(f.name)] = names;
    }
  return d;
}

}  // namespace

void set_options(UnwrapOptions& o, const py::dict& kw, const char* fn) { apply(o, kw, fn, unwrap_fields()); }
void set_options(AdaptOptions& o, const py::dict& kw, const char* fn) { apply(o, kw, fn, adapt_fields()); }
void set_options(PaintSessionOptions& o, const py::dict& kw, const char* fn) { apply(o, kw, fn, session_fields()); }
void set_options(PainterOptions& o, const py::dict& kw, const char* fn) { apply(o, kw, fn, painter_fields()); }
void set_options(EvalOptions& o, const py::dict& kw, const char* fn) { apply(o, kw, fn, eval_fields()); }

py::dict option_defaults() {
  py::dict d;
  d["unwrap"] = defaults(unwrap_fields());
  d["adapt"] = defaults(session_fields());
  py::dict reparam = defaults(adapt_fields());
  reparam["mode"] = "shrink";  // reparam's default (adapt/shrink.h); the other modes are AdaptOptions'
  d["reparam"] = reparam;
  d["paint"] = defaults(painter_fields());
  d["evaluate"] = defaults(eval_fields());
  return d;
}

py::dict option_choices() {
  py::dict d;
  d["unwrap"] = choices(unwrap_fields());
  d["adapt"] = choices(session_fields());
  py::dict reparam = choices(adapt_fields());
  py::list modes;
  modes.append(py::str("shrink"));
  for (const auto& m : reparam["mode"]) modes.append(m);
  reparam["mode"] = modes;
  d["reparam"] = reparam;
  d["paint"] = choices(painter_fields());
  d["evaluate"] = choices(eval_fields());
  return d;
}

}  // namespace adaptex::python
