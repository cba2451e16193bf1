// The Python module lists and runs the registered methods (adapt/method.h): a method registered from
// this test, with no edit in python/, is returned by adaptex.adapt_methods(), offered by the `mode`
// keyword (and listed in help()), and runs through adaptex.reparam(). The test embeds Python and
// defines the extension's functions (module.h) on a module standing in for adaptex._adaptex.
#include <gtest/gtest.h>
#include <pybind11/embed.h>
#include <pybind11/numpy.h>

#include <string>

#include "adaptex/core/shapes.h"
#include "adaptex/param/unwrap.h"
#include "identity_method.h"
#include "module.h"

namespace py = pybind11;

PYBIND11_EMBEDDED_MODULE(_adaptex_embedded, m) { adaptex::python::define_module(m); }

namespace adaptex {
namespace {

using test::IdentityMethod;

const bool registered = test::register_identity_method();

template <class T, class Row>
py::array_t<T> rows(const std::vector<Row>& v, py::ssize_t n) {
  py::array_t<T> a({static_cast<py::ssize_t>(v.size()), n});
  auto r = a.template mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (py::ssize_t k = 0; k < n; ++k) r(i, k) = static_cast<T>(v[static_cast<size_t>(i)][k]);
  return a;
}

TEST(PythonRegistry, ARegisteredMethodIsListedAndRunsFromPython) {
  ASSERT_TRUE(registered);
  py::scoped_interpreter python;
  try {
    py::module_::import("numpy");
  } catch (const py::error_already_set&) {
    GTEST_SKIP() << "numpy is not installed (Debian python3-numpy)";
  }
  py::module_ sys = py::module_::import("sys");
  sys.attr("modules")["adaptex._adaptex"] = py::module_::import("_adaptex_embedded");
  sys.attr("path").attr("insert")(0, ADAPTEX_PYTHON_DIR);
  py::module_ adaptex = py::module_::import("adaptex");

  const py::dict methods = adaptex.attr("adapt_methods")();
  ASSERT_TRUE(methods.contains("identity"));
  EXPECT_EQ(methods["identity"].cast<std::string>(), "test: the identity warp");
  const std::string doc = py::str(adaptex.attr("adapt").attr("__doc__"));
  EXPECT_NE(doc.find("mode : {'none', 'single', 'two-stage', 'density-flow', 'identity'}"), std::string::npos) << doc;

  const TriMesh mesh = shapes::torus(24, 12);
  const Parameterization param = unwrap(mesh).param;
  py::array_t<std::uint8_t> texture({py::ssize_t{32}, py::ssize_t{32}, py::ssize_t{4}});
  auto t = texture.mutable_unchecked<3>();
  for (py::ssize_t y = 0; y < 32; ++y)
    for (py::ssize_t x = 0; x < 32; ++x)
      for (py::ssize_t c = 0; c < 4; ++c) t(y, x, c) = static_cast<std::uint8_t>(c == 3 ? 255 : 8 * (x + y));
  const int computed = IdentityMethod::computed;
  const py::dict out = adaptex.attr("reparam")(rows<double>(mesh.positions, 3), rows<int>(mesh.faces, 3),
                                               rows<double>(param.uv, 2), rows<int>(param.uv_faces, 3), texture,
                                               py::arg("mode") = "identity");
  EXPECT_EQ(IdentityMethod::computed, computed + 1);
  EXPECT_EQ(out["report"]["mode"].cast<std::string>(), "identity");
  const auto uv = out["UV"].cast<py::array_t<double>>().unchecked<2>();
  ASSERT_EQ(uv.shape(0), static_cast<py::ssize_t>(param.uv.size()));
  for (py::ssize_t w = 0; w < uv.shape(0); ++w) {
    EXPECT_NEAR(uv(w, 0), param.uv[static_cast<size_t>(w)].x(), 1e-12);
    EXPECT_NEAR(uv(w, 1), param.uv[static_cast<size_t>(w)].y(), 1e-12);
  }
}

}  // namespace
}  // namespace adaptex
