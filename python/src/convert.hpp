#pragma once
/// numpy <-> the library's types. Points cross without a copy where the layout allows.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "runfolder/run_state.hpp"

namespace revisit::python {
namespace py = pybind11;

/// An (N, 3) or (N, 4) float32/float64 array as points in the sensor frame. A C-contiguous (N, 3)
/// float32 array is read in place (`data` points into it and `owned` stays empty); anything else is
/// converted into `owned`. The fourth column (intensity) goes to `intensities` when asked for.
struct PointsView {
    const Eigen::Vector3f* data = nullptr;
    std::size_t size = 0;
    std::vector<Eigen::Vector3f> owned;
    std::vector<float> intensities;
    py::array keep_alive;  ///< the array `data` may point into
};
PointsView ViewPoints(const py::array& points, bool want_intensities);

/// A 4x4 array (or None) as a rigid pose; throws ValueError for another shape.
Eigen::Isometry3d ToIsometry(const py::handle& matrix, const char* name);
py::array_t<double> ToNumpy(const Eigen::Isometry3d& pose);
/// (N, 4, 4)
py::array_t<double> ToNumpy(const Poses& poses);
/// A `set={...}` dict as the `key=value` texts `--set` takes (True -> true).
std::vector<std::string> SetOverrides(const py::dict& set);
/// (N, 3) float32 owning a moved vector's memory.
py::array_t<float> ToNumpy(std::vector<Eigen::Vector3f>&& points);

}  // namespace revisit::python
