/// A reference for part of a real log only (carmen_kitti/freiburg-101, 292 key frames of a 180 deg
/// laser, without its first and last 15% as a TUM file): the closure metrics of the local maps it
/// covers whole, every closure with a map outside them left out and counted, and every closure it
/// judges judged as the full reference judges it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <utility>

#include "cli.hpp"
#include "config/config.hpp"
#include "evaluation/ground_truth_closures.hpp"
#include "evaluation/pr_sweep.hpp"
#include "evaluation/predicted_closures.hpp"
#include "io/trajectory_io.hpp"
#include "runfolder/csv.hpp"
#include "runfolder/run_files.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;
using test::Quote;
using test::RunCli;

json ReadJson(const fs::path& file) {
    std::ifstream in(file);
    return json::parse(in);
}

/// Scans [first, last] of a KITTI folder as a TUM file: its times and its poses, orientation included.
void WriteTumOfScans(const fs::path& dataset, const fs::path& file, std::size_t first, std::size_t last) {
    const auto times = ReadTimes(dataset / "times.txt");
    const auto poses = ReadKittiPoses(dataset / "poses.txt").poses;
    std::ofstream out(file);
    for (std::size_t i = first; i <= last; ++i) {
        const Eigen::Vector3d p = poses.at(i).translation();
        const Eigen::Quaterniond q(poses.at(i).linear());
        char line[256];
        std::snprintf(line, sizeof line, "%.9f %.12f %.12f %.12f %.12f %.12f %.12f %.12f\n", times.at(i), p.x(), p.y(), p.z(), q.x(),
                      q.y(), q.z(), q.w());
        out << line;
    }
}

using ScanPairKey = std::pair<std::size_t, std::size_t>;  ///< (query first scan, reference first scan)

std::map<ScanPairKey, json> AcceptedByScans(const json& metrics) {
    std::map<ScanPairKey, json> by_scans;
    for (const auto& c : metrics["closure_truth"]["accepted"])
        by_scans[{c["query_first_scan"].get<std::size_t>(), c["ref_first_scan"].get<std::size_t>()}] = c;
    return by_scans;
}

/// The ground-truth cache of a run folder, whatever its key.
GtClosures ReadGtCache(const fs::path& file) {
    std::ifstream in(file);
    std::string magic, version, word, key;
    in >> magic >> version >> word >> key;
    in.seekg(0);
    const auto closures = ReadGroundTruthClosures(in, key);
    EXPECT_TRUE(closures) << file;
    return closures.value_or(GtClosures{});
}

