/// `revisit.open_dataset` (any format the CLI reads, scans as numpy) and `revisit.run` (the CLI's chain).
#include "dataset.hpp"

#include <oneapi/tbb/global_control.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <csignal>
#include <iostream>
#include <memory>
#include <sstream>

#include "io/reader.hpp"
#include "pipeline/interrupt.hpp"
#include "pipeline/run_and_report.hpp"
#include "settings/resolve_config.hpp"

namespace revisit::python {
namespace fs = std::filesystem;
namespace {

/// One scan as Python sees it; the arrays own the scan's memory (moved, not copied).
struct PyScan {
    std::size_t index = 0;
    double stamp = 0.0;
    std::string sensor;
    py::array_t<float> points;
    py::object intensities = py::none();
    py::object T_world_sensor = py::none();
    py::object prior = py::none();
};

PyScan ToPython(Scan&& scan) {
    PyScan out;
    out.index = scan.index;
    out.stamp = scan.timestamp;
    out.sensor = scan.sensor_label;
    out.points = ToNumpy(std::move(scan.points));
    if (scan.has_intensities()) out.intensities = py::array_t<float>(py::ssize_t(scan.intensities.size()), scan.intensities.data());
    if (scan.T_world_sensor) out.T_world_sensor = ToNumpy(*scan.T_world_sensor);
    if (scan.T_odom_sensor) out.prior = ToNumpy(*scan.T_odom_sensor);
    return out;
}

/// A dataset on disk; each iteration opens it afresh and streams it.
class PyDataset {
  public:
    PyDataset(fs::path path, const PipelineConfig& config) : path_(std::move(path)), options_(MakeReaderOptions(config.input)) {
        reader_ = OpenDataset(path_, options_);  // bad input fails here, naming the file
    }
    PyDataset& Iter() {
        if (used_) reader_ = OpenDataset(path_, options_);
        used_ = true;
        return *this;
    }
    PyScan Next() {
        std::optional<Scan> scan;
        {
            py::gil_scoped_release release;
            scan = reader_->Next();
        }
        if (!scan) throw py::stop_iteration();
        return ToPython(std::move(*scan));
    }
    py::dict Info() const {
        const DatasetInfo& info = reader_->Info();
        py::dict d;
        d["format"] = info.format;
        d["path"] = info.path.string();
        d["num_scans"] = info.num_scans ? py::object(py::int_(*info.num_scans)) : py::object(py::none());
        d["has_reference_poses"] = info.has_reference_poses;
        return d;
    }
    std::size_t Len() const {
        if (!reader_->Info().num_scans) throw py::type_error(path_.string() + ": the number of scans is known only once read");
        return *reader_->Info().num_scans;
    }

  private:
    fs::path path_;
    ReaderOptions options_;
    std::unique_ptr<Reader> reader_;
    bool used_ = false;
};

PoseSource ParsePoses(const std::string& poses, fs::path& poses_file) {
    if (poses == "odometry") return PoseSource::kOdometry;
    if (poses == "dataset") return PoseSource::kDataset;
    if (poses == "prior") return PoseSource::kPrior;
    poses_file = poses;
    return PoseSource::kFile;
}

/// `revisit run DATASET --out OUT`: the same config resolution, chain, evaluation and report.
py::dict Run(const fs::path& dataset, const fs::path& out, const std::optional<PipelineConfig>& given, const std::string& poses,
             const std::optional<fs::path>& gt, std::size_t from, std::optional<std::size_t> to, bool force, bool quiet,
             int threads) {
    RunOptions options;
    options.dataset = dataset;
    options.out = out;
    options.poses = ParsePoses(poses, options.poses_file);
    if (gt) options.gt_file = *gt;
    options.from = from;
    options.to = to;
    options.force = force;
    options.quiet = quiet;
    CheckScanRange(options, std::nullopt);
    std::ostringstream summary, silent;
    RunState state;
    // The run installs its own Ctrl-C handler (stop reading, write what was computed); Python's comes back after.
    const auto python_sigint = std::signal(SIGINT, SIG_DFL);
    const auto python_sigterm = std::signal(SIGTERM, SIG_DFL);
    try {
        py::gil_scoped_release release;
        std::unique_ptr<tbb::global_control> limit;
        if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
        PipelineConfig config = given ? *given : ResolveConfig({}, {});
        std::ostream& log = quiet ? static_cast<std::ostream&>(silent) : std::cerr;
        DeriveSettingsFromData(config, dataset, log);
        state = RunAndReport(options, config, log, summary);
    } catch (...) {
        std::signal(SIGINT, python_sigint);
        std::signal(SIGTERM, python_sigterm);
        throw;
    }
    std::signal(SIGINT, python_sigint);
    std::signal(SIGTERM, python_sigterm);
    if (InterruptRequested()) {
        PyErr_SetNone(PyExc_KeyboardInterrupt);
        throw py::error_already_set();
    }
    py::dict result;
    result["out"] = out;
    result["complete"] = state.complete;
    result["scans"] = state.odometry.size();
    result["maps"] = state.maps.size();
    result["closures"] = state.NumAccepted();
    result["summary"] = summary.str();
    return result;
}

}  // namespace

void BindDataset(py::module_& m) {
    py::class_<PyScan>(m, "Scan", "One sweep: points in the sensor frame, its stamp, and the poses the dataset gives.")
        .def_readonly("index", &PyScan::index)
        .def_readonly("stamp", &PyScan::stamp, "[s]")
        .def_readonly("sensor", &PyScan::sensor)
        .def_readonly("points", &PyScan::points, "(N, 3) float32 [m] in the sensor frame")
        .def_readonly("intensities", &PyScan::intensities, "(N,) float32, or None")
        .def_readonly("T_world_sensor", &PyScan::T_world_sensor, "4x4 reference (ground-truth) pose, or None")
        .def_readonly("prior", &PyScan::prior, "4x4 odometry prior (e.g. wheel odometry), or None")
        .def("__repr__", [](const PyScan& s) {
            return "<revisit.Scan " + std::to_string(s.index) + " at " + std::to_string(s.stamp) + " s, " +
                   std::to_string(s.points.shape(0)) + " points>";
        });
    py::class_<PyDataset>(m, "Dataset", "A dataset on disk; iterating streams its scans (again from the start each time).")
        .def("__iter__", &PyDataset::Iter, py::return_value_policy::reference_internal)
        .def("__next__", &PyDataset::Next)
        .def("__len__", &PyDataset::Len)
        .def_property_readonly("info", &PyDataset::Info);
    m.def(
        "open_dataset",
        [](const fs::path& path, const std::optional<PipelineConfig>& config) {
            return std::make_unique<PyDataset>(path, config ? *config : ResolveConfig({}, {}));
        },
        py::arg("path"), py::arg("config") = py::none(),
        "Opens any dataset `revisit run` reads (KITTI folder, .pcd/.ply folder, rawlog, ROS bag, CARMEN log, sim:PRESET); "
        "`config`'s input section picks topics, sensors and the like.");
    m.def("run", &Run, py::arg("dataset"), py::arg("out"), py::arg("config") = py::none(), py::arg("poses") = "odometry",
          py::arg("gt") = py::none(), py::arg("from_scan") = 0, py::arg("to_scan") = py::none(), py::arg("force") = false,
          py::arg("quiet") = true, py::arg("threads") = 0,
          "`revisit run DATASET --out OUT`: settings from the data, the whole chain, evaluation and the report, into the "
          "run folder OUT. Returns a dict: out, complete, scans, maps, closures, summary.");
}

}  // namespace revisit::python
