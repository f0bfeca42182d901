/// Issue 17: damaged input never passes as good. Each case is a small file crafted here; each must
/// give a DatasetError naming the file (and where reading stopped), at once, without a crash.
#include <gtest/gtest.h>

#include <zlib.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>

#include "cli.hpp"
#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/reader.hpp"
#include "io/trajectory_io.hpp"
#include "io/writer.hpp"
#include "test_data.hpp"

namespace revisit {
namespace {
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

void WriteBytes(const fs::path& file, const std::string& bytes) { std::ofstream(file, std::ios::binary) << bytes; }

/// The DatasetError message of `read(file)`; fails the test when it does not throw one.
template <typename Read>
std::string ErrorOf(const fs::path& file, Read read) {
    try {
        read(file);
    } catch (const DatasetError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        return e.what();
    }
    ADD_FAILURE() << file << " was read as good";
    return {};
}

std::size_t ReadAllScans(const fs::path& file, bool allow_truncated = false) {
    ReaderOptions options;
    options.allow_truncated = allow_truncated;
    auto reader = OpenDataset(file, options);
    std::size_t n = 0;
    while (reader->Next()) ++n;
    return n;
}

TEST(DamagedInput, PlyWithAHugeElementBeforeTheVerticesFailsAtOnce) {
    test::TempDir dir;
    const auto file = dir / "face.ply";
    WriteBytes(file, "ply\nformat ascii 1.0\nelement face 1000000000000000000\nproperty list uchar int v\n"
                     "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 3\n");
    const auto start = Clock::now();
    const auto error = ErrorOf(file, [](const fs::path& f) { LoadPly(f); });
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - start).count(), 1.0);
    EXPECT_NE(error.find("1000000000000000000 records"), std::string::npos) << error;
    EXPECT_NE(error.find(":3:"), std::string::npos) << error;  // the header line
}

TEST(DamagedInput, PcdPointCountsAreCheckedAgainstTheFileAndForOverflow) {
    test::TempDir dir;
    const std::string header = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
    WriteBytes(dir / "many.pcd", header + "WIDTH 99999999\nHEIGHT 1\nPOINTS 99999999\nDATA binary\n" + std::string(120, '\0'));
    const auto many = ErrorOf(dir / "many.pcd", [](const fs::path& f) { LoadPcd(f); });
    EXPECT_NE(many.find("declares 99999999 points"), std::string::npos) << many;
    WriteBytes(dir / "wrap.pcd", header + "WIDTH 4294967296\nHEIGHT 4294967296\nDATA ascii\n1 2 3\n");
    const auto wrap = ErrorOf(dir / "wrap.pcd", [](const fs::path& f) { LoadPcd(f); });
    EXPECT_NE(wrap.find("overflows"), std::string::npos) << wrap;
    WriteBytes(dir / "disagree.pcd", header + "WIDTH 3\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n");
    ErrorOf(dir / "disagree.pcd", [](const fs::path& f) { LoadPcd(f); });
}

TEST(DamagedInput, TimesGoingBackwardsAreNamedWithTheirLine) {
    test::TempDir dir;
    WriteBytes(dir / "times.txt", "0.0\n0.1\n0.2\n0.15\n0.3\n");
    const auto error = ErrorOf(dir / "times.txt", [](const fs::path& f) { ReadTimes(f); });
    EXPECT_NE(error.find("times.txt:4: time goes backwards"), std::string::npos) << error;
}

/// A plain and a gzip rawlog of 6 scans, 200 points each.
struct Rawlogs {
    test::TempDir dir;
    fs::path plain = dir / "seq.rawlog";
    fs::path gzip = dir / "seq.rawlog.gz";
    Rawlogs() {
        for (const auto& file : {plain, gzip}) {
            auto writer = CreateRawlogWriter(file);
            for (int s = 0; s < 6; ++s) {
                Scan scan;
                scan.timestamp = 0.1 * s;
                scan.points.emplace_back(1234.5f, 0.f, 0.f);
                for (int i = 1; i < 200; ++i) scan.points.emplace_back(i * 0.05f, static_cast<float>(s), 1.f);
                scan.T_world_sensor = Eigen::Isometry3d::Identity();
                writer->Write(scan);
            }
            writer->Finish();
        }
    }
};

