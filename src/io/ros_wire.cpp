#include "io/ros_wire.hpp"

#include <cstring>

namespace revisit {

WireReader::WireReader(const std::uint8_t* data, std::size_t size, RosWire wire)
    : data_(data), size_(size), cdr_(wire == RosWire::kCdr) {
    if (!cdr_) return;
    Need(4, "CDR encapsulation header");
    // PLAIN_CDR (0x00 0x00 big-endian, 0x00 0x01 little-endian); the options bytes are ignored.
    if (data_[0] != 0 || data_[1] > 1) {
        throw WireError("not a plain CDR message: encapsulation " + std::to_string(data_[0]) + " " + std::to_string(data_[1]));
    }
    swap_ = data_[1] == 0;
    pos_ = origin_ = 4;
}

void WireReader::Need(std::size_t n, const char* what) const {
    if (n > size_ - pos_) {
        throw WireError(std::string(what) + " needs " + std::to_string(n) + " bytes at message byte " +
                        std::to_string(pos_) + ", the message has " + std::to_string(size_));
    }
}

void WireReader::Align(std::size_t n) {
    if (!cdr_) return;
    const std::size_t misalign = (pos_ - origin_) % n;
    if (misalign == 0) return;
    Need(n - misalign, "alignment");
    pos_ += n - misalign;
}

std::uint64_t WireReader::Raw(std::size_t n) {
    Align(n);
    Need(n, "a value");
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const std::uint64_t byte = data_[pos_ + (swap_ ? n - 1 - i : i)];
        value |= byte << (8 * i);
    }
    pos_ += n;
    return value;
}

std::uint8_t WireReader::U8() { return static_cast<std::uint8_t>(Raw(1)); }
std::uint16_t WireReader::U16() { return static_cast<std::uint16_t>(Raw(2)); }
std::uint32_t WireReader::U32() { return static_cast<std::uint32_t>(Raw(4)); }

float WireReader::F32() {
    const std::uint32_t bits = U32();
    float value;
    std::memcpy(&value, &bits, 4);
    return value;
}

double WireReader::F64() {
    const std::uint64_t bits = Raw(8);
    double value;
    std::memcpy(&value, &bits, 8);
    return value;
}

std::uint32_t WireReader::Length(std::size_t min_element_bytes) {
    const std::uint32_t n = U32();
    const std::size_t left = size_ - pos_;
    if (min_element_bytes > 0 && n > left / min_element_bytes) {
        throw WireError("sequence length " + std::to_string(n) + " at message byte " + std::to_string(pos_ - 4) +
                        " exceeds the " + std::to_string(left) + " bytes left");
    }
    return n;
}

const std::uint8_t* WireReader::Bytes(std::size_t n) {
    Need(n, "a byte array");
    const std::uint8_t* p = data_ + pos_;
    pos_ += n;
    return p;
}

std::string WireReader::String() {
    const std::size_t at = pos_;
    const std::uint32_t n = Length(1);
    if (!cdr_) return std::string(reinterpret_cast<const char*>(Bytes(n)), n);
    // CDR counts the terminating NUL; an empty string is length 1.
    if (n == 0) throw WireError("CDR string of length 0 at message byte " + std::to_string(at));
    const std::uint8_t* p = Bytes(n);
    if (p[n - 1] != 0) throw WireError("CDR string at message byte " + std::to_string(at) + " is not NUL-terminated");
    return std::string(reinterpret_cast<const char*>(p), n - 1);
}

std::int64_t WireReader::Header(std::string& frame_id) {
    if (!cdr_) U32();  // seq
    const std::int64_t sec = cdr_ ? std::int64_t(I32()) : std::int64_t(U32());
    const std::int64_t nsec = U32();
    frame_id = String();
    return sec * 1'000'000'000 + nsec;
}

}  // namespace revisit
