#include "closure_pipeline.hpp"

#include <pybind11/stl.h>

#include <chrono>

namespace revisit::python {
namespace {

PipelineConfig Online(PipelineConfig config) {
    // As `revisit run` without ground truth: the elevation ablation is only scored against one.
    config.output.elevation_ablation = false;
    return config;
}

py::dict ScanRangeDict(const ScanRange& range) {
    py::dict d;
    d["first"] = range.first;
    d["last"] = range.last;
    return d;
}

}  // namespace

std::vector<ClosureRecord> Accepted(const std::vector<ClosureRecord>& records) {
    std::vector<ClosureRecord> out;
    for (const auto& r : records)
        if (r.accepted && CorrectsTrajectory(r)) out.push_back(r);
    return out;
}

PyClosurePipeline::PyClosurePipeline(const PipelineConfig& config) : config_(Online(config)), pipeline_(config_) {}

std::vector<ClosureRecord> PyClosurePipeline::AddScan(const py::array& points, const py::object& T_world_sensor,
                                                      const py::object& stamp) {
    if (finished_) throw py::value_error("add_scan after finish(): make a new ClosurePipeline");
    const std::size_t index = poses_.size();
    PipelineUpdate update;
    if (!T_world_sensor.is_none()) {
        const Eigen::Isometry3d pose = ToIsometry(T_world_sensor, "T_world_sensor");
        const PointsView view = ViewPoints(points, false);
        py::gil_scoped_release release;
        const auto start = std::chrono::steady_clock::now();
        update = pipeline_.AddScan(index, view.data, view.size, pose);
        add_scan_.total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        add_scan_.count++;
        poses_.push_back(pose);
    } else {
        // No pose: revisit's odometry registers the scan, and its deskewed points go on, as in `revisit run`.
        PointsView view = ViewPoints(points, true);
        OdometryStages::Item item;
        item.scan.index = index;
        item.scan.timestamp = stamp.is_none() ? double(index) : stamp.cast<double>();
        item.scan.points = view.owned.empty() ? std::vector<Eigen::Vector3f>(view.data, view.data + view.size) : std::move(view.owned);
        item.scan.intensities = std::move(view.intensities);
        py::gil_scoped_release release;
        if (!odometry_) odometry_.emplace(config_);
        odometry_->Admit(item);
        OdometryStages::Prepare(item);
        const Eigen::Isometry3d pose = odometry_->Register(item);
        std::vector<Eigen::Vector3f> deskewed;
        deskewed.reserve(odometry_->odometry().LastDeskewedPoints().size());
        for (const auto& p : odometry_->odometry().LastDeskewedPoints()) deskewed.push_back(p.cast<float>());
        update = pipeline_.AddScan(index, deskewed, pose);
        poses_.push_back(pose);
    }
    return Accepted(update.closures);
}

std::vector<ClosureRecord> PyClosurePipeline::Finish() {
    if (finished_) return Closures();
    {
        py::gil_scoped_release release;
        pipeline_.Finish();
    }
    finished_ = true;
    return Closures();
}

std::vector<ClosureRecord> PyClosurePipeline::Closures() const { return Accepted(pipeline_.closures()); }

py::array_t<double> PyClosurePipeline::CorrectedPoses() const {
    if (pipeline_.maps().empty()) return ToNumpy(poses_);
    // MapOfScan gives the scans of the map still open to the last closed one: they follow its correction.
    const std::vector<int> map_of_scan = MapOfScan(pipeline_.maps(), poses_.size());
    return ToNumpy(pipeline_.CorrectTrajectory(poses_, map_of_scan));
}

void BindClosurePipeline(py::module_& m) {
    py::class_<ClosureRecord>(m, "Closure", "An accepted loop closure between two local maps.")
        .def_property_readonly("query_map", [](const ClosureRecord& r) { return r.closure.query_id; })
        .def_property_readonly("ref_map", [](const ClosureRecord& r) { return r.closure.ref_id; })
        .def_property_readonly("query_scans", [](const ClosureRecord& r) { return ScanRangeDict(r.closure.query_scans); },
                               "the query map's scan range {'first', 'last'} (inclusive)")
        .def_property_readonly("ref_scans", [](const ClosureRecord& r) { return ScanRangeDict(r.closure.ref_scans); },
                               "the reference map's scan range {'first', 'last'} (inclusive)")
        .def_property_readonly("T_query_ref", [](const ClosureRecord& r) { return ToNumpy(r.refinement.T_query_ref); },
                               "4x4: maps reference-map points into the query map (after refinement)")
        .def_property_readonly("inliers", [](const ClosureRecord& r) { return r.closure.num_inliers; })
        .def_property_readonly("method", [](const ClosureRecord& r) { return r.method; })
        .def_property_readonly("overlap", [](const ClosureRecord& r) { return r.refinement.overlap; })
        .def_property_readonly("rms", [](const ClosureRecord& r) { return r.refinement.rms; }, "[m]")
        .def_property_readonly("graph_weight", [](const ClosureRecord& r) { return r.graph_weight; })
        .def_property_readonly("information", [](const ClosureRecord& r) { return Eigen::MatrixXd(r.refinement.information); },
                               "6x6 information of T_query_ref, right perturbation [translation; rotation]")
        .def("__repr__", [](const ClosureRecord& r) {
            return "<revisit.Closure map " + std::to_string(r.closure.query_id) + " -> " + std::to_string(r.closure.ref_id) +
                   " (" + r.method + ", " + std::to_string(r.closure.num_inliers) + " inliers)>";
        });

    py::class_<PyClosurePipeline>(m, "ClosurePipeline",
                                  "Feed scans one at a time; local maps close as the sensor travels and their closures "
                                  "are refined, verified and applied to the pose graph.")
        .def(py::init<const PipelineConfig&>(), py::arg("config"))
        .def("add_scan", &PyClosurePipeline::AddScan, py::arg("points"), py::arg("T_world_sensor") = py::none(),
             py::arg("stamp") = py::none(),
             "points: (N, 3) or (N, 4) float32/float64 in the sensor frame; T_world_sensor: 4x4 pose, or None for "
             "revisit's own odometry; stamp [s]. Returns the closures accepted by this call.")
        .def("finish", &PyClosurePipeline::Finish, "Closes the last map and runs the final optimization.")
        .def("closures", &PyClosurePipeline::Closures, "Every accepted closure so far.")
        .def("corrected_poses", &PyClosurePipeline::CorrectedPoses, "(N, 4, 4) corrected T_world_sensor per scan")
        .def("poses", &PyClosurePipeline::Poses, "(N, 4, 4) T_world_sensor as given (or as the odometry found)")
        .def(
            "timings",
            [](const PyClosurePipeline& p) {
                py::dict d;
                for (const auto& [stage, timer] : p.pipeline().timings()) d[py::str(stage)] = py::make_tuple(timer.total_ms, timer.count);
                d["add_scan"] = py::make_tuple(p.add_scan_timer().total_ms, p.add_scan_timer().count);
                return d;
            },
            "{stage: (total [ms], calls)}: the time in each stage of the C++ pipeline (stages nest: 'detector' "
            "holds 'detector.*'), and 'add_scan': the whole C++ AddScan calls with a pose given")
        .def_property_readonly("num_maps", [](const PyClosurePipeline& p) { return p.pipeline().maps().size(); })
        .def("map_poses", [](const PyClosurePipeline& p) { return ToNumpy(p.pipeline().CorrectedMapPoses()); },
             "(M, 4, 4) corrected origin of every closed map");
}

}  // namespace revisit::python
