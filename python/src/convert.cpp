#include "convert.hpp"

#include <cstring>
#include <string>

namespace revisit::python {

PointsView ViewPoints(const py::array& points, bool want_intensities) {
    if (points.ndim() != 2 || (points.shape(1) != 3 && points.shape(1) != 4)) {
        throw py::value_error("points: expected an (N, 3) or (N, 4) array, got shape " +
                              std::string(py::str(py::handle(points).attr("shape"))));
    }
    PointsView view;
    view.size = static_cast<std::size_t>(points.shape(0));
    const bool is_float = py::isinstance<py::array_t<float>>(points);
    const bool is_double = py::isinstance<py::array_t<double>>(points);
    if (!is_float && !is_double) throw py::type_error("points: expected float32 or float64, got " + std::string(py::str(points.dtype())));
    const bool c_contiguous = (points.flags() & py::array::c_style) != 0;
    if (is_float && c_contiguous && points.shape(1) == 3) {
        // Eigen::Vector3f is three packed floats: the array's rows are the points as they lie.
        view.keep_alive = points;
        view.data = reinterpret_cast<const Eigen::Vector3f*>(points.data());
        return view;
    }
    view.owned.resize(view.size);
    const bool has_intensity = points.shape(1) == 4 && want_intensities;
    if (has_intensity) view.intensities.resize(view.size);
    const auto copy = [&](auto typed) {
        const auto r = typed.template unchecked<2>();
        for (py::ssize_t i = 0; i < r.shape(0); ++i) {
            view.owned[i] = Eigen::Vector3f(float(r(i, 0)), float(r(i, 1)), float(r(i, 2)));
            if (has_intensity) view.intensities[i] = float(r(i, 3));
        }
    };
    if (is_float) copy(py::array_t<float>::ensure(points));
    else copy(py::array_t<double>::ensure(points));
    view.data = view.owned.data();
    return view;
}

Eigen::Isometry3d ToIsometry(const py::handle& matrix, const char* name) {
    const auto array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(matrix);
    if (!array || array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4) {
        throw py::value_error(std::string(name) + ": expected a 4x4 pose matrix");
    }
    Eigen::Matrix4d m;
    const auto r = array.unchecked<2>();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m(i, j) = r(i, j);
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.matrix() = m;
    return pose;
}

py::array_t<double> ToNumpy(const Eigen::Isometry3d& pose) {
    py::array_t<double> out({4, 4});
    auto w = out.mutable_unchecked<2>();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) w(i, j) = pose.matrix()(i, j);
    return out;
}

py::array_t<double> ToNumpy(const Poses& poses) {
    py::array_t<double> out({py::ssize_t(poses.size()), py::ssize_t(4), py::ssize_t(4)});
    auto w = out.mutable_unchecked<3>();
    for (std::size_t k = 0; k < poses.size(); ++k)
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) w(k, i, j) = poses[k].matrix()(i, j);
    return out;
}

py::array_t<float> ToNumpy(std::vector<Eigen::Vector3f>&& points) {
    auto* owned = new std::vector<Eigen::Vector3f>(std::move(points));
    py::capsule free(owned, [](void* p) { delete static_cast<std::vector<Eigen::Vector3f>*>(p); });
    return py::array_t<float>({py::ssize_t(owned->size()), py::ssize_t(3)},
                              {py::ssize_t(sizeof(Eigen::Vector3f)), py::ssize_t(sizeof(float))},
                              reinterpret_cast<const float*>(owned->data()), free);
}

std::vector<std::string> SetOverrides(const py::dict& set) {
    std::vector<std::string> overrides;
    for (const auto& [key, value] : set) {
        std::string text;
        if (py::isinstance<py::bool_>(value)) {
            text = value.cast<bool>() ? "true" : "false";
        } else {
            text = py::str(value).cast<std::string>();
        }
        overrides.push_back(py::str(key).cast<std::string>() + "=" + text);
    }
    return overrides;
}

}  // namespace revisit::python
