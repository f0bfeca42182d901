#pragma once
/// Lines of a text file that may be compressed: plain, gzip (zlib; every member's CRC-32 and length
/// checked) or bzip2 (libbz2; every stream's CRC checked), recognized by their magic bytes. Damage
/// is a DatasetError naming the file; a line longer than a bound is an error, not an allocation.
#include <bzlib.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace revisit {

enum class TextCompression { kPlain, kGzip, kBzip2 };

class CompressedTextLines {
  public:
    /// Throws DatasetError when the file cannot be opened.
    CompressedTextLines(const std::filesystem::path& file, std::size_t max_line_bytes);
    ~CompressedTextLines();
    CompressedTextLines(const CompressedTextLines&) = delete;
    CompressedTextLines& operator=(const CompressedTextLines&) = delete;

    /// The next line without its '\n' (and '\r'); false at the clean end of the data. Throws
    /// DatasetError for damaged compression, a read error or a line over the bound (with its number).
    bool Next(std::string& line);
    std::size_t line_number() const { return line_number_; }
    TextCompression compression() const { return compression_; }

  private:
    bool Fill();
    [[noreturn]] void Fail(const std::string& problem) const;

    std::filesystem::path file_;
    std::size_t max_line_bytes_;
    std::FILE* in_ = nullptr;
    TextCompression compression_ = TextCompression::kPlain;
    z_stream z_{};
    bz_stream bz_{};
    bool stream_ready_ = false;
    bool member_started_ = false;
    bool input_ended_ = false;
    bool ended_ = false;
    std::vector<char> in_buffer_;
    std::vector<char> out_buffer_;
    std::size_t out_begin_ = 0, out_end_ = 0;
    std::size_t line_number_ = 0;
};

}  // namespace revisit
