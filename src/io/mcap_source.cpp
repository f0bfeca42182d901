/// MCAP files (https://mcap.dev/spec), read front to back through the data section: the summary is
/// not needed, so a recording cut short (no summary, no footer, a record cut in the middle) is read up
/// to its last complete message. Every length is checked against the bytes the file still holds
/// before anything is allocated.
#include <zlib.h>

#include <cstdio>
#include <cstring>
#include <map>

#include "core/error.hpp"
#include "io/bag_source.hpp"
#include "io/chunk_codec.hpp"

namespace revisit {
namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', 0x30, '\r', '\n'};
enum Op : std::uint8_t { kHeader = 1, kFooter = 2, kSchema = 3, kChannel = 4, kMessage = 5, kChunk = 6, kDataEnd = 0x0F };
constexpr std::uint64_t kMaxChunkBytes = 1ull << 30;  ///< [bytes] a chunk declaring more is damaged (writers use ~1 MiB)
constexpr std::size_t kRecordHeader = 9;              ///< opcode + uint64 length
/// [bytes] decompressed chunks the first pass keeps for the second, which then skips decompressing them
/// (the first pass reads the poses, the second the scans): a recording's first 64 MiB.
constexpr std::size_t kKeptChunkBytes = 64u << 20;

class McapSource final : public BagSource {
  public:
    McapSource(const std::filesystem::path& file, const ReaderOptions& options)
        : file_(file), allow_truncated_(options.allow_truncated), f_(std::fopen(file.c_str(), "rb"), &std::fclose) {
        if (!f_) throw DatasetError(file_, "cannot open");
        std::fseek(f_.get(), 0, SEEK_END);
        size_ = std::uint64_t(ftello(f_.get()));
        std::uint8_t magic[8];
        if (!ReadAt(0, magic, 8) || std::memcmp(magic, kMagic, 8) != 0) throw DatasetError(file_, "not an MCAP file (bad magic at byte 0)");
    }

    std::string Format() const override { return "mcap"; }
    const std::vector<BagTopic>& Topics() const override { return topics_; }

    void Start(std::function<bool(std::size_t)> wanted) override {
        wanted_ = std::move(wanted);
        wanted_cache_.assign(topics_.size(), -1);
        counting_ = !counted_;
        in_chunk_ = ended_ = false;
        pos_ = 8;
        std::uint8_t op = 0;
        std::uint64_t length = 0;
        if (!RecordHeaderAt(pos_, op, length) || op != kHeader || length > size_ - pos_ - kRecordHeader) {
            throw DatasetError(file_, "no Header record at byte 8");
        }
        std::vector<std::uint8_t> header(length);
        ReadAt(pos_ + kRecordHeader, header.data(), length);
        WireReader in(header.data(), header.size(), RosWire::kRos1);
        try {
            profile_ = in.String();
        } catch (const WireError& e) {
            throw DatasetError(file_, std::string("damaged Header record at byte 8: ") + e.what());
        }
        pos_ += kRecordHeader + length;
    }

    bool Next(BagMessage& message) override {
        try {
            while (!ended_) {
                if (in_chunk_ ? NextInChunk(message) : NextTopLevel(message)) return true;
            }
        } catch (...) {
            counted_ = counted_ || counting_;  // a pass that stops at damage has counted all it can
            throw;
        }
        counted_ = true;
        return false;
    }

    std::string Where(const BagMessage& message) const override {
        return message.inner != ~0ull ? "chunk at byte offset " + std::to_string(message.position) + ", chunk byte " +
                                            std::to_string(message.inner)
                                      : "byte offset " + std::to_string(message.position);
    }

  private:
    bool ReadAt(std::uint64_t offset, void* out, std::size_t n) {
        if (offset > size_ || n > size_ - offset) return false;
        if (offset != at_ && fseeko(f_.get(), off_t(offset), SEEK_SET) != 0) return false;
        const bool ok = std::fread(out, 1, n, f_.get()) == n;
        at_ = ok ? offset + n : ~0ull;
        return ok;
    }

    bool RecordHeaderAt(std::uint64_t offset, std::uint8_t& op, std::uint64_t& length) {
        std::uint8_t bytes[kRecordHeader];
        if (!ReadAt(offset, bytes, kRecordHeader)) return false;
        op = bytes[0];
        length = 0;
        for (int i = 0; i < 8; ++i) length |= std::uint64_t(bytes[1 + i]) << (8 * i);
        return true;
    }

    [[noreturn]] void Cut(const std::string& what) const {
        throw DatasetError(file_, "the file ends " + what + " (file size " + std::to_string(size_) +
                                      "): the recording was cut short" +
                                      (allow_truncated_ ? "" : "; --allow-truncated reads the messages before the cut"));
    }
    [[noreturn]] void Damaged(std::uint64_t offset, const std::string& what) const {
        throw DatasetError(file_, "damaged MCAP at byte offset " + std::to_string(offset) + ": " + what);
    }

