#pragma once
/// The case groups of the suites (internal to the benchmark module). Each appends its figures to
/// `out` and, when its data is missing, a reason to `skipped`.
#include <filesystem>
#include <string>
#include <vector>

#include "bench_suite/fixtures.hpp"
#include "bench_suite/measure.hpp"
#include "bench_suite/suite.hpp"

namespace revisit {

struct CaseContext {
    SuiteScale scale;
    std::filesystem::path data_dir;     ///< empty when real data is absent
    std::filesystem::path scratch_dir;  ///< exists, removed after the suite
    FixtureCache* fixtures = nullptr;
    std::vector<Measurement>* out = nullptr;
    std::vector<std::string>* skipped = nullptr;

    void Add(Measurement m, const std::string& note) const {
        m.note = note;
        out->push_back(std::move(m));
    }
    void Skip(const std::string& reason) const { skipped->push_back(reason); }
    /// True when the real-data folder is set and `relative` exists in it; otherwise notes `what` as skipped.
    bool Need(const std::filesystem::path& relative, const std::string& what) const {
        if (data_dir.empty()) return Skip(what + ": no data folder"), false;
        if (std::filesystem::exists(data_dir / relative)) return true;
        return Skip(what + ": " + (data_dir / relative).string() + " absent"), false;
    }
};

void ReaderCases(const CaseContext& c);
/// The shared Livox walk read from its KITTI folder and from each ROS bag format.
void BagReaderCases(const CaseContext& c);
void OdometryCases(const CaseContext& c);
void LocalMapCases(const CaseContext& c);
void ClosureStageCases(const CaseContext& c);
void TreeCases(const CaseContext& c);
/// The database of a fleet: 8 sessions over size / 8 places, query+insert time and memory per map.
void FleetTreeCases(const CaseContext& c);
void RefinementCases(const CaseContext& c);
void PoseGraphCases(const CaseContext& c);
void GroundTruthCases(const CaseContext& c);
/// The ScanContext baseline's candidate search per scan, at several sequence lengths.
void ScanContextCases(const CaseContext& c);
void ConsistencyCases(const CaseContext& c);
void ProximityCases(const CaseContext& c);  ///< the proximity pass's overlap prediction per map
void ReportCases(const CaseContext& c);
void EndToEndCases(const CaseContext& c);

}  // namespace revisit
