/// Issue 17, the commands' side: damaged options, ground truth, configs and run folders give a named
/// error (or, for the report's closure database, a named warning), never a silent result.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "test_data.hpp"
#include "cli.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"
#include "runfolder/csv.hpp"
#include "runfolder/run_files.hpp"
#include "sim_dataset.hpp"
#include "small_disk.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using test::Quote;
using test::RunCli;

/// One finished run of the first 301 scans (3 local maps), made once; tests damage copies of it.
const fs::path& GoodRun() {
    static test::TempDir dir;
    static const fs::path run = [] {
        const fs::path out = dir / "run";
        const auto result = RunCli("run " + Quote(test::TinySimDataset().string()) +
                                   " --to 300 --quiet --set output.write_report=false --out " + Quote(out.string()));
        EXPECT_EQ(result.exit_code, 0) << result.output;
        return out;
    }();
    return run;
}

/// A KITTI folder of 5 small scans, for the checks that fail before any scan is processed.
fs::path FiveScanKitti(const test::TempDir& dir) {
    const fs::path root = dir / "kitti5";
    fs::create_directories(root / "velodyne");
    for (int i = 0; i < 5; ++i) {
        std::ofstream bin(root / "velodyne" / ("00000" + std::to_string(i) + ".bin"), std::ios::binary);
        const float point[4] = {float(i), 1.f, 2.f, 0.5f};
        for (int k = 0; k < 10; ++k) bin.write(reinterpret_cast<const char*>(point), sizeof(point));
    }
    return root;
}

/// A copy of the good run; `keep_manifest` false: without run.json's `files` table (as a run of an
/// earlier version), so that damage reaches the parsers instead of stopping at the size check.
fs::path CopyOfGoodRun(const test::TempDir& dir, bool keep_manifest = false) {
    const fs::path copy = dir / "run";
    fs::copy(GoodRun(), copy, fs::copy_options::recursive);
    if (!keep_manifest) {
        nlohmann::json info = nlohmann::json::parse(test::ReadFile(copy / "run.json"));
        info.erase("files");
        std::ofstream(copy / "run.json", std::ios::trunc) << info.dump(2) << '\n';
    }
    return copy;
}

/// Replaces the first occurrence of `from` in line `line` (1: the header) of `file` by `to`.
void ReplaceInLine(const fs::path& file, int line, const std::string& from, const std::string& to) {
    std::string text = test::ReadFile(file);
    std::size_t start = 0;
    for (int i = 1; i < line; ++i) start = text.find('\n', start) + 1;
    const auto at = text.find(from, start);
    ASSERT_LT(at, text.find('\n', start)) << from << " not in line " << line << " of " << file;
    text.replace(at, from.size(), to);
    std::ofstream(file, std::ios::binary) << text;
}

TEST(DamagedRun, ScanRangesThatSelectNothingAreNamedErrors) {
    test::TempDir dir;
    const std::string run = "run " + Quote(FiveScanKitti(dir).string()) + " --quiet --out " + Quote((dir / "r").string());
    const auto backwards = RunCli(run + " --from 10 --to 5");
    EXPECT_EQ(backwards.exit_code, 1);
    EXPECT_NE(backwards.output.find("--from 10 --to 5: an empty range"), std::string::npos) << backwards.output;
    const auto past = RunCli(run + " --from 7");
    EXPECT_EQ(past.exit_code, 1);
    EXPECT_NE(past.output.find("--from 7 is past the end: the dataset has 5 scans"), std::string::npos) << past.output;
    const auto negative = RunCli(run + " --from -3");
    EXPECT_EQ(negative.exit_code, 1);
    EXPECT_NE(negative.output.find("--from -3"), std::string::npos) << negative.output;
    EXPECT_FALSE(fs::exists(dir / "r"));
}

TEST(DamagedRun, GroundTruthWithAnotherPoseCountIsANamedError) {
    test::TempDir dir;
    std::ofstream gt(dir / "gt.txt");
    for (int i = 0; i < 10; ++i) gt << "1 0 0 " << i << " 0 1 0 0 0 0 1 0\n";
    gt.close();
    const auto result = RunCli("run " + Quote(FiveScanKitti(dir).string()) + " --quiet --gt " +
                               Quote((dir / "gt.txt").string()) + " --out " + Quote((dir / "r").string()));
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find("gt.txt: --gt has 10 poses for 5 scans"), std::string::npos) << result.output;
}