TEST(DamagedInput, TruncatedRawlogsSayWhereReadingStoppedAndHowManyScansWereRead) {
    Rawlogs logs;
    ASSERT_EQ(ReadAllScans(logs.plain), 6u);
    ASSERT_EQ(ReadAllScans(logs.gzip), 6u);
    for (const auto& original : {logs.plain, logs.gzip}) {
        const std::string bytes = test::ReadFile(original);
        for (int k = 1; k < 20; ++k) {
            const auto cut = logs.dir / (original == logs.gzip ? "cut.rawlog.gz" : "cut.rawlog");
            // +7: the scans are all the same size, and a plain rawlog cut exactly between two objects is a
            // valid shorter rawlog (plain rawlogs carry no length or checksum; gzip ones do).
            WriteBytes(cut, bytes.substr(0, bytes.size() * k / 20 + 7));
            const auto error = ErrorOf(cut, [](const fs::path& f) { ReadAllScans(f); });
            if (error.empty()) ADD_FAILURE() << "cut at " << k << "/20 of " << original;
            EXPECT_NE(error.find("reading stopped"), std::string::npos) << error;
            EXPECT_NE(error.find(" scans"), std::string::npos) << error;
            // --allow-truncated keeps what was read before the damage.
            EXPECT_LT(ReadAllScans(cut, true), 6u);
        }
    }
}

TEST(DamagedInput, GzipCrcAndBitFlipsAreErrors) {
    Rawlogs logs;
    std::string bytes = test::ReadFile(logs.gzip);
    std::string crc = bytes;
    crc[crc.size() - 8] ^= 0x01;  // the trailer's CRC-32
    WriteBytes(logs.dir / "crc.rawlog.gz", crc);
    const auto error = ErrorOf(logs.dir / "crc.rawlog.gz", [](const fs::path& f) { ReadAllScans(f); });
    EXPECT_NE(error.find("incorrect data check"), std::string::npos) << error;
    for (std::size_t at = 20; at < bytes.size() - 8; at += bytes.size() / 15) {
        std::string flipped = bytes;
        flipped[at] ^= 0x10;
        WriteBytes(logs.dir / "flip.rawlog.gz", flipped);
        ErrorOf(logs.dir / "flip.rawlog.gz", [](const fs::path& f) { ReadAllScans(f); });
    }
    WriteBytes(logs.dir / "trailing.rawlog.gz", bytes + "garbage");
    ErrorOf(logs.dir / "trailing.rawlog.gz", [](const fs::path& f) { ReadAllScans(f); });
}

TEST(DamagedInput, ALyingSizeFieldIsAnErrorNotAnAllocation) {
    Rawlogs logs;
    std::string bytes = test::ReadFile(logs.plain);
    // The point cloud stores its point count (uint32) right before the x coordinates; the first x is 1234.5.
    std::uint32_t count = 200;
    float first_x = 1234.5f;
    std::string pattern(8, '\0');
    std::memcpy(pattern.data(), &count, 4);
    std::memcpy(pattern.data() + 4, &first_x, 4);
    const auto at = bytes.find(pattern);
    ASSERT_NE(at, std::string::npos) << "point count not found in the serialized cloud";
    const std::uint32_t lie = 0x7fffffff;  // 8 GiB per coordinate array
    std::memcpy(bytes.data() + at, &lie, 4);
    WriteBytes(logs.dir / "lie.rawlog", bytes);
    const auto error = ErrorOf(logs.dir / "lie.rawlog", [](const fs::path& f) { ReadAllScans(f); });
    EXPECT_NE(error.find("reading stopped"), std::string::npos) << error;
}

