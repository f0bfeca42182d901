// revisit batch on a real, single-node Slurm cluster started by the test (scripts/slurm-single-node.sh:
// munged, slurmctld and slurmd on this host, state in a temporary folder), and on the local engine.
// Skips with the reason when Slurm is not installed or cannot start (e.g. not root).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "fleet_sessions.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

/// The daemons of one test, stopped (by their pid files) when it ends.
class SingleNodeSlurm {
  public:
    SingleNodeSlurm() {
        script_ = std::string(REVISIT_SOURCE_DIR) + "/scripts/slurm-single-node.sh";
        const std::string log = (dir_ / "start.log").string();
        const int status = std::system((Quote(script_) + " start " + Quote((dir_ / "cluster").string()) + " > " + Quote(log) + " 2>&1").c_str());
        std::ifstream in(log);
        std::getline(in, message_, '\0');
        started_ = status == 0;
        if (started_) setenv("SLURM_CONF", (dir_ / "cluster" / "slurm.conf").c_str(), 1);
    }
    ~SingleNodeSlurm() {
        std::system((Quote(script_) + " stop " + Quote((dir_ / "cluster").string()) + " > /dev/null 2>&1").c_str());
        unsetenv("SLURM_CONF");
    }
    bool started() const { return started_; }
    const std::string& message() const { return message_; }

  private:
    test::TempDir dir_;
    std::string script_;
    std::string message_;
    bool started_ = false;
};

nlohmann::json ReadJson(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

/// The two overlapping sessions of the city drive, cut by the manifest itself.
fs::path WriteManifest(const fs::path& folder, const fs::path& city, const std::string& extra = "") {
    fs::create_directories(folder);
    const fs::path manifest = folder / "fleet.yaml";
    std::ofstream(manifest) << "sequences:\n  - {path: " << city.string() << ", to: 199}\n  - {path: " << city.string()
                            << ", from: 110}\n" << extra;
    return manifest;
}

const std::string kSmall = " --set output.write_report=false --set fleet.slurm_cpus_per_task=1 --set fleet.slurm_memory_mb=1000";

TEST(BatchSlurm, RunsTheManifestAsAJobArrayMergesAfterItResumesAndListsFailures) {
    if (geteuid() != 0) GTEST_SKIP() << "the single-node Slurm cluster needs root (munged, slurmd)";
    const SingleNodeSlurm slurm;
    if (!slurm.started()) GTEST_SKIP() << "Slurm could not start: " << slurm.message();
    auto& fleet = test::Fleet();
    const fs::path city = fleet.City();
    const fs::path work = fleet.dir() / "slurm_batch";
    const fs::path manifest = WriteManifest(work, city);
    const fs::path out = work / "out";
    const auto batch = RunCli("batch " + Quote(manifest.string()) + " --out " + Quote(out.string()) + " --engine slurm --poll 0.3" + kSmall);
    ASSERT_EQ(batch.exit_code, 0) << batch.output;
    EXPECT_NE(batch.output.find("submitted: run array"), std::string::npos) << batch.output;
    EXPECT_NE(batch.output.find("merge: 2 of 2 sessions in one frame"), std::string::npos) << batch.output;
    const auto sessions = ReadJson(out / "merge" / "sessions.json");
    EXPECT_EQ(sessions["connected_sessions"], 2);
    EXPECT_GE(sessions["cross_closures"]["accepted"].get<int>(), 1);
    EXPECT_TRUE(fs::exists(out / "slurm" / "runs.sbatch"));
    EXPECT_TRUE(fs::exists(out / "logs" / "00_city_0-199.log"));

    // Resume: both runs are finished, so only the merge is submitted again.
    const auto resume = RunCli("batch " + Quote(manifest.string()) + " --out " + Quote(out.string()) +
                               " --engine slurm --resume --poll 0.3" + kSmall);
    ASSERT_EQ(resume.exit_code, 0) << resume.output;
    EXPECT_NE(resume.output.find("resume: 0 of 2 runs to (re)do"), std::string::npos) << resume.output;
    EXPECT_NE(resume.output.find("run array (none: every run finished)"), std::string::npos) << resume.output;

    // A third session starting past the end of the recording: its task fails, is listed with its log, and
    // the merge (afterok) never runs. --resume reruns only that task.
    const fs::path failing = WriteManifest(work / "failing", city, "  - {path: " + city.string() + ", from: 5000}\n");
    const auto failed = RunCli("batch " + Quote(failing.string()) + " --out " + Quote(out.string()) +
                               " --engine slurm --resume --poll 0.3" + kSmall);
    EXPECT_EQ(failed.exit_code, 1) << failed.output;
    EXPECT_NE(failed.output.find("resume: 1 of 3 runs to (re)do"), std::string::npos) << failed.output;
    EXPECT_NE(failed.output.find("FAILED task 2 (02_city_5000-end)"), std::string::npos) << failed.output;
    EXPECT_NE(failed.output.find((out / "logs" / "02_city_5000-end.log").string()), std::string::npos) << failed.output;
    EXPECT_NE(failed.output.find("is past the end"), std::string::npos) << failed.output;  // the log's tail
    EXPECT_NE(failed.output.find("failed: 02_city_5000-end"), std::string::npos) << failed.output;
}

TEST(BatchLocal, RunsTheManifestOnThisMachineThenMerges) {
    auto& fleet = test::Fleet();
    const fs::path work = fleet.dir() / "local_batch";
    const fs::path manifest = WriteManifest(work, fleet.City());
    const fs::path out = work / "out";
    const auto batch = RunCli("batch " + Quote(manifest.string()) + " --out " + Quote(out.string()) +
                              " --engine local --jobs 2 --set output.write_report=false");
    ASSERT_EQ(batch.exit_code, 0) << batch.output;
    EXPECT_NE(batch.output.find("run 2/2"), std::string::npos) << batch.output;
    const auto sessions = ReadJson(out / "merge" / "sessions.json");
    EXPECT_EQ(sessions["connected_sessions"], 2);
    EXPECT_GE(sessions["cross_closures"]["accepted"].get<int>(), 1);
}

TEST(BatchLocal, ALinkPlantedAtALogsNameIsReplacedNotWrittenThrough) {
    auto& fleet = test::Fleet();
    const fs::path work = fleet.dir() / "planted_logs";
    const fs::path manifest = WriteManifest(work, fleet.City());
    const std::string batch = "batch " + Quote(manifest.string()) + " --engine local --jobs 2 --set output.write_report=false";
    const auto first = RunCli(batch + " --out " + Quote((work / "first").string()));
    ASSERT_EQ(first.exit_code, 0) << first.output;
    // The same log names in a fresh folder, each a link to a file of someone else's.
    const fs::path victim = work / "precious.txt";
    std::ofstream(victim) << "mine";
    fs::create_directories(work / "second" / "logs");
    std::size_t planted = 0;
    for (const auto& log : fs::directory_iterator(work / "first" / "logs")) {
        fs::create_symlink(victim, work / "second" / "logs" / log.path().filename());
        ++planted;
    }
    ASSERT_GE(planted, 3u);  // two runs and the merge
    const auto second = RunCli(batch + " --force --out " + Quote((work / "second").string()));
    ASSERT_EQ(second.exit_code, 0) << second.output;
    EXPECT_EQ(test::ReadFile(victim), "mine");
    for (const auto& log : fs::directory_iterator(work / "second" / "logs")) {
        EXPECT_FALSE(fs::is_symlink(log.symlink_status())) << log.path();
        EXPECT_GT(fs::file_size(log.path()), 0u) << log.path();
    }
}

}  // namespace
}  // namespace revisit
