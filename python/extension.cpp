// The extension module `adaptex._adaptex` (module.h).
#include "module.h"

PYBIND11_MODULE(_adaptex, m) { adaptex::python::define_module(m); }
