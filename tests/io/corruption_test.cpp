/// Randomized corruption of valid files for every reader: a read either succeeds or throws
/// DatasetError; nothing else (other exceptions, crashes) is acceptable. The same inputs run under
/// ASan/UBSan with `cmake -DREVISIT_SANITIZE=ON`, and libFuzzer explores further (`make fuzz`).
#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <random>

#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "io/writer.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

/// Flips, truncates, duplicates or zeroes random bytes of `original` and runs `read` on the result.
void CorruptAndRead(const std::string& original, const std::filesystem::path& file,
                    const std::function<void(const std::filesystem::path&)>& read, int rounds, unsigned seed) {
    std::mt19937 rng(seed);
    for (int round = 0; round < rounds; ++round) {
        std::string bytes = original;
        std::uniform_int_distribution<std::size_t> position(0, bytes.size() - 1);
        switch (round % 4) {
            case 0:
                for (int k = 0; k < 1 + round % 7; ++k) bytes[position(rng)] = static_cast<char>(rng());
                break;
            case 1: bytes.resize(position(rng)); break;
            case 2: bytes.insert(position(rng), bytes.substr(position(rng) / 2, 64)); break;
            default: std::fill_n(bytes.begin() + static_cast<long>(position(rng) / 2), 16, '\0'); break;
        }
        std::ofstream(file, std::ios::binary) << bytes;
        try {
            read(file);
        } catch (const DatasetError&) {
        } catch (const std::exception& e) {
            ADD_FAILURE() << file.filename() << " round " << round << ": unexpected exception " << e.what();
        }
    }
}

TEST(Corruption, PointCloudFilesAndPoses) {
    test::TempDir dir;
    std::vector<Eigen::Vector3f> points;
    for (int i = 0; i < 50; ++i) points.emplace_back(i * 0.1f, -i * 0.2f, 1.f);
    SavePly(dir / "seed.ply", points, std::vector<float>(points.size(), 0.5f));
    std::ofstream(dir / "seed.pcd") << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
                                       "COUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n1 2 3 4\n5 6 7 8\n9 1 2 3\n";
    Scan scan;
    scan.points = points;
    SaveKittiBin(dir / "seed.bin", scan);
    WriteKittiPoses(dir / "seed.txt", Poses(5, Eigen::Isometry3d::Identity()));
    CorruptAndRead(test::ReadFile(dir / "seed.ply"), dir / "x.ply", [](const auto& f) { LoadPly(f); }, 300, 1);
    CorruptAndRead(test::ReadFile(dir / "seed.pcd"), dir / "x.pcd", [](const auto& f) { LoadPcd(f); }, 300, 2);
    CorruptAndRead(test::ReadFile(dir / "seed.bin"), dir / "x.bin", [](const auto& f) { LoadKittiBin(f); }, 100, 3);
    CorruptAndRead(test::ReadFile(dir / "seed.txt"), dir / "x.txt", [](const auto& f) { ReadPoses(f); }, 300, 4);
}

TEST(Corruption, Rawlogs) {
    test::TempDir dir;
    {
        auto writer = CreateRawlogWriter(dir / "seed.rawlog");
        for (int s = 0; s < 4; ++s) {
            Scan scan;
            for (int i = 0; i < 30; ++i) scan.points.emplace_back(i * 0.3f, static_cast<float>(s), 0.5f);
            scan.T_world_sensor = Eigen::Isometry3d::Identity();
            writer->Write(scan);
        }
        writer->Finish();
    }
    const auto read_all = [](const std::filesystem::path& f) {
        auto reader = OpenDataset(f);
        while (reader->Next()) {
        }
    };
    CorruptAndRead(test::ReadFile(dir / "seed.rawlog"), dir / "x.rawlog", read_all, 200, 5);
}

}  // namespace
}  // namespace revisit
