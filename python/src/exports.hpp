#pragma once
#include "convert.hpp"

namespace revisit::python {
void BindExports(py::module_& m);
}  // namespace revisit::python
