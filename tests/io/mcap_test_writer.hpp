#pragma once
/// Test-only builders: CDR messages and MCAP files (https://mcap.dev/spec), small and uncompressed or
/// with lz4-frame chunks, so the reader meets layouts the shared recordings do not have.
#include <lz4frame.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace revisit::test {

/// Little-endian bytes; CDR alignment counted from `origin`.
class Bytes {
  public:
    std::string data;
    std::size_t origin = 0;
    Bytes& Align(std::size_t n) {
        while ((data.size() - origin) % n) data += '\0';
        return *this;
    }
    template <typename T>
    Bytes& Put(T value, bool align = false) {
        if (align) Align(sizeof(T));
        char raw[sizeof(T)];
        std::memcpy(raw, &value, sizeof(T));
        data.append(raw, sizeof(T));
        return *this;
    }
    Bytes& Str(const std::string& s) { return Put(std::uint32_t(s.size())).Raw(s); }  ///< MCAP string
    Bytes& CdrStr(const std::string& s) { Put(std::uint32_t(s.size() + 1), true).Raw(s); data += '\0'; return *this; }
    Bytes& Raw(const std::string& s) { data += s; return *this; }
};

/// A CDR (little-endian) PointCloud2 of float32 x, y, z points, unorganized.
inline std::string CdrCloud(std::int32_t sec, std::uint32_t nsec, const std::vector<float>& xyz, const std::string& frame = "lidar") {
    Bytes b;
    b.Raw(std::string("\0\1\0\0", 4));
    b.origin = 4;
    b.Put(sec, true).Put(nsec, true).CdrStr(frame);
    b.Put(std::uint32_t(1), true).Put(std::uint32_t(xyz.size() / 3), true);
    b.Put(std::uint32_t(3), true);
    for (int f = 0; f < 3; ++f) b.CdrStr(std::string(1, char('x' + f))).Put(std::uint32_t(4 * f), true).Put(std::uint8_t(7)).Put(std::uint32_t(1), true);
    b.Put(std::uint8_t(0)).Put(std::uint32_t(12), true).Put(std::uint32_t(12 * xyz.size() / 3), true);
    b.Put(std::uint32_t(xyz.size() * 4), true);
    b.Raw(std::string(reinterpret_cast<const char*>(xyz.data()), xyz.size() * 4));
    b.Put(std::uint8_t(1));
    return b.data;
}

inline std::string Record(std::uint8_t op, const std::string& content) {
    Bytes b;
    b.Put(op).Put(std::uint64_t(content.size())).Raw(content);
    return b.data;
}

inline std::string Schema(std::uint16_t id, const std::string& name) {
    return Record(3, Bytes().Put(id).Str(name).Str("ros2msg").Str("").data);
}
inline std::string Channel(std::uint16_t id, std::uint16_t schema, const std::string& topic) {
    return Record(4, Bytes().Put(id).Put(schema).Str(topic).Str("cdr").Put(std::uint32_t(0)).data);
}
inline std::string Message(std::uint16_t channel, std::uint64_t log_time, const std::string& data) {
    return Record(5, Bytes().Put(channel).Put(std::uint32_t(0)).Put(log_time).Put(log_time).Raw(data).data);
}

inline std::string Lz4Frame(const std::string& plain) {
    std::string out(LZ4F_compressFrameBound(plain.size(), nullptr), '\0');
    out.resize(LZ4F_compressFrame(out.data(), out.size(), plain.data(), plain.size(), nullptr));
    return out;
}

/// A chunk of `records` stored with `compression` ("" or "lz4"); `declared` overrides the uncompressed size.
inline std::string Chunk(const std::string& records, const std::string& compression, std::uint64_t declared = ~0ull) {
    const std::string stored = compression == "lz4" ? Lz4Frame(records) : records;
    return Record(6, Bytes()
                         .Put(std::uint64_t(0))
                         .Put(std::uint64_t(0))
                         .Put(declared == ~0ull ? std::uint64_t(records.size()) : declared)
                         .Put(std::uint32_t(0))
                         .Str(compression)
                         .Put(std::uint64_t(stored.size()))
                         .Raw(stored)
                         .data);
}

inline const std::string kMcapMagic("\x89MCAP0\r\n", 8);

/// Magic, Header (profile ros2), the data records, DataEnd, Footer, magic.
inline std::string Mcap(const std::string& data_records) {
    return kMcapMagic + Record(1, Bytes().Str("ros2").Str("revisit test").data) + data_records +
           Record(0x0F, Bytes().Put(std::uint32_t(0)).data) +
           Record(2, Bytes().Put(std::uint64_t(0)).Put(std::uint64_t(0)).Put(std::uint32_t(0)).data) + kMcapMagic;
}

}  // namespace revisit::test