TEST(DamagedInput, ConvertRefusesToWriteOverItsInput) {
    Rawlogs logs;
    const auto before = test::ReadFile(logs.plain);
    fs::create_symlink(logs.plain, logs.dir / "link.rawlog");
    for (const auto& output : {logs.plain, logs.dir / "link.rawlog"}) {
        const auto result = test::RunCli("convert " + test::Quote(logs.plain.string()) + " " +
                                         test::Quote(output.string()) + " --force");
        EXPECT_EQ(result.exit_code, 1) << result.output;
        EXPECT_NE(result.output.find("would destroy the input"), std::string::npos) << result.output;
    }
    EXPECT_EQ(test::ReadFile(logs.plain), before);
    // A conversion that fails half-way leaves no output under the final name.
    std::string bytes = before;
    bytes.resize(bytes.size() * 2 / 3 + 5);  // not at an object boundary (see above)
    WriteBytes(logs.dir / "cut.rawlog", bytes);
    const auto failed = test::RunCli("convert " + test::Quote((logs.dir / "cut.rawlog").string()) + " " +
                                     test::Quote((logs.dir / "out.rawlog").string()));
    EXPECT_EQ(failed.exit_code, 1) << failed.output;
    EXPECT_FALSE(fs::exists(logs.dir / "out.rawlog"));
}

TEST(DamagedInput, FuzzerRawlogWhoseErrorPathOnceTerminated) {
    // Found by fuzz_rawlog: a CObservationOdometry with a lying size, then the end of the file. MRPT
    // builds its exception (with a backtrace) while the allocation budget was spent: that must not
    // throw again (std::terminate); the reader reports a damaged rawlog.
    static const char* const kHex =
        "9f6d7270743a3a6f62733a3a434f62736572766174696f6e4f646f6d6574727902946d7270743a3a706f7365733a3a43506f"
        "7365324401000000000000000000000000000000000000000000000000880800001010101010101010101010101010101010"
        "10101010101010101010101010101010101010101010101010101010101010101010101010101010004f444f4d4554525900"
        "803ed5deb19d01000088a06d7270743a3a6f62733a3a434f62736572766174696f6e526f626f74506f7365019f6d7270743a"
        "3a706f7365733a3a43506f73653344504446476175737369616e01946d7270743a3a706f7365733a3a43506f736533440300"
        "0000000000000000000000000000000000000000000000000000000000f03f00000000000000000000000000000000000000"
        "0000000000000000000000f03f000000000000000000000000000000000000000000000000000000000000f03f8800000000"
        "0000000000000000000000000000a06d7270743a3a6f62733a3a434f62736572766174696f6e526f626f74506f7365019f6d"
        "7270743a3a706f7365733a3a43506f73653344504446476175737369616e01946d7270743a3a706f7365733a3a43506f7365"
        "334403000000000000000000000000000000000000000000000000000000000000f03f000000000000000000000000000000"
        "000000000000000000000000000000f03f000000000000000000000000000000000000000000000000000000000000f03f88"
        "0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
        "0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
        "0000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000000"
        "00000000000000000000000000000000000088080000004f444f4d4554525900803ed5deb19d01946d7270743a3a706f0000"
        "0000000000000000000000000000007300000000";
    std::string bytes;
    for (std::size_t i = 0; kHex[i] && kHex[i + 1]; i += 2) bytes.push_back(static_cast<char>(std::stoi(std::string(kHex + i, 2), nullptr, 16)));
    ASSERT_EQ(bytes.size(), 770u);
    test::TempDir dir;
    WriteBytes(dir / "fuzz.rawlog", bytes);
    const auto error = ErrorOf(dir / "fuzz.rawlog", [](const fs::path& f) { ReadAllScans(f); });
    EXPECT_NE(error.find("reading stopped in object 0"), std::string::npos) << error;
}

}  // namespace
}  // namespace revisit