TEST(PartialReference, ClosureMetricsOnTheMapsItCoversWholeAgreeWithTheFullReference) {
    const auto dataset = test::SharedData("carmen_kitti/freiburg-101");
    REVISIT_REQUIRE_DATA(dataset);
    test::TempDir dir;
    const std::size_t scans = ReadTimes(dataset / "times.txt").size();
    const std::size_t first = scans * 15 / 100, last = scans - 1 - scans * 15 / 100;
    WriteTumOfScans(dataset, dir / "middle.tum", first, last);
    // The folder's poses as the chain's (its own 2D odometry takes ~25 s here): the closures are
    // still detected and verified on the real scans, and judged against the reference.
    const std::string common = " --poses dataset --quiet --set output.scan_context=false --set output.elevation_ablation=false";
    // The folder's poses.txt as the reference of every scan; then the TUM file for the middle only.
    const auto full = RunCli("run " + Quote(dataset.string()) + " --out " + Quote((dir / "full").string()) + common +
                             " --set output.write_report=false");
    ASSERT_EQ(full.exit_code, 0) << full.output;
    const auto part = RunCli("run " + Quote(dataset.string()) + " --gt " + Quote((dir / "middle.tum").string()) + " --out " +
                             Quote((dir / "part").string()) + common);
    ASSERT_EQ(part.exit_code, 0) << part.output;

    const RunState state = ReadRunState(RunFolder(dir / "part"));
    ASSERT_EQ(state.reference_scans.size(), last - first + 1);
    // The reference is not an input of the chain: both runs found the same closures.
    const RunState full_state = ReadRunState(RunFolder(dir / "full"));
    ASSERT_EQ(full_state.closures.size(), state.closures.size());
    ASSERT_EQ(full_state.NumAccepted(), state.NumAccepted());

    const json f = ReadJson(dir / "full" / "metrics.json");
    const json p = ReadJson(dir / "part" / "metrics.json");
    // Every figure of a full reference is there, plus what the partial one covers.
    for (const auto& [key, value] : f.items()) EXPECT_TRUE(p.contains(key)) << key;
    EXPECT_FALSE(f.contains("reference"));
    const json& r = p["reference"];
    EXPECT_EQ(r["scans"], scans);
    EXPECT_EQ(r["paired_scans"], last - first + 1);

    // The maps wholly inside [first, last] are the evaluated ones.
    std::set<std::size_t> whole_map_scans;
    std::size_t whole_maps = 0;
    for (const auto& m : state.maps) {
        if (m.first_scan < first || m.last_scan > last) continue;
        ++whole_maps;
        for (std::size_t s = m.first_scan; s <= m.last_scan; ++s) whole_map_scans.insert(s);
    }
    EXPECT_EQ(r["evaluated_maps"], whole_maps);
    EXPECT_EQ(r["evaluated_scans"], whole_map_scans.size());
    EXPECT_LT(whole_maps, state.maps.size());
    EXPECT_GT(p["ground_truth"]["scan_pairs"].get<std::size_t>(), 0u);
    EXPECT_LE(p["ground_truth"]["scan_pairs"].get<std::size_t>(), f["ground_truth"]["scan_pairs"].get<std::size_t>());

    // Accepted closures: those between two evaluated maps are judged exactly as with the full
    // reference (the same reference poses of their first scans); the others are counted, never judged.
    std::size_t expected_left_out = 0, expected_left_out_accepted = 0;
    std::set<ScanPairKey> inside;
    for (const auto& record : state.closures) {
        if (!CorrectsTrajectory(record)) continue;
        const auto& c = record.closure;
        const bool covered = whole_map_scans.count(c.query_scans.first) && whole_map_scans.count(c.query_scans.last) &&
                             whole_map_scans.count(c.ref_scans.first) && whole_map_scans.count(c.ref_scans.last);
        if (!covered) {
            ++expected_left_out;
            expected_left_out_accepted += record.accepted;
        } else if (record.accepted) {
            inside.insert({c.query_scans.first, c.ref_scans.first});
        }
    }
    EXPECT_GT(expected_left_out_accepted, 0u);  // the test leaves real closures out
    EXPECT_GT(inside.size(), 0u);               // and judges others
    EXPECT_EQ(r["left_out_closures"], expected_left_out);
    EXPECT_EQ(r["left_out_accepted_closures"], expected_left_out_accepted);
    const auto judged = AcceptedByScans(p), judged_full = AcceptedByScans(f);
    EXPECT_EQ(judged.size() + expected_left_out_accepted, judged_full.size());
    std::set<ScanPairKey> judged_keys;
    for (const auto& [key, verdict] : judged) {
        judged_keys.insert(key);
        ASSERT_TRUE(judged_full.count(key)) << key.first << " " << key.second;
        const json& full_verdict = judged_full.at(key);
        EXPECT_EQ(verdict["true"], full_verdict["true"]);
        EXPECT_NEAR(verdict["translation_error_m"].get<double>(), full_verdict["translation_error_m"].get<double>(), 1e-6);
        EXPECT_NEAR(verdict["yaw_error_deg"].get<double>(), full_verdict["yaw_error_deg"].get<double>(), 1e-5);
    }
    EXPECT_EQ(judged_keys, inside);
    const auto& pt = p["closure_truth"];
    EXPECT_EQ(pt["true"].get<std::size_t>() + pt["false"].get<std::size_t>(), inside.size());
    // Revisits and missed revisits only between evaluated maps.
    std::set<int> evaluated_ids;
    for (const auto& m : state.maps)
        if (m.first_scan >= first && m.last_scan <= last) evaluated_ids.insert(m.id);
    for (const auto& m : p["missed_revisits"]["missed"]) {
        EXPECT_TRUE(evaluated_ids.count(m["query_map"].get<int>())) << m.dump();
        EXPECT_TRUE(evaluated_ids.count(m["ref_map"].get<int>())) << m.dump();
    }
    EXPECT_GT(p["revisit_coverage"]["revisit_scans"].get<std::size_t>(), 0u);

    // The ground truth of the covered part against the full one's pairs between the same scans (the
    // segments of 2 m start at the first evaluated scan instead of the run's first).
    const auto full_gt = ReadGtCache(dir / "full" / "ground_truth_closures.txt");
    const auto part_gt = ReadGtCache(dir / "part" / "ground_truth_closures.txt");
    const std::vector<std::size_t> evaluated(whole_map_scans.begin(), whole_map_scans.end());
    std::set<ScanPair> full_pairs, part_pairs;
    for (const auto& pair : full_gt.scan_pairs)
        if (whole_map_scans.count(pair.first) && whole_map_scans.count(pair.second)) full_pairs.insert(pair);
    for (const auto& pair : part_gt.scan_pairs) part_pairs.insert({evaluated.at(pair.first), evaluated.at(pair.second)});
    std::size_t common_pairs = 0;
    for (const auto& pair : part_pairs) common_pairs += full_pairs.count(pair);
    std::printf("ground truth between the evaluated scans: full reference %zu pairs, partial %zu, both %zu\n", full_pairs.size(),
                part_pairs.size(), common_pairs);
    const std::size_t gt_differ = full_pairs.size() + part_pairs.size() - 2 * common_pairs;
    EXPECT_LT(gt_differ, common_pairs / 20);  // the same revisits

    // Precision and recall of the density closures: the full run's predicted scan pairs between the
    // evaluated scans, scored against its ground truth between them, at every threshold, are the
    // partial evaluation's curve: the same pairs predicted (none with a scan outside), true positives
    // apart by at most the pairs on which the two ground truths differ.
    PipelineConfig config = LoadConfig({(dir / "part" / "config.yaml").string()}, {});
    config.predicted.max_distance = p["ground_truth"]["tau_d_m"].get<double>();  // as the partial evaluation resolved it
    std::vector<MapClosureForEval> density_closures;
    for (const auto& record : full_state.closures) {
        if (record.method != "density") continue;
        MapClosureForEval c;
        c.query_first_scan = record.closure.query_scans.first;
        c.query_last_scan = record.closure.query_scans.last;
        c.ref_first_scan = record.closure.ref_scans.first;
        c.ref_last_scan = record.closure.ref_scans.last;
        c.T_query_ref = record.refined && record.accepted ? record.refinement.T_query_ref : Eigen::Isometry3d(record.closure.T_query_ref);
        c.inliers = record.closure.num_inliers;
        density_closures.push_back(c);
    }
    std::vector<ScoredPair> restricted;
    for (const auto& p : ExpandMapClosures(density_closures, full_state.odometry, config.predicted))
        if (whole_map_scans.count(p.pair.first) && whole_map_scans.count(p.pair.second)) restricted.push_back(p);
    const auto sweep = SweepPrecisionRecall(restricted, std::vector<ScanPair>(full_pairs.begin(), full_pairs.end()),
                                            InlierThresholds(restricted), Acceptance::kScoreAtLeast);
    const auto curve = CsvTable::Read(dir / "part" / "pr_curve_density.csv");
    ASSERT_EQ(curve.size(), sweep.curve.size());
    ASSERT_GT(sweep.curve.size(), 0u);
    EXPECT_GT(sweep.curve.front().true_positives, 0u);
    for (std::size_t i = 0; i < curve.size(); ++i) {
        const auto& point = sweep.curve[i];
        EXPECT_EQ(curve.Number(i, "threshold"), point.threshold);
        EXPECT_EQ(static_cast<std::size_t>(curve.Integer(i, "predicted")), point.num_predicted) << "threshold " << point.threshold;
        EXPECT_LE(std::llabs(curve.Integer(i, "true_positives") - static_cast<long long>(point.true_positives)),
                  static_cast<long long>(gt_differ)) << "threshold " << point.threshold;
    }
    std::printf("density maps between the evaluated scans: full reference P %.3f / R %.3f at %g inliers\n", sweep.best.precision,
                sweep.best.recall, sweep.best.threshold);

    const auto density = [](const json& metrics) { return metrics["methods"][0]; };
    std::printf("freiburg-101, --poses dataset: full reference %zu scans, partial %zu paired (%zu in %zu of %zu maps evaluated)\n"
                "  ground-truth scan pairs %zu vs %zu; density P %.3f / R %.3f vs P %.3f / R %.3f; accepted true/false %d/%d vs %d/%d; "
                "left out %zu candidates (%zu accepted); coverage %.3f of %d vs %.3f of %d\n",
                scans, last - first + 1, whole_map_scans.size(), whole_maps, state.maps.size(),
                f["ground_truth"]["scan_pairs"].get<std::size_t>(), p["ground_truth"]["scan_pairs"].get<std::size_t>(),
                density(f)["precision"].get<double>(), density(f)["recall"].get<double>(), density(p)["precision"].get<double>(),
                density(p)["recall"].get<double>(), f["closure_truth"]["true"].get<int>(), f["closure_truth"]["false"].get<int>(),
                pt["true"].get<int>(), pt["false"].get<int>(), expected_left_out, expected_left_out_accepted,
                f["revisit_coverage"]["coverage"].get<double>(), f["revisit_coverage"]["revisit_scans"].get<int>(),
                p["revisit_coverage"]["coverage"].get<double>(), p["revisit_coverage"]["revisit_scans"].get<int>());

    // What the user reads: the summary and the report say what the closure figures cover.
    EXPECT_NE(part.output.find("reference poses for " + std::to_string(last - first + 1) + " of " + std::to_string(scans) + " scans"),
              std::string::npos) << part.output;
    EXPECT_NE(part.output.find("closure metrics on " + std::to_string(whole_map_scans.size()) + " of " + std::to_string(scans) + " scans"),
              std::string::npos) << part.output;
    EXPECT_NE(part.output.find(std::to_string(expected_left_out) + " closure candidates (" + std::to_string(expected_left_out_accepted) +
                               " accepted) involve scans without a reference pose: left out"),
              std::string::npos) << part.output;
    EXPECT_NE(part.output.find("precision  recall"), std::string::npos) << part.output;
    const std::string index = test::ReadFile(dir / "part" / "report" / "index.html");
    EXPECT_NE(index.find("cover " + std::to_string(whole_map_scans.size()) + " of " + std::to_string(scans) + " scans"), std::string::npos);
    EXPECT_NE(index.find("Were the revisits found?"), std::string::npos);
}

}  // namespace
}  // namespace revisit