TEST(DamagedRun, AConfigThatIsAFolderIsNamed) {
    test::TempDir dir;
    const auto result = RunCli("config --config " + Quote(dir.path().string()));
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find(dir.path().string() + ": is a folder"), std::string::npos) << result.output;
}






/// One finished run, damaged in turn (one test: the run is made once per test process).
TEST(DamagedRun, DamagedRunFoldersAreNamed) {
    {  // NonFiniteOrImplausibleRunFilesAreNamedErrors
        test::TempDir dir;
        const fs::path run = CopyOfGoodRun(dir);
        // NaN in a map pose, then a resolution no run writes: errors with file and line, not solver text.
        const auto maps = RunFolder(run).local_maps_csv();
        const std::string original = test::ReadFile(maps);
        const auto table = CsvTable::Read(maps);
        ASSERT_GE(table.size(), 2u);
        ReplaceInLine(maps, 3, "," + table.Text(1, "density_resolution") + ",", ",1e-300,");
        const auto tiny = RunCli("report " + Quote(run.string()));
        EXPECT_EQ(tiny.exit_code, 1);
        EXPECT_NE(tiny.output.find("local_maps.csv:3: density_resolution"), std::string::npos) << tiny.output;
        std::ofstream(maps, std::ios::binary) << original;
        // The translation x of the corrected pose: the 13th field from the end of row 1 (12 T_ground_map fields follow).
        std::string row = test::ReadFile(maps).substr(test::ReadFile(maps).find('\n') + 1);
        row = row.substr(0, row.find('\n'));
        std::size_t at = row.size();
        for (int i = 0; i < 13; ++i) at = row.rfind(',', at - 1);
        const std::size_t end = row.find(',', at + 1);
        ReplaceInLine(maps, 2, row, row.substr(0, at + 1) + "nan" + row.substr(end));
        const auto nan = RunCli("report " + Quote(run.string()));
        EXPECT_EQ(nan.exit_code, 1);
        EXPECT_NE(nan.output.find("local_maps.csv:2: column"), std::string::npos) << nan.output;
        EXPECT_NE(nan.output.find("not finite"), std::string::npos) << nan.output;
    }
    {  // NanPoseInClosuresCsvIsANamedError
        test::TempDir dir;
        const fs::path run = CopyOfGoodRun(dir);
        const auto file = RunFolder(run).closures_csv();
        const std::string header = test::ReadFile(file).substr(0, test::ReadFile(file).find('\n'));
        // One closure row: identity poses, except a NaN translation.
        std::string row;
        std::size_t start = 0;
        for (std::size_t column = 0;; ++column) {
            const auto end = header.find(',', start);
            const std::string name = header.substr(start, end - start);
            std::string value = "0";
            if (name == "method") value = "density";
            else if (name == "query") value = "1";
            else if (name == "reason") value = "x";
            else if (name.size() > 3 && (name.substr(name.size() - 3) == "_00" || name.substr(name.size() - 3) == "_11" ||
                                         name.substr(name.size() - 3) == "_22"))
                value = "1";
            if (name == "T_query_ref_03") value = "nan";
            row += (column ? "," : "") + value;
            if (end == std::string::npos) break;
            start = end + 1;
        }
        std::ofstream(file, std::ios::binary) << header << '\n' << row << '\n';
        const auto result = RunCli("report " + Quote(run.string()));
        EXPECT_EQ(result.exit_code, 1);
        EXPECT_NE(result.output.find("closures.csv:2: column 'T_query_ref_03': not finite"), std::string::npos) << result.output;
    }
    {  // CorruptDatabaseIsAWarningForReportAndAnErrorForInspect
        test::TempDir dir;
        const fs::path run = CopyOfGoodRun(dir);
        const auto database = RunFolder(run).database();
        std::string bytes = test::ReadFile(database);
        bytes[bytes.size() / 2] ^= 0x5a;
        std::ofstream(database, std::ios::binary) << bytes;
        const auto report = RunCli("report " + Quote(run.string()));
        EXPECT_EQ(report.exit_code, 0) << report.output;
        EXPECT_NE(report.output.find("warning: " + database.string() + ": corrupt closure database"), std::string::npos)
            << report.output;
        const auto inspect = RunCli("inspect " + Quote(run.string()) + " --maps 1 0");
        EXPECT_EQ(inspect.exit_code, 1);
        EXPECT_NE(inspect.output.find(database.string()), std::string::npos) << inspect.output;
        fs::remove(database);
        const auto missing = RunCli("inspect " + Quote(run.string()) + " --maps 1 0");
        EXPECT_EQ(missing.exit_code, 1);
        EXPECT_NE(missing.output.find("database.bin: no such file"), std::string::npos) << missing.output;
    }
    {  // HugeDensityImageIsRefusedBeforeDecoding
        test::TempDir dir;
        const fs::path run = CopyOfGoodRun(dir);
        const auto png = RunFolder(run).map_density(0);
        std::string bytes = test::ReadFile(png);
        ASSERT_GT(bytes.size(), 24u);
        const unsigned char side[4] = {0x00, 0x00, 0x4e, 0x20};  // 20000, big-endian
        bytes.replace(16, 4, reinterpret_cast<const char*>(side), 4);
        bytes.replace(20, 4, reinterpret_cast<const char*>(side), 4);
        std::ofstream(png, std::ios::binary) << bytes;
        // The bounded report draws only the maps of its closure pages; the map's own page must decode it.
        const auto start = std::chrono::steady_clock::now();
        const auto result = RunCli("inspect " + Quote(run.string()) + " --map 0");
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
        EXPECT_EQ(result.exit_code, 1);
        EXPECT_NE(result.output.find(png.string() + ": image declares 20000 x 20000 pixels"), std::string::npos) << result.output;
    }
    {  // ResultFilesCutOrChangedAfterTheRunAreNamedByTheManifest
        test::TempDir dir;
        const fs::path run = CopyOfGoodRun(dir, true);
        const auto info = nlohmann::json::parse(test::ReadFile(run / "run.json"));
        ASSERT_TRUE(info.at("files").contains("closures.csv")) << info.dump(2);
        ASSERT_TRUE(info.at("files").contains("maps/map_0000.rvmap"));
        // closures.csv cut at a line boundary (still valid CSV: it would read as fewer closures).
        const auto closures = RunFolder(run).closures_csv();
        const std::string original = test::ReadFile(closures);
        // With closures: only the header kept; without: the header cut to 50 bytes.
        const bool has_rows = std::count(original.begin(), original.end(), '\n') > 1;
        std::ofstream(closures, std::ios::binary | std::ios::trunc)
            << original.substr(0, has_rows ? original.find('\n') + 1 : 50);
        for (const std::string& command : {"report", "eval", "inspect"}) {
            const auto result = RunCli(command + " " + Quote(run.string()) + (command == "inspect" ? " --map 0" : ""));
            EXPECT_EQ(result.exit_code, 1) << command << ": " << result.output;
            EXPECT_NE(result.output.find(closures.string() + ": has "), std::string::npos) << command << ": " << result.output;
            EXPECT_NE(result.output.find("run.json says"), std::string::npos) << result.output;
        }
        const auto merge = RunCli("merge " + Quote(run.string()) + " " + Quote(GoodRun().string()) + " --out " + Quote((dir / "m").string()));
        EXPECT_EQ(merge.exit_code, 1) << merge.output;
        EXPECT_NE(merge.output.find(closures.string()), std::string::npos) << merge.output;
        std::ofstream(closures, std::ios::binary | std::ios::trunc) << original;
        // One flipped byte in a map's points: same size, another CRC-32.
        const fs::path map = run / "maps" / "map_0000.rvmap";
        std::string bytes = test::ReadFile(map);
        bytes[bytes.size() / 3] ^= 0x01;
        std::ofstream(map, std::ios::binary | std::ios::trunc) << bytes;
        const auto flipped = RunCli("report " + Quote(run.string()));
        EXPECT_EQ(flipped.exit_code, 1) << flipped.output;
        EXPECT_NE(flipped.output.find(map.string() + ": CRC-32"), std::string::npos) << flipped.output;
    }
    {  // AFolderWhereAFileShouldBeIsNamed
        test::TempDir dir;
        const fs::path run = CopyOfGoodRun(dir, true);
        for (const char* name : {"database.bin", "run.json"}) {
            fs::path file = run / name;
            const fs::path saved = dir / (std::string(name) + ".saved");
            fs::rename(file, saved);
            fs::create_directories(file);
            for (const std::string& command : {"inspect " + Quote(run.string()) + " --map 0", "eval " + Quote(run.string())}) {
                const auto result = RunCli(command);
                EXPECT_EQ(result.exit_code, 1) << command << ": " << result.output;
                EXPECT_NE(result.output.find(file.string() + ": is a folder, expected a file"), std::string::npos)
                    << command << ": " << result.output;
                EXPECT_EQ(result.output.find("basic_filebuf"), std::string::npos) << result.output;
            }
            fs::remove(file);
            fs::rename(saved, file);
        }
    }
    {  // InspectOfAMapThatDoesNotExistIsANamedError
        const auto result = RunCli("inspect " + Quote(GoodRun().string()) + " --maps 99 0");
        EXPECT_EQ(result.exit_code, 1);
        EXPECT_NE(result.output.find("no map 99"), std::string::npos) << result.output;
    }
}

