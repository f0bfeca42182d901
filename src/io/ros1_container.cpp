#include "io/ros1_container.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "io/chunk_codec.hpp"
#include "io/ros_wire.hpp"

namespace revisit {
namespace {

constexpr std::uint64_t kMaxChunkBytes = 1ull << 30;  ///< [bytes] a chunk declaring more is damaged
constexpr char kVersionLine[] = "#ROSBAG V2.0\n";
constexpr std::uint64_t kFirstRecord = sizeof kVersionLine - 1;  ///< [bytes] where the bag header starts

enum Op : int { kMessage = 2, kBagHeader = 3, kIndexData = 4, kChunk = 5, kChunkInfo = 6, kConnection = 7 };

/// A record header's fields by name ("name=value", each after its uint32 length); later names win, as in rosbag.
using Fields = std::map<std::string, std::string>;

/// Calls visit(name, value) for each of `size` header bytes' fields. Returns what is wrong, or an empty string.
template <typename Visit>
std::string ForEachField(const std::uint8_t* data, std::size_t size, Visit&& visit) {
    for (std::size_t p = 0; p < size;) {
        if (size - p < 4) return "its header ends inside a field length";
        std::uint32_t length = 0;
        std::memcpy(&length, data + p, 4);
        p += 4;
        if (length > size - p) return "a header field of " + std::to_string(length) + " bytes runs past its header";
        const std::string_view field(reinterpret_cast<const char*>(data + p), length);
        const std::size_t equals = field.find('=');
        if (equals == std::string_view::npos) return "a header field has no '='";
        visit(field.substr(0, equals), field.substr(equals + 1));
        p += length;
    }
    return {};
}

std::string SplitFields(const std::uint8_t* data, std::size_t size, Fields& fields) {
    fields.clear();
    return ForEachField(data, size, [&](std::string_view name, std::string_view value) { fields[std::string(name)] = std::string(value); });
}

/// A field's value of exactly sizeof(T) bytes, as rosbag reads numbers; nullopt when missing or of another size.
template <typename T>
std::optional<T> Number(const Fields& fields, const char* name) {
    const auto it = fields.find(name);
    if (it == fields.end() || it->second.size() != sizeof(T)) return std::nullopt;
    T value;
    std::memcpy(&value, it->second.data(), sizeof(T));
    return value;
}

int OpOf(const Fields& fields) {
    const auto op = Number<std::uint8_t>(fields, "op");
    return op ? int(*op) : -1;
}

/// What the index section's check needs of each top-level record.
struct TopRecord {
    std::uint64_t at = 0;         ///< [bytes] the record's offset in the file
    int op = -1;
    std::uint32_t conn = 0;       ///< connections and index data: the connection id
    std::uint64_t chunk_pos = 0;  ///< chunk infos: the chunk they describe
};

class ContainerCheck {
  public:
    explicit ContainerCheck(const std::filesystem::path& file) : file_(file) {}

    void Run() {
        f_.reset(std::fopen(file_.c_str(), "rb"));
        if (!f_) throw DatasetError(file_, "cannot open");
        std::fseek(f_.get(), 0, SEEK_END);
        size_ = std::uint64_t(ftello(f_.get()));
        char version[kFirstRecord] = {};
        if (size_ >= kFirstRecord) Read(version, kFirstRecord, 0);
        if (std::memcmp(version, kVersionLine, kFirstRecord) != 0) {
            throw DatasetError(file_, "not a ROS 1 bag of format 2.0 (no '#ROSBAG V2.0' line at byte 0)");
        }
        Fields fields;
        for (std::uint64_t at = kFirstRecord; at < size_;) {
            std::uint32_t header_len = 0, data_len = 0;
            if (size_ - at < 4) Fail(at, "the record ends inside its header length");
            Read(&header_len, 4, at);
            if (header_len > size_ - at - 4) Fail(at, "the record header of " + std::to_string(header_len) + " bytes runs past the end of the file");
            header_.resize(header_len);
            Read(header_.data(), header_len, at + 4);
            if (size_ - at - 4 - header_len < 4) Fail(at, "the record ends inside its data length");
            Read(&data_len, 4, at + 4 + header_len);
            const std::uint64_t data_at = at + 8 + header_len;
            if (data_len > size_ - data_at) Fail(at, "the record data of " + std::to_string(data_len) + " bytes runs past the end of the file");
            if (const std::string wrong = SplitFields(header_.data(), header_len, fields); !wrong.empty()) Fail(at, "record: " + wrong);
            TopRecord record{at, OpOf(fields)};
            if (record.op == kBagHeader && at == kFirstRecord) {
                bag_header_ = fields;
                // Said before the walk meets what they cause: a recording cut short ends inside a chunk, and an
                // encrypted bag's chunks do not decompress.
                if (Number<std::uint64_t>(fields, "index_pos") == std::uint64_t(0)) Unindexed();
                if (fields.count("encryptor")) {
                    throw DatasetError(file_, "encrypted ROS 1 bags are not read (encryptor " + fields.at("encryptor") + ")");
                }
            } else if (record.op == kChunk) {
                CheckChunk(at, fields, data_at, data_len);
            } else if (record.op == kIndexData) {
                record.conn = CheckIndexData(at, fields, data_at, data_len);
            } else if (record.op == kConnection) {
                record.conn = Required<std::uint32_t>(at, fields, "conn");
                data_.resize(data_len);
                Read(data_.data(), data_len, data_at);
                // Its data is the connection's own header: rosbag parses it like one.
                if (const std::string wrong = ForEachField(data_.data(), data_len, [](std::string_view, std::string_view) {});
                    !wrong.empty()) {
                    Fail(at, "connection record: " + wrong);
                }
            } else if (record.op == kChunkInfo) {
                record.chunk_pos = CheckChunkInfo(at, fields, data_len);
            }
            records_.push_back(record);
            at = data_at + data_len;
        }
        CheckIndexSection();
    }

