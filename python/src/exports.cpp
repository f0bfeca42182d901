/// `revisit.export`: `revisit export RUN --format ...` for a finished run folder.
#include "exports.hpp"

#include "convert.hpp"

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <pybind11/eigen.h>

#include "exports/run_exports.hpp"
#include "optimization/pose_graph.hpp"
#include "settings/resolve_config.hpp"

namespace revisit::python {
namespace {

/// revisit's own pose graph (optimization/pose_graph.hpp) over numpy: nodes (N, 4, 4) and edges as
/// (from, to, T_from_to 4x4, information 6x6 [translation; rotation], is_loop) tuples.
py::array_t<double> OptimizePoseGraphNumpy(const py::array_t<double, py::array::c_style | py::array::forcecast>& nodes,
                                           const std::vector<py::tuple>& edge_tuples,
                                           const std::optional<PipelineConfig>& config) {
    if (nodes.ndim() != 3 || nodes.shape(1) != 4 || nodes.shape(2) != 4) throw py::value_error("nodes: expected an (N, 4, 4) array");
    Poses T_world_node;
    for (py::ssize_t k = 0; k < nodes.shape(0); ++k) {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) T.matrix()(i, j) = nodes.at(k, i, j);
        T_world_node.push_back(T);
    }
    std::vector<PoseGraphEdge> edges;
    for (const auto& t : edge_tuples) {
        if (t.size() != 5) throw py::value_error("edges: expected (from, to, T_from_to, information, is_loop) tuples");
        PoseGraphEdge edge;
        edge.from = t[0].cast<int>();
        edge.to = t[1].cast<int>();
        edge.T_from_to = ToIsometry(t[2], "T_from_to");
        edge.information = t[3].cast<Matrix6d>();
        edge.is_loop = t[4].cast<bool>();
        edges.push_back(edge);
    }
    const PoseGraphConfig graph = config ? config->graph : ResolveConfig({}, {}).graph;
    PoseGraphResult result;
    {
        py::gil_scoped_release release;
        result = OptimizePoseGraph(T_world_node, edges, graph);
    }
    return ToNumpy(result.T_world_node);
}

}  // namespace

void BindExports(py::module_& m) {
    m.def(
        "export",
        [](const std::filesystem::path& run, const std::string& format, bool per_scan, const std::optional<std::filesystem::path>& out,
           const py::dict& set) {
            ExportOptions options;
            options.format = format;
            options.per_scan = per_scan;
            if (out) options.out = *out;
            options.overrides = SetOverrides(set);
            py::gil_scoped_release release;
            return ExportRun(run, options);
        },
        py::arg("run"), py::arg("format") = "g2o", py::arg("per_scan") = false, py::arg("out") = py::none(),
        py::arg("set") = py::dict(),
        "Writes a finished run's pose graph (format='g2o', per map or per_scan), its closures "
        "(format='closures-json') or its occupancy grid (format='occupancy': the .png (or .pgm) and its .yaml; `set` takes "
        "occupancy.* keys); returns the file written (the occupancy grid's YAML; default: into the run folder).");
    m.def("optimize_pose_graph", &OptimizePoseGraphNumpy, py::arg("nodes"), py::arg("edges"), py::arg("config") = py::none(),
          "revisit's Ceres pose graph: nodes (N, 4, 4) initial T_world_node; edges (from, to, T_from_to 4x4, information "
          "6x6 over [translation; rotation], is_loop); the robust loss on loop edges and the solver settings from "
          "config's graph section. Returns the optimized (N, 4, 4).");
}

}  // namespace revisit::python
