#include "io/rawlog_stream.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "core/error.hpp"

namespace revisit {
namespace {
constexpr std::size_t kBufferBytes = 1 << 16;
constexpr std::uint64_t kMaxDeflateRatio = 1032;  ///< zlib's technical limit for deflate
}  // namespace

RawlogInputStream::RawlogInputStream(const std::filesystem::path& file)
    : file_(file), in_buffer_(kBufferBytes), out_buffer_(4 * kBufferBytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw DatasetError(file, "not a readable file");
    file_bytes_ = std::filesystem::file_size(file, ec);
    if (ec) throw DatasetError(file, "cannot read: " + ec.message());
    in_ = std::fopen(file.c_str(), "rb");
    if (!in_) throw DatasetError(file, std::string("cannot open: ") + std::strerror(errno));
    unsigned char magic[2] = {0, 0};
    const std::size_t n = std::fread(magic, 1, 2, in_);
    std::rewind(in_);
    gzip_ = n == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
    if (gzip_) {
        // 16 + MAX_WBITS: gzip wrapper only, so zlib checks the header, the CRC-32 and the length.
        if (inflateInit2(&z_, 16 + MAX_WBITS) != Z_OK) throw DatasetError(file, "cannot start gzip decompression");
        z_ready_ = true;
    }
}

RawlogInputStream::~RawlogInputStream() {
    if (z_ready_) inflateEnd(&z_);
    if (in_) std::fclose(in_);
}

void RawlogInputStream::Fail(const std::string& problem) {
    error_ = problem;
    throw DatasetError(file_, problem);
}

std::uint64_t RawlogInputStream::file_position() const { return gzip_ ? file_read_ - z_.avail_in : file_read_; }

std::uint64_t RawlogInputStream::MaxBytesLeft() const {
    const std::uint64_t buffered = out_end_ - out_begin_;
    const std::uint64_t file_left = file_bytes_ > file_position() ? file_bytes_ - file_position() : 0;
    return buffered + (gzip_ ? kMaxDeflateRatio * file_left : file_left);
}

bool RawlogInputStream::Fill() {
    out_begin_ = out_end_ = 0;
    if (ended_) return false;
    if (!gzip_) {
        const std::size_t n = std::fread(out_buffer_.data(), 1, out_buffer_.size(), in_);
        if (n == 0) {
            if (std::ferror(in_)) Fail(std::string("read error: ") + std::strerror(errno));
            ended_ = true;
            return false;
        }
        file_read_ += n;
        out_end_ = n;
        return true;
    }
    for (;;) {
        if (z_.avail_in == 0 && !input_ended_) {
            const std::size_t n = std::fread(in_buffer_.data(), 1, in_buffer_.size(), in_);
            if (n == 0 && std::ferror(in_)) Fail(std::string("read error: ") + std::strerror(errno));
            input_ended_ = n == 0;
            file_read_ += n;
            z_.next_in = in_buffer_.data();
            z_.avail_in = static_cast<uInt>(n);
        }
        if (z_.avail_in == 0 && input_ended_) {
            if (member_started_) Fail("truncated gzip stream: the file ends before the gzip end marker");
            ended_ = true;
            return false;
        }
        z_.next_out = out_buffer_.data();
        z_.avail_out = static_cast<uInt>(out_buffer_.size());
        const int status = inflate(&z_, Z_NO_FLUSH);
        const std::size_t produced = out_buffer_.size() - z_.avail_out;
        if (status == Z_STREAM_END) {
            // This member's CRC-32 and length matched. More bytes must be another gzip member.
            member_started_ = false;
            inflateReset(&z_);
        } else if (status == Z_OK) {
            member_started_ = true;
        } else if (status != Z_BUF_ERROR) {  // Z_BUF_ERROR: no progress without more input, read on
            Fail(std::string("corrupt gzip stream (") + (z_.msg ? z_.msg : "zlib error " + std::to_string(status)) + ")");
        }
        if (produced > 0) {
            out_end_ = produced;
            return true;
        }
    }
}

bool RawlogInputStream::AtEnd() { return out_begin_ == out_end_ && !Fill(); }

std::size_t RawlogInputStream::Read(void* buffer, std::size_t count) {
    auto* out = static_cast<unsigned char*>(buffer);
    std::size_t done = 0;
    while (done < count) {
        if (out_begin_ == out_end_ && !Fill()) break;
        const std::size_t n = std::min(count - done, out_end_ - out_begin_);
        std::memcpy(out + done, out_buffer_.data() + out_begin_, n);
        out_begin_ += n;
        done += n;
    }
    position_ += done;
    return done;
}

std::size_t RawlogInputStream::Write(const void*, std::size_t) {
    throw std::logic_error("RawlogInputStream is read-only");
}

std::uint64_t RawlogInputStream::Seek(std::int64_t, CStream::TSeekOrigin) {
    throw std::logic_error("RawlogInputStream reads forward only");
}

}  // namespace revisit
