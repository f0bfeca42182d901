// revisit batch without running anything: manifests, the commands of a plan, the Slurm scripts that
// --dry-run prints, and reading Slurm's job states.
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "fleet/batch_plan.hpp"
#include "fleet/batch_slurm.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;

void Write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

TEST(BatchManifest, ReadsYamlAndCsvWithPathsRelativeToTheManifest) {
    test::TempDir dir;
    fs::create_directories(dir / "data/day1");
    fs::create_directories(dir / "data/day2");
    Write(dir / "data/gt1.txt", "");
    Write(dir / "fleet.yaml",
          "sequences:\n"
          "  - path: data/day1\n"
          "    config: kitti\n"
          "    reference: data/gt1.txt\n"
          "  - {path: data/day2, config: configs/mine.yaml, from: 100, to: 499}\n"
          "  - data/day2\n");
    const auto yaml = ReadManifest(dir / "fleet.yaml");
    ASSERT_EQ(yaml.size(), 3u);
    EXPECT_EQ(yaml[0].path, dir / "data/day1");
    EXPECT_EQ(yaml[0].config, "kitti");  // a preset name stays a name
    EXPECT_EQ(yaml[0].reference, dir / "data/gt1.txt");
    EXPECT_EQ(yaml[1].config, (dir / "configs/mine.yaml").string());
    EXPECT_EQ(yaml[1].from, 100u);
    EXPECT_EQ(yaml[1].to, 499u);
    EXPECT_FALSE(yaml[2].from.has_value());

    Write(dir / "fleet.csv", "path,config,reference,from,to\n# a comment\ndata/day1,,data/gt1.txt\ndata/day2,kitti,,0,99\n");
    const auto csv = ReadManifest(dir / "fleet.csv");
    ASSERT_EQ(csv.size(), 2u);
    EXPECT_EQ(csv[0].reference, dir / "data/gt1.txt");
    EXPECT_EQ(csv[1].config, "kitti");
    EXPECT_EQ(csv[1].to, 99u);
}