    bool NextTopLevel(BagMessage& message) {
        std::uint8_t op = 0;
        std::uint64_t length = 0;
        if (pos_ == size_) Cut("at byte " + std::to_string(pos_) + " without a DataEnd record");
        if (!RecordHeaderAt(pos_, op, length)) Cut("inside the record header at byte " + std::to_string(pos_));
        const std::uint64_t content = pos_ + kRecordHeader, left = size_ - content;
        if (op == 0) Damaged(pos_, "record with opcode 0");
        if (length > left && !(op == kChunk && allow_truncated_)) {
            Cut("inside a record (opcode " + std::to_string(op) + ") at byte " + std::to_string(pos_) + " that declares " +
                std::to_string(length) + " bytes, " + std::to_string(left) + " left");
        }
        const std::uint64_t record = pos_;
        pos_ = content + std::min(length, left);
        switch (op) {
            case kDataEnd:
            case kFooter: {
                ended_ = true;
                std::uint8_t magic[8];
                if (size_ < 8 || !ReadAt(size_ - 8, magic, 8) || std::memcmp(magic, kMagic, 8) != 0 || size_ < pos_ + 8) {
                    Cut("after the data section at byte " + std::to_string(pos_) + ", before its footer and closing magic");
                }
                return false;
            }
            case kChunk: return LoadChunk(record, content, length, std::min(length, left), message);
            case kSchema:
            case kChannel:
            case kMessage:
                record_.resize(length);
                ReadAt(content, record_.data(), length);
                return Handle(op, record_.data(), length, record, ~0ull, message);
            default: return false;  // message indexes, attachments, metadata, unknown records: skipped
        }
    }

    bool LoadChunk(std::uint64_t record, std::uint64_t content, std::uint64_t length, std::uint64_t available,
                   BagMessage& message) {
        raw_.resize(available);
        ReadAt(content, raw_.data(), available);
        WireReader in(raw_.data(), raw_.size(), RosWire::kRos1);
        std::uint64_t declared = 0, records = 0;
        std::uint32_t crc = 0;
        std::string compression;
        try {
            in.U64(), in.U64();  // message start and end times
            declared = in.U64();
            crc = in.U32();
            compression = in.String();
            records = in.U64();
        } catch (const WireError&) {
            Cut("inside the chunk header at byte " + std::to_string(record));
        }
        const bool cut = available < length;
        const std::size_t header = in.offset();
        if (!cut && records != length - header) {
            Damaged(record, "chunk records length " + std::to_string(records) + " does not match the record's " + std::to_string(length - header));
        }
        if (cut && !allow_truncated_) Cut("inside the chunk at byte " + std::to_string(record));
        if (declared > kMaxChunkBytes) {
            Damaged(record, "chunk declares an uncompressed size of " + std::to_string(declared) + " bytes (more than " +
                                std::to_string(kMaxChunkBytes) + ")");
        }
        if (!compression.empty() && compression != "zstd" && compression != "lz4") {
            Damaged(record, "chunk compression '" + compression + "' is not one of MCAP's (zstd, lz4 or none)");
        }
        const std::size_t have = std::min<std::uint64_t>(records, available - header);
        bool keep = false;
        try {
            if (compression.empty()) {
                if (declared != records) Damaged(record, "uncompressed chunk of " + std::to_string(records) + " bytes declares " + std::to_string(declared));
                chunk_ = raw_.data() + header;
                chunk_size_ = have;
            } else if (const auto kept = kept_.find(record); kept != kept_.end() && !counting_) {
                plain_.swap(kept->second);
                kept_bytes_ -= plain_.size();
                kept_.erase(kept);
                chunk_ = plain_.data();
                chunk_size_ = plain_.size();
            } else {
                chunk_size_ = Decompress(compression, raw_.data() + header, have, declared, cut, plain_);
                chunk_ = plain_.data();
                keep = counting_ && !cut && kept_bytes_ + chunk_size_ <= kKeptChunkBytes;
            }
        } catch (const WireError& e) {
            Damaged(record, std::string("chunk: ") + e.what());
        }
        // The CRC once, in the first pass: the second reads the same bytes.
        if (counting_ && !cut && crc != 0 && std::uint32_t(crc32(0, chunk_, uInt(chunk_size_))) != crc) {
            Damaged(record, "chunk CRC mismatch: the chunk's data is damaged");
        }
        if (keep) {  // only chunks that passed their checks
            kept_[record].assign(chunk_, chunk_ + chunk_size_);
            kept_bytes_ += chunk_size_;
        }
        in_chunk_ = true;
        chunk_cut_ = cut;
        chunk_record_ = record;
        chunk_pos_ = 0;
        return NextInChunk(message);
    }

