/// The `revisit` Python module: a thin layer over the C++ library (configuration, datasets, the online
/// closure pipeline, the CLI's run and exports). Long calls release the GIL; the library's errors
/// arrive as Python exceptions carrying its message.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <sstream>

#include "closure_pipeline.hpp"
#include "convert.hpp"
#include "core/error.hpp"
#include "dataset.hpp"
#include "exports.hpp"
#include "settings/resolve_config.hpp"
#include "sim/sim_reader.hpp"

namespace py = pybind11;

namespace {

revisit::PipelineConfig LoadConfig(const std::vector<std::string>& files, const py::dict& set,
                                   const std::optional<std::filesystem::path>& dataset) {
    revisit::PipelineConfig config = revisit::ResolveConfig(files, revisit::python::SetOverrides(set));
    if (dataset) {
        py::gil_scoped_release release;
        std::ostringstream log;
        revisit::DeriveSettingsFromData(config, *dataset, log);
    }
    return config;
}

}  // namespace

PYBIND11_MODULE(revisit, m) {
    m.doc() = "revisit: loop closures for LiDAR and 2D-laser sequences, from Python and numpy.";
    m.attr("__version__") = REVISIT_VERSION;
    revisit::RegisterSimulatorDatasets();  // `sim:PRESET` wherever a dataset is named

    static py::exception<revisit::ConfigError> config_error(m, "ConfigError", PyExc_ValueError);
    static py::exception<revisit::DatasetError> dataset_error(m, "DatasetError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const revisit::ConfigError& e) {
            PyErr_SetString(config_error.ptr(), e.what());
        } catch (const revisit::DatasetError& e) {
            PyErr_SetString(dataset_error.ptr(), e.what());
        }
    });

    py::class_<revisit::PipelineConfig>(m, "Config", "A resolved configuration (configs/default.yaml's keys).")
        .def("yaml", [](const revisit::PipelineConfig& c) { return revisit::DumpConfig(c); }, "as `revisit config` prints it")
        .def_readonly("derived", &revisit::PipelineConfig::derived, "the settings derived from the data, with the reasons")
        .def("__repr__", [](const revisit::PipelineConfig&) { return std::string("<revisit.Config>"); });
    m.def("load_config", &LoadConfig, py::arg("files") = std::vector<std::string>{}, py::arg("set") = py::dict(),
          py::arg("dataset") = py::none(),
          "The built-in defaults, then each YAML file or preset name (kitti, indoor2d, ...), then each key=value of "
          "`set` (as --config and --set). With `dataset`, the settings none of them gave are derived from its first "
          "scans, as `revisit run` does.");

    revisit::python::BindClosurePipeline(m);
    revisit::python::BindDataset(m);
    revisit::python::BindExports(m);
}
