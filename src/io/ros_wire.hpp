#pragma once
/// Bounded reading of serialized ROS messages. ROS 1: packed little-endian, strings as uint32 length +
/// bytes. ROS 2 CDR (XCDR1, as rosbag2 stores it): a 4-byte encapsulation header (byte 1: 0 big-endian,
/// 1 little-endian), each value aligned to its size counted from the end of that header, strings as
/// uint32 length including a terminating NUL. Every length is checked against the bytes left first.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace revisit {

enum class RosWire { kRos1, kCdr };

/// What is wrong inside one message and at which byte; the reader adds the file, topic and index.
struct WireError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class WireReader {
  public:
    /// CDR: reads and checks the encapsulation header. Throws WireError.
    WireReader(const std::uint8_t* data, std::size_t size, RosWire wire);

    std::uint8_t U8();
    std::uint16_t U16();
    std::uint32_t U32();
    std::uint64_t U64() { return Raw(8); }
    std::int32_t I32() { return static_cast<std::int32_t>(U32()); }
    float F32();
    double F64();
    std::string String();
    /// A sequence length, at most what the bytes left can hold with `min_element_bytes` per element.
    std::uint32_t Length(std::size_t min_element_bytes);
    /// `n` bytes in place (no copy).
    const std::uint8_t* Bytes(std::size_t n);
    /// A std_msgs/Header's stamp [ns] and frame_id (ROS 1 headers also carry a seq, skipped).
    std::int64_t Header(std::string& frame_id);

    bool big_endian() const { return swap_; }
    std::size_t offset() const { return pos_; }
    std::size_t left() const { return size_ - pos_; }

  private:
    void Align(std::size_t n);
    void Need(std::size_t n, const char* what) const;
    std::uint64_t Raw(std::size_t n);

    const std::uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
    std::size_t origin_ = 0;  ///< CDR alignment counts from here
    bool cdr_;
    bool swap_ = false;
};

}  // namespace revisit