  private:
    [[noreturn]] void Fail(std::uint64_t at, const std::string& what) const {
        throw DatasetError(file_, "damaged ROS 1 bag at byte offset " + std::to_string(at) + ": " + what);
    }

    [[noreturn]] void Unindexed() const {
        throw DatasetError(file_, "the ROS 1 bag has no index (was its recording cut short?); `rosbag reindex` rebuilds it");
    }

    void Read(void* out, std::size_t size, std::uint64_t at) {
        if (fseeko(f_.get(), off_t(at), SEEK_SET) != 0 || std::fread(out, 1, size, f_.get()) != size) {
            throw DatasetError(file_, "cannot read " + std::to_string(size) + " bytes at byte offset " + std::to_string(at));
        }
    }

    template <typename T>
    T Required(std::uint64_t at, const Fields& fields, const char* name) const {
        const auto value = Number<T>(fields, name);
        if (!value) Fail(at, std::string("the record has no ") + std::to_string(sizeof(T)) + "-byte '" + name + "' field");
        return *value;
    }

    /// Decompresses the chunk to exactly its declared size and keeps the offsets of its message records,
    /// each whole inside the chunk: the index entries after it may point only at those.
    void CheckChunk(std::uint64_t at, const Fields& fields, std::uint64_t data_at, std::uint32_t data_len) {
        const auto compression = fields.find("compression");
        if (compression == fields.end()) Fail(at, "the chunk has no 'compression' field");
        const std::uint32_t size = Required<std::uint32_t>(at, fields, "size");
        if (size > kMaxChunkBytes) Fail(at, "the chunk declares " + std::to_string(size) + " uncompressed bytes");
        data_.resize(data_len);
        Read(data_.data(), data_len, data_at);
        const std::uint8_t* records = data_.data();
        if (compression->second == "none") {
            if (size != data_len) Fail(at, "an uncompressed chunk of " + std::to_string(data_len) + " bytes declares " + std::to_string(size));
        } else if (compression->second == "bz2" || compression->second == "lz4") {
            try {
                Decompress(compression->second, data_.data(), data_len, size, false, chunk_);
            } catch (const WireError& e) {
                Fail(at, std::string("chunk: ") + e.what());
            }
            records = chunk_.data();
        } else {
            Fail(at, "chunk compression '" + compression->second + "' is not one of ROS 1's (none, bz2, lz4)");
        }
        messages_.clear();
        for (std::uint64_t p = 0; p < size;) {
            const auto fail = [&](const std::string& what) {
                Fail(at, "in the chunk's uncompressed data at byte " + std::to_string(p) + ", " + what);
            };
            if (size - p < 8) fail("a record ends inside its lengths");
            std::uint32_t header_len = 0, inner_len = 0;
            std::memcpy(&header_len, records + p, 4);
            if (header_len > size - p - 8) fail("a record header of " + std::to_string(header_len) + " bytes runs past the chunk");
            std::memcpy(&inner_len, records + p + 4 + header_len, 4);
            if (inner_len > size - p - 8 - header_len) fail("a record's data of " + std::to_string(inner_len) + " bytes runs past the chunk");
            // Chunks hold many small records: their fields are checked without a map.
            int op = -1;
            const std::string wrong = ForEachField(records + p + 4, header_len, [&](std::string_view name, std::string_view value) {
                if (name == "op") op = value.size() == 1 ? int(std::uint8_t(value[0])) : -1;
            });
            if (!wrong.empty()) fail(wrong);
            if (op == kMessage) messages_.push_back(std::uint32_t(p));
            p += 8 + std::uint64_t(header_len) + inner_len;
        }
        chunk_at_ = at;
    }

