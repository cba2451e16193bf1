#pragma once
/// \file options.h
/// Keyword arguments of the Python module mapped onto the library's own option structs: every
/// default is the struct's (UnwrapOptions{}, AdaptOptions{}, ...), none is declared again here. A
/// keyword set to None keeps the default. Enums are strings ("mean-value", "density-flow", ...).
#include <pybind11/pybind11.h>

#include "adaptex/adapt/adapt.h"
#include "adaptex/adapt/session.h"
#include "adaptex/paint/eval.h"
#include "adaptex/paint/painter.h"
#include "adaptex/param/unwrap.h"

namespace adaptex::python {

namespace py = pybind11;

/// Sets the fields of \p options named by \p kwargs (a field per keyword, same names as the struct).
/// \throw py::type_error an unknown keyword (the message lists the known ones)
/// \throw InvalidInputError a value of the wrong type or an unknown enum name
void set_options(UnwrapOptions& options, const py::dict& kwargs, const char* fn);
void set_options(AdaptOptions& options, const py::dict& kwargs, const char* fn);
/// PaintSessionOptions fields plus those of its AdaptOptions `adapt` (mode, alpha, refine, ...).
void set_options(PaintSessionOptions& options, const py::dict& kwargs, const char* fn);
void set_options(PainterOptions& options, const py::dict& kwargs, const char* fn);
void set_options(EvalOptions& options, const py::dict& kwargs, const char* fn);

/// The keyword arguments and their defaults of each function, as a dict:
/// {"unwrap": {...}, "adapt": {...}, "reparam": {...}, "paint": {...}, "evaluate": {...}}.
py::dict option_defaults();
/// The names an enum keyword accepts, per function: {"adapt": {"mode": [...], ...}, ...}.
py::dict option_choices();

}  // namespace adaptex::python