TEST(BatchManifest, BadManifestsAreNamedErrors) {
    test::TempDir dir;
    const auto message = [&](const std::string& name, const std::string& text) {
        Write(dir / name, text);
        try {
            ReadManifest(dir / name);
        } catch (const DatasetError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("a.csv", "missing/folder\n").find("missing/folder: no such dataset"), std::string::npos);
    EXPECT_NE(message("b.csv", "").find("b.csv"), std::string::npos);
    fs::create_directories(dir / "d");
    EXPECT_NE(message("c.csv", "d,,,ten\n").find("c.csv: line 1: 'ten' is not a scan index"), std::string::npos)
        << message("c.csv", "d,,,ten\n");
    EXPECT_NE(message("e.yaml", "sequences:\n  - {path: d, speed: 3}\n").find("unknown key 'speed'"), std::string::npos);
    EXPECT_NE(message("f.yaml", "runs: [d]\n").find("needs a list `sequences:`"), std::string::npos);
    EXPECT_THROW(ReadManifest(dir / "nothing.csv"), DatasetError);
}

BatchPlan ExamplePlan() {
    std::vector<BatchSequence> sequences(2);
    sequences[0].path = "/data/day 1";
    sequences[0].reference = "/data/gt1.txt";
    sequences[1].path = "/data/it's";
    sequences[1].config = "kitti";
    sequences[1].from = 10;
    sequences[1].to = 99;
    return MakeBatchPlan(sequences, "/shared/fleet", "/opt/revisit/bin/revisit", {"ouster"}, {"fleet.slurm_memory_mb=2000"}, 2);
}

TEST(BatchPlan, OneRunPerSequenceThenAMergeOfEveryRun) {
    const auto plan = ExamplePlan();
    ASSERT_EQ(plan.tasks.size(), 2u);
    EXPECT_EQ(plan.tasks[0].name, "00_day 1");
    EXPECT_EQ(plan.tasks[1].name, "01_it's_10-99");
    EXPECT_EQ(ShellCommand(plan.executable, plan.tasks[1].arguments),
              "'/opt/revisit/bin/revisit' 'run' '/data/it'\\''s' '--out' '/shared/fleet/runs/01_it'\\''s_10-99' '--force' "
              "'--quiet' '--config' 'ouster' '--config' 'kitti' '--set' 'fleet.slurm_memory_mb=2000' '--from' '10' '--to' "
              "'99' '--threads' '2'");
    EXPECT_EQ(ShellCommand(plan.executable, plan.merge_arguments),
              "'/opt/revisit/bin/revisit' 'merge' '/shared/fleet/runs/00_day 1' '/shared/fleet/runs/01_it'\\''s_10-99' "
              "'--out' '/shared/fleet/merge' '--force' '--threads' '2'");
}

TEST(BatchSlurm, DryRunScriptsHaveTheExpectedContent) {
    const auto plan = ExamplePlan();
    FleetConfig fleet;
    fleet.slurm_cpus_per_task = 4;
    fleet.slurm_memory_mb = 2000;
    fleet.slurm_time_minutes = 30;
    fleet.slurm_partition = "cpu";
    EXPECT_EQ(SlurmArrayScript(plan, {1}, fleet),
              "#!/bin/bash\n"
              "#SBATCH --job-name=revisit-runs\n"
              "#SBATCH --output=/shared/fleet/logs/slurm_%A_%a.out\n"
              "#SBATCH --cpus-per-task=4\n"
              "#SBATCH --mem=2000M\n"
              "#SBATCH --time=30\n"
              "#SBATCH --partition=cpu\n"
              "#SBATCH --array=1\n"
              "# One `revisit run` per manifest sequence; the task id is the sequence's index.\n"
              "# A log's name is removed first and opened without clobbering (set -C): a link planted there is\n"
              "# replaced, never written through.\n"
              "set -uC\n"
              "case \"$SLURM_ARRAY_TASK_ID\" in\n"
              "  1) rm -f -- '/shared/fleet/logs/01_it'\\''s_10-99.log' && exec " + ShellCommand(plan.executable, plan.tasks[1].arguments) +
              " > '/shared/fleet/logs/01_it'\\''s_10-99.log' 2>&1 ;;\n"
              "esac\n"
              "echo \"revisit batch: no task $SLURM_ARRAY_TASK_ID\" >&2\n"
              "exit 2\n");
    fleet.slurm_partition.clear();
    EXPECT_EQ(SlurmMergeScript(plan, fleet),
              "#!/bin/bash\n"
              "#SBATCH --job-name=revisit-merge\n"
              "#SBATCH --output=/shared/fleet/logs/slurm_merge_%j.out\n"
              "#SBATCH --cpus-per-task=4\n"
              "#SBATCH --mem=2000M\n"
              "#SBATCH --time=30\n"
              "# The cross-session merge of every run; submitted with --dependency=afterok on the run array.\n"
              "set -C\n"
              "rm -f -- '/shared/fleet/logs/merge.log' && exec " + ShellCommand(plan.executable, plan.merge_arguments) +
              " > '/shared/fleet/logs/merge.log' 2>&1\n");
    EXPECT_NE(SlurmArrayScript(plan, {0, 1}, fleet).find("#SBATCH --array=0,1\n"), std::string::npos);
}

TEST(BatchSlurm, ReadsJobStatesFromSacctAndScontrol) {
    const auto sacct = ParseSacct("12_0|COMPLETED|0:0\n12_0.batch|COMPLETED|0:0\n12_1|FAILED|1:0\n13|CANCELLED by 0|0:0\n");
    ASSERT_EQ(sacct.size(), 3u);
    EXPECT_EQ(sacct[1].id, "12_1");
    EXPECT_EQ(sacct[1].state, "FAILED");
    EXPECT_EQ(sacct[1].exit_code, "1:0");
    EXPECT_EQ(sacct[2].state, "CANCELLED");
    const auto scontrol = ParseScontrol(
        "JobId=14 ArrayJobId=12 ArrayTaskId=1 JobName=revisit-runs JobState=FAILED Reason=NonZeroExitCode ExitCode=1:0\n"
        "JobId=13 JobName=revisit-merge JobState=COMPLETED Reason=None ExitCode=0:0\n");
    ASSERT_EQ(scontrol.size(), 2u);
    EXPECT_EQ(scontrol[0].id, "12_1");
    EXPECT_EQ(scontrol[0].state, "FAILED");
    EXPECT_EQ(scontrol[1].id, "13");
    EXPECT_EQ(scontrol[1].exit_code, "0:0");
}

}  // namespace
}  // namespace revisit