TEST(DamagedRun, AFullDiskIsNamedAndLeavesNoEmptyOrPartialFiles) {
    test::SmallDisk disk(512 * 1024);
    if (!disk.mounted()) GTEST_SKIP() << "cannot mount a small tmpfs (needs root)";
    const fs::path out = disk.path() / "run";
    const auto result = RunCli("run " + Quote(test::TinySimDataset().string()) + " --to 300 --quiet --out " +
                               Quote(out.string()));
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_NE(result.output.find("No space left on device"), std::string::npos) << result.output;
    std::size_t files = 0;
    for (const auto& entry : fs::recursive_directory_iterator(disk.path())) {
        if (!entry.is_regular_file()) continue;
        ++files;
        EXPECT_GT(entry.file_size(), 0u) << entry.path();
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
    }
    EXPECT_GT(files, 0u);
    EXPECT_FALSE(fs::exists(out / "run.json"));  // not a finished run, and nothing claims it is
}

TEST(DamagedRun, TruncatedRawlogFailsUnlessAllowedAndThenSaysSo) {
    test::TempDir dir;
    const fs::path rawlog = dir / "seq.rawlog.gz";
    {
        auto reader = OpenDataset(test::TinySimDataset());
        auto writer = CreateRawlogWriter(rawlog);
        for (int i = 0; i < 80; ++i) writer->Write(*reader->Next());
        writer->Finish();
    }
    std::string bytes = test::ReadFile(rawlog);
    bytes.resize(bytes.size() * 3 / 4);
    std::ofstream(rawlog, std::ios::binary) << bytes;
    const std::string run = "run " + Quote(rawlog.string()) + " --quiet --set output.write_report=false --out ";
    const auto refused = RunCli(run + Quote((dir / "a").string()));
    EXPECT_EQ(refused.exit_code, 1);
    EXPECT_NE(refused.output.find("truncated gzip stream"), std::string::npos) << refused.output;
    EXPECT_NE(refused.output.find("scans"), std::string::npos) << refused.output;
    const auto allowed = RunCli(run + Quote((dir / "b").string()) + " --allow-truncated");
    EXPECT_EQ(allowed.exit_code, 0) << allowed.output;
    EXPECT_NE(allowed.output.find("warning: --allow-truncated"), std::string::npos) << allowed.output;
    const std::string info = test::ReadFile(dir / "b" / "run.json");
    EXPECT_NE(info.find("\"truncated\": true"), std::string::npos) << info;
    const RunState state = ReadRunState(RunFolder::Open(dir / "b"));
    EXPECT_GT(state.odometry.size(), 20u);
    EXPECT_LT(state.odometry.size(), 80u);
    EXPECT_FALSE(state.truncated.empty());
}

TEST(DamagedRun, CtrlCDuringTheReportExitsWith130) {
    test::TempDir dir;
    const fs::path out = dir / "run";
    const std::string log = (dir / "log.txt").string();
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
        freopen(log.c_str(), "w", stderr);
        execl(REVISIT_CLI, REVISIT_CLI, "run", test::TinySimDataset().c_str(), "--to", "300", "--quiet", "--out",
              out.c_str(), static_cast<char*>(nullptr));
        _exit(127);
    }
    // run.json is written (renamed into place) when the chain ends: then only evaluation and the report run.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(out / "run.json") && std::chrono::steady_clock::now() < deadline) usleep(5000);
    kill(pid, SIGINT);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130) << test::ReadFile(log);
    EXPECT_NE(test::ReadFile(log).find("the report was skipped"), std::string::npos) << test::ReadFile(log);
    EXPECT_TRUE(ReadRunState(RunFolder::Open(out)).complete);  // the chain itself finished
}

}  // namespace
}  // namespace revisit