    /// An index record's entries (time, offset) must each point at a message record of the chunk before it.
    std::uint32_t CheckIndexData(std::uint64_t at, const Fields& fields, std::uint64_t data_at, std::uint32_t data_len) {
        if (!chunk_at_) Fail(at, "an index record comes before any chunk");
        if (Required<std::uint32_t>(at, fields, "ver") != 1) Fail(at, "the index record's version is not 1");
        const std::uint32_t conn = Required<std::uint32_t>(at, fields, "conn");
        const std::uint32_t count = Required<std::uint32_t>(at, fields, "count");
        if (std::uint64_t(count) * 12 != data_len) {
            Fail(at, "the index record of " + std::to_string(count) + " entries has " + std::to_string(data_len) + " bytes of data");
        }
        data_.resize(data_len);
        Read(data_.data(), data_len, data_at);
        for (std::uint32_t i = 0; i < count; ++i) {
            std::uint32_t offset = 0;
            std::memcpy(&offset, data_.data() + 12 * std::size_t(i) + 8, 4);
            if (!std::binary_search(messages_.begin(), messages_.end(), offset)) {
                Fail(at, "index entry " + std::to_string(i) + " points at byte " + std::to_string(offset) +
                             " of the chunk at byte offset " + std::to_string(*chunk_at_) + ", where no message record starts");
            }
        }
        return conn;
    }

    std::uint64_t CheckChunkInfo(std::uint64_t at, const Fields& fields, std::uint32_t data_len) const {
        if (Required<std::uint32_t>(at, fields, "ver") != 1) Fail(at, "the chunk info's version is not 1");
        const std::uint32_t count = Required<std::uint32_t>(at, fields, "count");
        if (std::uint64_t(count) * 8 != data_len) {
            Fail(at, "the chunk info of " + std::to_string(count) + " connections has " + std::to_string(data_len) + " bytes of data");
        }
        return Required<std::uint64_t>(at, fields, "chunk_pos");
    }

    /// rosbag seeks to the bag header's index position, reads that many connection records, then that
    /// many chunk infos, and seeks to each chunk: each position must be a record of the right kind.
    void CheckIndexSection() const {
        if (records_.empty() || records_.front().op != kBagHeader) Fail(kFirstRecord, "the first record is not a bag header");
        const std::uint64_t index_pos = Required<std::uint64_t>(kFirstRecord, bag_header_, "index_pos");
        const std::uint32_t conn_count = Required<std::uint32_t>(kFirstRecord, bag_header_, "conn_count");
        const std::uint32_t chunk_count = Required<std::uint32_t>(kFirstRecord, bag_header_, "chunk_count");
        const auto find = [&](std::uint64_t at) {
            return std::lower_bound(records_.begin(), records_.end(), at, [](const TopRecord& r, std::uint64_t v) { return r.at < v; });
        };
        auto it = find(index_pos);
        if (it == records_.end() || it->at != index_pos) Fail(kFirstRecord, "the index position " + std::to_string(index_pos) + " is not a record");
        std::set<std::uint32_t> connections;
        for (std::uint32_t i = 0; i < conn_count; ++i, ++it) {
            if (it == records_.end() || it->op != kConnection) Fail(kFirstRecord, "the index section has fewer than its " + std::to_string(conn_count) + " connection records");
            connections.insert(it->conn);
        }
        for (std::uint32_t i = 0; i < chunk_count; ++i, ++it) {
            if (it == records_.end() || it->op != kChunkInfo) Fail(kFirstRecord, "the index section has fewer than its " + std::to_string(chunk_count) + " chunk infos");
            const auto chunk = find(it->chunk_pos);
            if (chunk == records_.end() || chunk->at != it->chunk_pos || chunk->op != kChunk) {
                Fail(it->at, "the chunk info points at byte offset " + std::to_string(it->chunk_pos) + ", where no chunk starts");
            }
        }
        for (const TopRecord& record : records_) {
            if (record.op == kIndexData && !connections.count(record.conn)) {
                Fail(record.at, "the index record names connection " + std::to_string(record.conn) + ", which the bag does not declare");
            }
        }
    }

    std::filesystem::path file_;
    std::unique_ptr<std::FILE, decltype(&std::fclose)> f_{nullptr, &std::fclose};
    std::uint64_t size_ = 0;                   ///< [bytes]
    std::vector<std::uint8_t> header_, data_;  ///< the current record's header and data
    std::vector<std::uint8_t> chunk_;          ///< the current chunk, decompressed
    std::vector<std::uint32_t> messages_;      ///< [bytes] where the current chunk's message records start, ascending
    std::optional<std::uint64_t> chunk_at_;    ///< [bytes] where the current chunk starts in the file
    Fields bag_header_;
    std::vector<TopRecord> records_;  ///< every top-level record, by offset
};

}  // namespace

void CheckRos1Container(const std::filesystem::path& file) { ContainerCheck(file).Run(); }

}  // namespace revisit
