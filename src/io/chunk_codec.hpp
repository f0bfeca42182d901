#pragma once
/// Decompression of MCAP chunks (zstd, lz4 frames) and ROS 1 bag chunks (bz2, lz4 frames), into a reused buffer.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace revisit {

/// Decompresses `compression` ("zstd", "lz4" or "bz2") `input` into `out` (grown as output comes, never past
/// `declared` bytes) and returns the bytes produced. With `partial` (the input was cut), stops quietly
/// where the input ends; otherwise the output must be exactly `declared` bytes and the frame complete.
/// Throws WireError saying what is wrong.
std::size_t Decompress(const std::string& compression, const std::uint8_t* input, std::size_t size,
                       std::size_t declared, bool partial, std::vector<std::uint8_t>& out);

}  // namespace revisit
