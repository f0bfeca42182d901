#include "io/compressed_text.hpp"

#include <cerrno>
#include <cstring>

#include "core/error.hpp"

namespace revisit {
namespace {
constexpr std::size_t kBufferBytes = 1 << 16;
}  // namespace

CompressedTextLines::CompressedTextLines(const std::filesystem::path& file, std::size_t max_line_bytes)
    : file_(file), max_line_bytes_(max_line_bytes), in_buffer_(kBufferBytes), out_buffer_(4 * kBufferBytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw DatasetError(file, "not a readable file");
    in_ = std::fopen(file.c_str(), "rb");
    if (!in_) throw DatasetError(file, std::string("cannot open: ") + std::strerror(errno));
    unsigned char magic[3] = {0, 0, 0};
    const std::size_t n = std::fread(magic, 1, 3, in_);
    std::rewind(in_);
    if (n >= 2 && magic[0] == 0x1f && magic[1] == 0x8b) {
        compression_ = TextCompression::kGzip;
        // 16 + MAX_WBITS: gzip wrapper only, so zlib checks the header, the CRC-32 and the length.
        if (inflateInit2(&z_, 16 + MAX_WBITS) != Z_OK) throw DatasetError(file, "cannot start gzip decompression");
        stream_ready_ = true;
    } else if (n == 3 && magic[0] == 'B' && magic[1] == 'Z' && magic[2] == 'h') {
        compression_ = TextCompression::kBzip2;
        if (BZ2_bzDecompressInit(&bz_, 0, 0) != BZ_OK) throw DatasetError(file, "cannot start bzip2 decompression");
        stream_ready_ = true;
    }
}

CompressedTextLines::~CompressedTextLines() {
    if (stream_ready_ && compression_ == TextCompression::kGzip) inflateEnd(&z_);
    if (stream_ready_ && compression_ == TextCompression::kBzip2) BZ2_bzDecompressEnd(&bz_);
    if (in_) std::fclose(in_);
}

void CompressedTextLines::Fail(const std::string& problem) const {
    throw DatasetError(file_, problem + (line_number_ > 0 ? " (after line " + std::to_string(line_number_) + ")" : ""));
}

bool CompressedTextLines::Fill() {
    out_begin_ = out_end_ = 0;
    if (ended_) return false;
    if (compression_ == TextCompression::kPlain) {
        const std::size_t n = std::fread(out_buffer_.data(), 1, out_buffer_.size(), in_);
        if (n == 0) {
            if (std::ferror(in_)) Fail(std::string("read error: ") + std::strerror(errno));
            ended_ = true;
            return false;
        }
        out_end_ = n;
        return true;
    }
    const bool gzip = compression_ == TextCompression::kGzip;
    for (;;) {
        const std::size_t avail_in = gzip ? z_.avail_in : bz_.avail_in;
        if (avail_in == 0 && !input_ended_) {
            const std::size_t n = std::fread(in_buffer_.data(), 1, in_buffer_.size(), in_);
            if (n == 0 && std::ferror(in_)) Fail(std::string("read error: ") + std::strerror(errno));
            input_ended_ = n == 0;
            if (gzip) {
                z_.next_in = reinterpret_cast<Bytef*>(in_buffer_.data());
                z_.avail_in = static_cast<uInt>(n);
            } else {
                bz_.next_in = in_buffer_.data();
                bz_.avail_in = static_cast<unsigned>(n);
            }
        }
        if ((gzip ? z_.avail_in : bz_.avail_in) == 0 && input_ended_) {
            if (member_started_) Fail(gzip ? "truncated gzip stream: the file ends before the gzip end marker"
                                           : "truncated bzip2 stream: the file ends before the end of the stream");
            ended_ = true;
            return false;
        }
        std::size_t produced = 0;
        if (gzip) {
            z_.next_out = reinterpret_cast<Bytef*>(out_buffer_.data());
            z_.avail_out = static_cast<uInt>(out_buffer_.size());
            const int status = inflate(&z_, Z_NO_FLUSH);
            produced = out_buffer_.size() - z_.avail_out;
            if (status == Z_STREAM_END) {
                member_started_ = false;  // CRC-32 and length matched; more bytes must be another member
                inflateReset(&z_);
            } else if (status == Z_OK) {
                member_started_ = true;
            } else if (status != Z_BUF_ERROR) {
                Fail(std::string("corrupt gzip stream (") + (z_.msg ? z_.msg : "zlib error " + std::to_string(status)) + ")");
            }
        } else {
            bz_.next_out = out_buffer_.data();
            bz_.avail_out = static_cast<unsigned>(out_buffer_.size());
            const int status = BZ2_bzDecompress(&bz_);
            produced = out_buffer_.size() - bz_.avail_out;
            if (status == BZ_STREAM_END) {
                member_started_ = false;  // the stream's CRC matched; more bytes must be another stream
                BZ2_bzDecompressEnd(&bz_);
                stream_ready_ = false;
                if (BZ2_bzDecompressInit(&bz_, 0, 0) != BZ_OK) Fail("cannot restart bzip2 decompression");
                stream_ready_ = true;
            } else if (status == BZ_OK) {
                member_started_ = true;
            } else {
                Fail("corrupt bzip2 stream (libbz2 error " + std::to_string(status) + ")");
            }
        }
        if (produced > 0) {
            out_end_ = produced;
            return true;
        }
    }
}

bool CompressedTextLines::Next(std::string& line) {
    line.clear();
    bool any = false;
    for (;;) {
        if (out_begin_ == out_end_ && !Fill()) break;
        any = true;
        const char* begin = out_buffer_.data() + out_begin_;
        const char* end = out_buffer_.data() + out_end_;
        const char* newline = static_cast<const char*>(std::memchr(begin, '\n', static_cast<std::size_t>(end - begin)));
        const char* stop = newline ? newline : end;
        if (line.size() + static_cast<std::size_t>(stop - begin) > max_line_bytes_) {
            ++line_number_;
            throw DatasetError(file_, "line longer than " + std::to_string(max_line_bytes_) + " bytes", line_number_);
        }
        line.append(begin, stop);
        out_begin_ += static_cast<std::size_t>(stop - begin) + (newline ? 1 : 0);
        if (newline) break;
    }
    if (!any) return false;
    ++line_number_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
}

}  // namespace revisit
