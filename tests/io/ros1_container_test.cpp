/// Damaged ROS 1 bags: bags written by rosbag, then one length or offset changed as a damaged copy
/// would have it. Each must give a DatasetError naming the file and the byte offset, never reach
/// rosbag_storage (which reads wherever an index entry points: the fuzzer's crash).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "read_all.hpp"
#include "core/error.hpp"
#include "test_data.hpp"

#ifdef REVISIT_HAVE_ROSBAG
#include <rosbag/bag.h>

#include "ros1_cloud.hpp"
#endif

namespace revisit {
namespace {

#ifdef REVISIT_HAVE_ROSBAG
/// Three clouds on one topic, in one chunk of the given compression.
std::string WriteBag(const std::filesystem::path& file, rosbag::CompressionType compression) {
    {
        rosbag::Bag bag(file.string(), rosbag::bagmode::Write);
        bag.setCompression(compression);
        for (int i = 0; i < 3; ++i) {
            const auto cloud = test::Ros1Cloud(ros::Time(100 + i, 0), "velodyne", {"x", "y", "z"}, {float(i), 1, 2});
            bag.write("/velodyne_points", cloud.header.stamp, cloud);
        }
    }
    std::ifstream in(file, std::ios::binary);
    std::stringstream bytes;
    bytes << in.rdbuf();
    return bytes.str();
}

struct Record {
    std::size_t at = 0, data_at = 0;  ///< [bytes] where the record and its data start
    std::uint32_t data_len = 0;
    int op = -1;
};

/// The bag's top-level records, as the format's page describes them (the test's own reading).
std::vector<Record> Records(const std::string& bytes) {
    std::vector<Record> records;
    for (std::size_t at = 13; at + 8 <= bytes.size();) {
        std::uint32_t header_len = 0;
        std::memcpy(&header_len, bytes.data() + at, 4);
        Record r{at, at + 8 + header_len};
        std::memcpy(&r.data_len, bytes.data() + at + 4 + header_len, 4);
        const std::size_t op = bytes.find(std::string("op=", 3), at + 4);
        if (op < at + 4 + header_len) r.op = bytes[op + 3];
        records.push_back(r);
        at = r.data_at + r.data_len;
    }
    return records;
}

const Record& First(const std::vector<Record>& records, int op) {
    for (const Record& r : records) {
        if (r.op == op) return r;
    }
    throw std::runtime_error("no record of op " + std::to_string(op));
}

std::string ErrorOf(const std::filesystem::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary) << bytes;
    try {
        test::ReadAllScans(file);
    } catch (const DatasetError& e) {
        return e.what();
    }
    return "no error";
}

TEST(Ros1Container, EveryCompressionReadsAsWritten) {
    test::TempDir dir;
    for (const auto compression : {rosbag::compression::Uncompressed, rosbag::compression::BZ2, rosbag::compression::LZ4}) {
        const auto file = dir / ("ok" + std::to_string(int(compression)) + ".bag");
        WriteBag(file, compression);
        const auto scans = test::ReadAllScans(file);
        ASSERT_EQ(scans.size(), 3u);
        EXPECT_EQ(scans[2].points[0], Eigen::Vector3f(2, 1, 2));
    }
}

TEST(Ros1Container, AnIndexEntryPointingInsideAMessageIsDamage) {
    // What the fuzzer found: rosbag read a header length wherever the offset pointed and crashed.
    test::TempDir dir;
    for (const auto compression : {rosbag::compression::Uncompressed, rosbag::compression::BZ2, rosbag::compression::LZ4}) {
        const auto file = dir / ("index" + std::to_string(int(compression)) + ".bag");
        std::string bytes = WriteBag(file, compression);
        const Record index = First(Records(bytes), 4);
        ASSERT_EQ(index.data_len, 36u);  // three entries: sec, nsec, offset
        for (const std::uint32_t offset : {1u, 0x7fffffffu}) {
            std::string damaged = bytes;
            std::memcpy(&damaged[index.data_at + 12 + 8], &offset, 4);  // the second entry's offset
            const std::string error = ErrorOf(file, damaged);
            EXPECT_NE(error.find(file.string()), std::string::npos) << error;
            EXPECT_NE(error.find("at byte offset " + std::to_string(index.at) + ": index entry 1 points at byte " + std::to_string(offset)),
                      std::string::npos)
                << error;
        }
    }
}

TEST(Ros1Container, DamagedChunksLengthsAndIndexPositionsAreNamed) {
    test::TempDir dir;
    const auto file = dir / "x.bag";
    const std::string plain = WriteBag(file, rosbag::compression::Uncompressed);
    const auto records = Records(plain);
    const Record chunk = First(records, 5), info = First(records, 6);
    const auto expect = [&](std::string damaged, const std::string& expected) {
        const std::string error = ErrorOf(file, damaged);
        EXPECT_NE(error.find(expected), std::string::npos) << error;
    };
    // A message record's header length inside the uncompressed chunk made larger than the chunk.
    std::string inner = plain;
    inner[chunk.data_at + 3] = '\x40';
    expect(inner, "damaged ROS 1 bag at byte offset " + std::to_string(chunk.at) + ": in the chunk's uncompressed data at byte 0");
    // The chunk info's position moved by one byte: not a chunk.
    std::string moved = plain;
    const std::size_t pos = moved.find("chunk_pos=", info.at);
    ++moved[pos + 10];
    expect(moved, "at byte offset " + std::to_string(info.at) + ": the chunk info points at byte offset " + std::to_string(chunk.at + 1));
    // An interrupted recording: index_pos still 0.
    std::string unindexed = plain;
    const std::size_t index_pos = unindexed.find("index_pos=");
    std::memset(&unindexed[index_pos + 10], 0, 8);
    expect(unindexed, "has no index (was its recording cut short?)");
    // ... and cut inside its chunk, as a crashed `rosbag record` leaves it: the same advice, not the cut.
    expect(unindexed.substr(0, chunk.data_at + chunk.data_len / 2), "`rosbag reindex` rebuilds it");
    // An encrypted bag (a field rosbag's encryptor plugins add to the bag header; the header's padding
    // shrinks by as much, so every offset stays): refused as such, before its chunks fail to decompress.
    std::string encrypted = plain;
    const std::string field = "encryptor=rosbag/AesCbcEncryptor";
    const Record header = records.front();
    std::uint32_t header_len = 0, padding = 0;
    std::memcpy(&header_len, &encrypted[header.at], 4);
    std::memcpy(&padding, &encrypted[header.at + 4 + header_len], 4);
    const std::uint32_t field_len = std::uint32_t(field.size()), grown = header_len + 4 + field_len, shrunk = padding - 4 - field_len;
    std::string with_field(reinterpret_cast<const char*>(&field_len), 4);
    with_field += field;
    encrypted.replace(header.at + 4 + header_len, 4 + 4 + field.size(), with_field + std::string(reinterpret_cast<const char*>(&shrunk), 4));
    std::memcpy(&encrypted[header.at], &grown, 4);
    ASSERT_EQ(encrypted.size(), plain.size());
    expect(encrypted, "encrypted ROS 1 bags are not read (encryptor rosbag/AesCbcEncryptor)");
    // A bz2 chunk whose compressed bytes are damaged: bzip2's CRC, not rosbag's decoder, finds it.
    const std::string bz2 = WriteBag(file, rosbag::compression::BZ2);
    const Record bz2_chunk = First(Records(bz2), 5);
    std::string flipped = bz2;
    flipped[bz2_chunk.data_at + bz2_chunk.data_len / 2] ^= 0x55;
    expect(flipped, "damaged ROS 1 bag at byte offset " + std::to_string(bz2_chunk.at) + ": chunk: bz2");
}
#endif

}  // namespace
}  // namespace revisit
