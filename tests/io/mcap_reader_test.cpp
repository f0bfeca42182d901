/// MCAP specifics: recordings cut short, lz4 chunks, damaged files, topic ambiguity.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "read_all.hpp"
#include "core/error.hpp"
#include "io/reader.hpp"
#include "mcap_test_writer.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {

std::filesystem::path Write(const std::filesystem::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    return file;
}

std::string ErrorOf(const std::filesystem::path& path, const ReaderOptions& options = {}) {
    try {
        test::ReadAllScans(path, options);
    } catch (const DatasetError& e) {
        return e.what();
    }
    return "no error";
}

std::string BinPath(std::size_t i) {
    char name[16];
    std::snprintf(name, sizeof name, "%06zu.bin", i);
    return test::SharedData("livox_handheld_walk/velodyne/" + std::string(name)).string();
}

/// Cut copies of the uncompressed shared MCAP: where each cloud's message ends is found independently
/// of the reader, from its .bin bytes (a PointCloud2's CDR ends with the data and one is_dense byte).
TEST(McapReader, CutRecordingReadsEveryCompleteMessageBeforeTheCut) {
    const auto source = test::SharedData("bags/livox_walk_uncompressed.mcap");
    REVISIT_REQUIRE_DATA(source);
    const std::string file = test::ReadFile(source);
    std::vector<std::size_t> cloud_end;
    std::vector<std::string> clouds;
    for (std::size_t i = 0, from = 0; i < 266; ++i) {
        clouds.push_back(test::ReadFile(BinPath(i)));
        const std::size_t at = file.find(clouds.back(), from);
        ASSERT_NE(at, std::string::npos) << "cloud " << i;
        cloud_end.push_back(at + clouds.back().size() + 1);
        from = cloud_end.back();
    }
    // The footer says where the summary starts (the data section, with DataEnd, ends there).
    std::uint64_t summary_start = 0;
    std::memcpy(&summary_start, file.data() + file.size() - 8 - 20, 8);
    ASSERT_GT(summary_start, cloud_end.back());
    const std::vector<std::size_t> cuts = {cloud_end[100] - 50,  // inside cloud 100's data
                                           cloud_end[150] + 10,  // just after cloud 150, mid-chunk
                                           cloud_end[30] - 1,    // its last byte missing
                                           std::size_t(summary_start) - 13,  // before DataEnd
                                           std::size_t(summary_start),       // before the summary
                                           file.size() - 1};                 // the closing magic cut
    test::TempDir dir;
    for (const std::size_t cut : cuts) {
        const auto copy = Write(dir / "cut.mcap", file.substr(0, cut));
        std::size_t expected = 0;
        while (expected < 266 && cloud_end[expected] <= cut) ++expected;
        const std::string strict = ErrorOf(copy);
        EXPECT_NE(strict.find("cut short"), std::string::npos) << strict;
        EXPECT_NE(strict.find("--allow-truncated"), std::string::npos) << strict;
        ReaderOptions options;
        options.allow_truncated = true;
        auto reader = OpenDataset(copy, options);
        EXPECT_EQ(reader->Info().num_scans, expected) << "cut at " << cut;
        std::size_t n = 0;
        while (auto scan = reader->Next()) {
            ASSERT_LT(n, expected) << "cut at " << cut;
            ASSERT_EQ(scan->points.size() * 16, clouds[n].size());
            EXPECT_EQ(std::memcmp(scan->points.data(), clouds[n].data(), 12), 0);
            ++n;
        }
        EXPECT_EQ(n, expected) << "cut at " << cut;
        EXPECT_NE(reader->Info().truncated.find("cut short"), std::string::npos) << reader->Info().truncated;
    }
}

TEST(McapReader, CutZstdRecordingReadsAPrefix) {
    const auto source = test::SharedData("bags/livox_walk.mcap");
    REVISIT_REQUIRE_DATA(source);
    const std::string file = test::ReadFile(source);
    test::TempDir dir;
    const auto copy = Write(dir / "cut.mcap", file.substr(0, file.size() / 2));
    EXPECT_NE(ErrorOf(copy).find("cut short"), std::string::npos);
    ReaderOptions options;
    options.allow_truncated = true;
    const auto scans = test::ReadAllScans(copy, options);
    // Half the file: about half the scans, the last ones from the cut chunk's decoded part.
    EXPECT_GT(scans.size(), 100u);
    EXPECT_LT(scans.size(), 170u);
    for (std::size_t i = 0; i < scans.size(); ++i) {
        const std::string cloud = test::ReadFile(BinPath(i));
        ASSERT_EQ(scans[i].points.size() * 16, cloud.size()) << i;
        EXPECT_EQ(std::memcmp(&scans[i].points.back(), cloud.data() + cloud.size() - 16, 12), 0) << i;
    }
}

