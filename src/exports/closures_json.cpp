#include "exports/closures_json.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <iomanip>

#include "core/error.hpp"
#include "exports/pose_graph_export.hpp"

namespace revisit {
namespace {
using nlohmann::json;

json Rows(const Eigen::MatrixXd& m) {
    json rows = json::array();
    for (int i = 0; i < m.rows(); ++i) {
        json row = json::array();
        for (int j = 0; j < m.cols(); ++j) row.push_back(m(i, j));
        rows.push_back(row);
    }
    return rows;
}

json MapEnd(const RunState& state, int map_id) {
    const MapRecordSummary& map = state.maps.at(map_id);
    json end;
    end["map"] = map_id;
    end["scan"] = map.first_scan;  // the map's origin: the pose T_query_ref relates
    end["stamp"] = map.first_scan < state.timestamps.size() ? state.timestamps[map.first_scan] : 0.0;
    end["first_scan"] = map.first_scan;
    end["last_scan"] = map.last_scan;
    return end;
}

}  // namespace

void WriteClosuresJson(std::ostream& out, const RunState& state, const PipelineConfig& config) {
    json closures = json::array();
    for (std::size_t k = 0; k < state.closures.size(); ++k) {
        const ClosureRecord& record = state.closures[k];
        if (!record.accepted || !CorrectsTrajectory(record)) continue;
        const Matrix6d information = ClosureInformation(record, config.graph_noise);
        // A registration can leave a direction unconstrained (a corridor): its covariance is the pseudo-inverse.
        const Eigen::MatrixXd covariance = Eigen::MatrixXd(information).completeOrthogonalDecomposition().pseudoInverse();
        json c;
        c["index"] = k;
        c["method"] = record.method;
        c["query"] = MapEnd(state, record.closure.query_id);
        c["reference"] = MapEnd(state, record.closure.ref_id);
        c["T_query_ref"] = Rows(record.refinement.T_query_ref.matrix());
        c["information"] = Rows(information);
        c["covariance"] = Rows(covariance);
        c["inliers"] = record.closure.num_inliers;
        c["overlap"] = record.refinement.overlap;
        c["rms_m"] = record.refinement.rms;
        c["graph_weight"] = record.graph_weight;
        closures.push_back(c);
    }
    json doc;
    doc["frames"] = "T_query_ref: the reference scan's pose in the query scan's frame (each a map's origin scan); "
                    "information and covariance over [translation; rotation] of a right perturbation, [m], [rad]";
    doc["closures"] = closures;
    out << std::setw(2) << doc << '\n';
}

void ReadClosureInformation(const std::filesystem::path& file, RunState& state) {
    std::ifstream in(file);
    if (!in) throw DatasetError(file, "cannot open");
    try {
        const json doc = json::parse(in);
        for (const auto& c : doc.at("closures")) {
            const std::size_t k = c.at("index").get<std::size_t>();
            if (k >= state.closures.size()) throw DatasetError(file, "closure index " + std::to_string(k) + " is not in closures.csv");
            Matrix6d information;
            const auto& rows = c.at("information");
            if (rows.size() != 6) throw DatasetError(file, "closure " + std::to_string(k) + ": information is not 6x6");
            for (int i = 0; i < 6; ++i) {
                if (rows[i].size() != 6) throw DatasetError(file, "closure " + std::to_string(k) + ": information is not 6x6");
                for (int j = 0; j < 6; ++j) information(i, j) = rows[i][j].get<double>();
            }
            state.closures[k].refinement.information = information;
        }
    } catch (const json::exception& e) {
        throw DatasetError(file, std::string("malformed: ") + e.what());
    }
}

}  // namespace revisit
