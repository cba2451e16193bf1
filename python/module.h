#pragma once
/// \file module.h
/// The functions of the extension `adaptex._adaptex`, defined on a module object: by the extension
/// itself (extension.cpp) and by tests that embed Python next to methods they register.
#include <pybind11/pybind11.h>

namespace adaptex::python {

/// Defines every function and exception class of `_adaptex` on \p m.
void define_module(pybind11::module_& m);

}  // namespace adaptex::python