std::string TwoClouds(const std::string& compression) {
    using namespace test;
    const std::string inner = Schema(1, "sensor_msgs/msg/PointCloud2") + Channel(0, 1, "/cloud") +
                              Message(0, 10, CdrCloud(1, 5, {1, 2, 3, 4, 5, 6})) +
                              Message(0, 20, CdrCloud(2, 7, {7, 8, 9}));
    return Mcap(Chunk(inner, compression));
}

TEST(McapReader, Lz4ChunksReadLikeUncompressedOnes) {
    test::TempDir dir;
    const auto plain = test::ReadAllScans(Write(dir / "plain.mcap", TwoClouds("")));
    const auto lz4 = test::ReadAllScans(Write(dir / "lz4.mcap", TwoClouds("lz4")));
    ASSERT_EQ(plain.size(), 2u);
    ASSERT_EQ(lz4.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(lz4[i].points, plain[i].points);
        EXPECT_EQ(lz4[i].stamp_ns, plain[i].stamp_ns);
    }
    EXPECT_EQ(plain[0].points, (std::vector<Eigen::Vector3f>{{1, 2, 3}, {4, 5, 6}}));
    EXPECT_EQ(plain[1].stamp_ns, 2'000'000'007);
    EXPECT_FALSE(plain[0].T_world_sensor);
    EXPECT_FALSE(plain[0].T_odom_sensor);
}

TEST(McapReader, SeveralCloudTopicsAskForTopic) {
    using namespace test;
    test::TempDir dir;
    const auto file = Write(dir / "two.mcap", Mcap(Schema(1, "sensor_msgs/msg/PointCloud2") + Channel(0, 1, "/front") +
                                                   Channel(1, 1, "/rear") + Message(0, 1, CdrCloud(0, 1, {1, 1, 1})) +
                                                   Message(1, 2, CdrCloud(0, 2, {2, 2, 2}))));
    const std::string error = ErrorOf(file);
    EXPECT_NE(error.find("/front"), std::string::npos) << error;
    EXPECT_NE(error.find("/rear"), std::string::npos) << error;
    EXPECT_NE(error.find("--topic"), std::string::npos) << error;
    ReaderOptions options;
    options.points_topic = "/rear";
    const auto scans = test::ReadAllScans(file, options);
    ASSERT_EQ(scans.size(), 1u);
    EXPECT_EQ(scans[0].points[0], Eigen::Vector3f(2, 2, 2));
}

TEST(McapReader, DamagedFilesNameTheFileAndTheByteOffset) {
    using namespace test;
    test::TempDir dir;
    const std::string good = TwoClouds("");
    const auto expect_error = [&](const std::string& name, const std::string& bytes, const std::string& expected) {
        const auto file = Write(dir / name, bytes);
        const std::string error = ErrorOf(file);
        EXPECT_NE(error.find(file.string()), std::string::npos) << error;
        EXPECT_NE(error.find(expected), std::string::npos) << name << ": " << error;
        ReaderOptions lenient;
        lenient.allow_truncated = true;
        try {
            test::ReadAllScans(file, lenient);  // either an error or a note, never a crash
        } catch (const DatasetError&) {
        }
    };
    std::string bad_magic = good;
    bad_magic[1] = 'X';
    expect_error("magic.mcap", bad_magic, "bad magic at byte 0");
    // The chunk's record length (after the 8-byte magic and the Header record) made huge.
    const std::size_t chunk = kMcapMagic.size() + Record(1, Bytes().Str("ros2").Str("revisit test").data).size();
    std::string long_record = good;
    long_record[chunk + 6] = '\x7f';
    expect_error("length.mcap", long_record, "at byte " + std::to_string(chunk));
    const std::string inner = Schema(1, "sensor_msgs/msg/PointCloud2") + Channel(0, 1, "/cloud") + Message(0, 10, CdrCloud(1, 5, {1, 2, 3}));
    expect_error("absurd.mcap", Mcap(Chunk(inner, "lz4", 1ull << 40)),
                 "damaged MCAP at byte offset " + std::to_string(chunk) + ": chunk declares an uncompressed size of 1099511627776");
    expect_error("size.mcap", Mcap(Chunk(inner, "lz4", 1000)), "byte offset " + std::to_string(chunk));
    expect_error("codec.mcap", Mcap(Chunk(inner, "brotli")), "compression 'brotli' is not one of MCAP's");
    // The frame_id's CDR length made larger than the message.
    std::string cloud = CdrCloud(1, 5, {1, 2, 3});
    cloud[12] = '\x40';
    expect_error("cdr.mcap", Mcap(Chunk(Schema(1, "sensor_msgs/msg/PointCloud2") + Channel(0, 1, "/cloud") + Message(0, 10, cloud), "")),
                 "topic /cloud message 0 (chunk at byte offset " + std::to_string(chunk));
    expect_error("channel.mcap", Mcap(Message(3, 1, cloud)), "message on channel 3, not declared before it");
}

}  // namespace
}  // namespace revisit