    bool NextInChunk(BagMessage& message) {
        const std::size_t left = chunk_size_ - chunk_pos_;
        std::uint64_t length = 0;
        if (left >= kRecordHeader) {
            for (int i = 0; i < 8; ++i) length |= std::uint64_t(chunk_[chunk_pos_ + 1 + i]) << (8 * i);
        }
        if (left < kRecordHeader || length > left - kRecordHeader) {
            if (chunk_cut_) Cut("inside the chunk at byte " + std::to_string(chunk_record_));
            if (left != 0) Damaged(chunk_record_, "record at chunk byte " + std::to_string(chunk_pos_) + " runs past the chunk's end");
            in_chunk_ = false;
            return false;
        }
        const std::uint8_t op = chunk_[chunk_pos_];
        const std::size_t at = chunk_pos_;
        chunk_pos_ += kRecordHeader + length;
        if (op != kSchema && op != kChannel && op != kMessage) return false;
        return Handle(op, chunk_ + at + kRecordHeader, length, chunk_record_, at, message);
    }

    /// Schemas and channels are registered; a message of a wanted topic is returned.
    bool Handle(std::uint8_t op, const std::uint8_t* data, std::uint64_t length, std::uint64_t position,
                std::uint64_t inner, BagMessage& message) {
        BagMessage probe;
        probe.position = position;
        probe.inner = inner;
        WireReader in(data, length, RosWire::kRos1);
        try {
            if (op == kSchema) {
                const std::uint16_t id = in.U16();
                schemas_[id] = in.String();
                return false;
            }
            if (op == kChannel) {
                const std::uint16_t id = in.U16(), schema = in.U16();
                const std::string topic = in.String(), encoding = in.String();
                if (channels_.count(id)) return false;
                std::string type = schema == 0 ? "" : schemas_.count(schema) ? schemas_[schema] : "";
                if (schema != 0 && type.empty()) throw WireError("channel " + std::to_string(id) + " names schema " + std::to_string(schema) + ", not declared before it");
                const bool ros1 = encoding == "ros1";
                if (!ros1 && encoding != "cdr") type += " (" + encoding + " encoded)";
                channels_[id] = AddTopic(topic, type, ros1 ? RosWire::kRos1 : RosWire::kCdr);
                return false;
            }
            const std::uint16_t channel = in.U16();
            in.U32();  // sequence
            const std::uint64_t log_time = in.U64();
            in.U64();  // publish time
            const auto found = channels_.find(channel);
            if (found == channels_.end()) throw WireError("message on channel " + std::to_string(channel) + ", not declared before it");
            const std::size_t topic = found->second;
            if (counting_) {
                BagTopic& t = topics_[topic];
                if (t.count++ == 0) t.first_ns = std::int64_t(log_time);
                t.last_ns = std::int64_t(log_time);
            }
            if (!Wanted(topic)) return false;
            message.topic = topic;
            message.log_time_ns = std::int64_t(log_time);
            message.size = in.left();
            message.data = in.Bytes(message.size);
            message.position = position;
            message.inner = inner;
            return true;
        } catch (const WireError& e) {
            throw DatasetError(file_, "damaged MCAP record (opcode " + std::to_string(op) + ") at " + Where(probe) + ": " + e.what());
        }
    }

    std::size_t AddTopic(const std::string& name, const std::string& type, RosWire wire) {
        for (std::size_t i = 0; i < topics_.size(); ++i) {
            if (topics_[i].name == name && topics_[i].type == type && topics_[i].wire == wire) return i;
        }
        topics_.push_back({name, type, wire, 0, 0, 0});
        return topics_.size() - 1;
    }

    bool Wanted(std::size_t topic) {
        if (wanted_cache_.size() <= topic) wanted_cache_.resize(topic + 1, -1);
        if (wanted_cache_[topic] < 0) wanted_cache_[topic] = wanted_(topic) ? 1 : 0;
        return wanted_cache_[topic] == 1;
    }

    std::filesystem::path file_;
    bool allow_truncated_;
    std::unique_ptr<std::FILE, decltype(&std::fclose)> f_;
    std::uint64_t size_ = 0, at_ = ~0ull, pos_ = 0;
    std::string profile_;
    std::vector<BagTopic> topics_;
    std::map<std::uint16_t, std::string> schemas_;
    std::map<std::uint16_t, std::size_t> channels_;
    std::function<bool(std::size_t)> wanted_;
    std::vector<signed char> wanted_cache_;
    bool counting_ = false, counted_ = false, ended_ = false, in_chunk_ = false, chunk_cut_ = false;
    std::vector<std::uint8_t> record_, raw_, plain_;
    std::map<std::uint64_t, std::vector<std::uint8_t>> kept_;  ///< by chunk record offset
    std::size_t kept_bytes_ = 0;
    const std::uint8_t* chunk_ = nullptr;
    std::size_t chunk_size_ = 0, chunk_pos_ = 0;
    std::uint64_t chunk_record_ = 0;
};

}  // namespace

std::unique_ptr<BagSource> OpenMcapSource(const std::filesystem::path& file, const ReaderOptions& options) {
    return std::make_unique<McapSource>(file, options);
}

}  // namespace revisit
