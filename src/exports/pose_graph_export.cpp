#include "exports/pose_graph_export.hpp"

#include <cmath>
#include <iomanip>
#include <limits>

namespace revisit {
namespace {

OdometryNoise NoiseOf(const GraphNoiseConfig& noise) {
    OdometryNoise odometry;
    odometry.translation_per_m = noise.odometry_translation_per_m;
    odometry.rotation_per_m = noise.odometry_rotation_per_m;
    return odometry;
}

double Yaw(const Eigen::Isometry3d& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

Eigen::Quaterniond Rotation(const Eigen::Isometry3d& T) {
    Eigen::Quaterniond q(T.linear());
    q.normalize();
    if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // g2o keeps w >= 0
    return q;
}

void WriteSE3(std::ostream& out, const Eigen::Isometry3d& T) {
    const Eigen::Quaterniond q = Rotation(T);
    const Eigen::Vector3d t = T.translation();
    out << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w();
}

template <int N>
void WriteUpperTriangle(std::ostream& out, const Eigen::Matrix<double, N, N>& information) {
    for (int i = 0; i < N; ++i)
        for (int j = i; j < N; ++j) out << ' ' << information(i, j);
}

}  // namespace

Matrix6d ClosureInformation(const ClosureRecord& record, const GraphNoiseConfig& noise) {
    return noise.closure_information_from_registration && record.refinement.information.trace() > 0
               ? record.refinement.information
               : DiagonalInformation(noise.closure_sigma_translation, noise.closure_sigma_rotation);
}

ExportGraph RunPoseGraph(const RunState& state, const PipelineConfig& config, bool per_scan) {
    ExportGraph graph;
    graph.planar = config.odometry.planar;
    // The drift calibration may have lowered the rotation drift rate before the final optimization.
    GraphNoiseConfig graph_noise = config.graph_noise;
    for (const auto& update : state.setting_updates)
        if (update.key == "graph.odometry_rotation_per_m") graph_noise.odometry_rotation_per_m = update.to;
    const OdometryNoise noise = NoiseOf(graph_noise);
    if (per_scan) {
        graph.T_world_node = state.odometry;
        for (std::size_t i = 1; i < state.odometry.size(); ++i) {
            const Eigen::Isometry3d T_prev_next = state.odometry[i - 1].inverse() * state.odometry[i];
            graph.edges.push_back({int(i - 1), int(i), T_prev_next, OdometryInformation(T_prev_next.translation().norm(), noise), false});
        }
    } else {
        for (const auto& map : state.maps) graph.T_world_node.push_back(map.T_world_map);
        for (std::size_t i = 1; i < state.maps.size(); ++i) {
            const Eigen::Isometry3d T_prev_next = state.maps[i - 1].T_world_map.inverse() * state.maps[i].T_world_map;
            const double travel = state.maps[i].travel_start - state.maps[i - 1].travel_start;
            graph.edges.push_back({int(i - 1), int(i), T_prev_next, OdometryInformation(travel, noise), false});
        }
    }
    for (std::size_t k = 0; k < state.closures.size(); ++k) {
        const ClosureRecord& record = state.closures[k];
        if (!record.accepted || !CorrectsTrajectory(record)) continue;
        PoseGraphEdge edge;
        edge.from = per_scan ? int(state.maps.at(record.closure.query_id).first_scan) : record.closure.query_id;
        edge.to = per_scan ? int(state.maps.at(record.closure.ref_id).first_scan) : record.closure.ref_id;
        edge.T_from_to = record.refinement.T_query_ref;
        edge.information = ClosureInformation(record, config.graph_noise);
        edge.is_loop = true;
        graph.edges.push_back(edge);
        graph.closure_of_edge.push_back(k);
    }
    return graph;
}

void WriteG2o(std::ostream& out, const ExportGraph& graph) {
    out << std::setprecision(std::numeric_limits<double>::max_digits10);
    for (std::size_t i = 0; i < graph.T_world_node.size(); ++i) {
        const Eigen::Isometry3d& T = graph.T_world_node[i];
        if (graph.planar) {
            out << "VERTEX_SE2 " << i << ' ' << T.translation().x() << ' ' << T.translation().y() << ' ' << Yaw(T) << '\n';
        } else {
            out << "VERTEX_SE3:QUAT " << i << ' ';
            WriteSE3(out, T);
            out << '\n';
        }
    }
    for (const auto& edge : graph.edges) {
        if (graph.planar) {
            // x, y, yaw rows of [translation; rotation]; g2o's SE(2) angle error equals revisit's 2 vec(q).z to first order.
            const int rows[3] = {0, 1, 5};
            Eigen::Matrix3d information;
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j) information(i, j) = edge.information(rows[i], rows[j]);
            const auto& t = edge.T_from_to.translation();
            out << "EDGE_SE2 " << edge.from << ' ' << edge.to << ' ' << t.x() << ' ' << t.y() << ' ' << Yaw(edge.T_from_to);
            WriteUpperTriangle<3>(out, information);
        } else {
            Matrix6d scale = Matrix6d::Identity();
            scale.bottomRightCorner<3, 3>() *= 2.0;  // e_revisit = S e_g2o, so Omega_g2o = S Omega S
            out << "EDGE_SE3:QUAT " << edge.from << ' ' << edge.to << ' ';
            WriteSE3(out, edge.T_from_to);
            WriteUpperTriangle<6>(out, Matrix6d(scale * edge.information * scale));
        }
        out << '\n';
    }
}

}  // namespace revisit
