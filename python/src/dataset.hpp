#pragma once
#include "convert.hpp"

namespace revisit::python {
void BindDataset(py::module_& m);
}  // namespace revisit::python
