#pragma once
/// The byte stream MRPT deserializes rawlogs from: plain or gzip (read through zlib to the end of
/// every member, so the CRC-32 and length trailer are checked), with positions for error messages and
/// an upper bound of the bytes still to come, which bounds what one object may allocate.
#include <mrpt/io/CStream.h>
#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace revisit {

class RawlogInputStream final : public mrpt::io::CStream {
  public:
    /// Opens `file`; gzip is recognized by its magic bytes, not by the name. Throws DatasetError.
    explicit RawlogInputStream(const std::filesystem::path& file);
    ~RawlogInputStream() override;
    RawlogInputStream(const RawlogInputStream&) = delete;
    RawlogInputStream& operator=(const RawlogInputStream&) = delete;

    /// Returns fewer than `count` bytes only at the clean end of the data. Damage (a gzip stream that
    /// stops before its end marker, a bad CRC, trailing bytes, a read error) throws DatasetError naming
    /// the file and the compressed byte offset.
    std::size_t Read(void* buffer, std::size_t count) override;
    std::size_t Write(const void* buffer, std::size_t count) override;
    std::uint64_t Seek(std::int64_t offset, CStream::TSeekOrigin origin = sFromBeginning) override;
    std::uint64_t getTotalBytesCount() const override { return file_bytes_; }
    /// [bytes] of decompressed data read so far.
    std::uint64_t getPosition() const override { return position_; }

    /// True when every byte has been read and (gzip) every member's trailer checked.
    bool AtEnd();
    bool is_gzip() const { return gzip_; }
    /// The damage Read() found (MRPT wraps the exception it throws), empty when none.
    const std::string& error() const { return error_; }
    /// [bytes] of the file consumed so far (compressed bytes for gzip).
    std::uint64_t file_position() const;
    /// [bytes] an upper bound of the decompressed bytes still to come: exact for plain files; for gzip,
    /// deflate's maximum ratio (1032:1) times the compressed bytes left.
    std::uint64_t MaxBytesLeft() const;

  private:
    bool Fill();
    [[noreturn]] void Fail(const std::string& problem);

    std::filesystem::path file_;
    std::FILE* in_ = nullptr;
    bool gzip_ = false;
    z_stream z_{};
    bool z_ready_ = false;
    bool member_started_ = false;
    bool input_ended_ = false;
    bool ended_ = false;
    std::vector<unsigned char> in_buffer_;
    std::vector<unsigned char> out_buffer_;
    std::size_t out_begin_ = 0, out_end_ = 0;
    std::uint64_t file_bytes_ = 0;
    std::uint64_t file_read_ = 0;  ///< [bytes] fread from the file
    std::uint64_t position_ = 0;
    std::string error_;
};

}  // namespace revisit
