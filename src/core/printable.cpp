#include "core/printable.hpp"

#include <cstdio>
#include <iostream>

namespace revisit {
namespace {

bool IsControl(unsigned char c) { return (c < 0x20 && c != '\n' && c != '\t' && c != '\r') || c == 0x7f; }

std::string Escaped(unsigned char c) {
    char text[5];
    std::snprintf(text, sizeof(text), "\\x%02x", c);
    return text;
}

}  // namespace

std::string Printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        const auto c = static_cast<unsigned char>(text[i]);
        const auto next = i + 1 < text.size() ? static_cast<unsigned char>(text[i + 1]) : 0;
        if (c == 0xc2 && next >= 0x80 && next <= 0x9f) {  // a C1 control in UTF-8 (U+009B is a CSI)
            out += Escaped(c) + Escaped(next);
            ++i;
        } else if (IsControl(c)) {
            out += Escaped(c);
        } else {
            out.push_back(static_cast<char>(c));
        }
    }
    return out;
}

std::string PrintableField(std::string_view text) {
    std::string out;
    for (const char c : Printable(text)) {
        if (c == '\n' || c == '\r' || c == '\t') out += Escaped(static_cast<unsigned char>(c));
        else out.push_back(c);
    }
    return out;
}

PrintableStreambuf::~PrintableStreambuf() {
    if (after_c2_) target_->sputc(static_cast<char>(0xc2));
    target_->pubsync();
}

bool PrintableStreambuf::Put(unsigned char c) {
    const auto put = [this](const std::string& s) {
        return target_->sputn(s.data(), static_cast<std::streamsize>(s.size())) == static_cast<std::streamsize>(s.size());
    };
    if (after_c2_) {
        after_c2_ = false;
        if (c >= 0x80 && c <= 0x9f) return put(Escaped(0xc2) + Escaped(c));
        if (!put(std::string(1, static_cast<char>(0xc2)))) return false;
    }
    if (c == 0xc2) {
        after_c2_ = true;
        return true;
    }
    if (IsControl(c)) return put(Escaped(c));
    return target_->sputc(static_cast<char>(c)) != traits_type::eof();
}

PrintableStreambuf::int_type PrintableStreambuf::overflow(int_type c) {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    return Put(static_cast<unsigned char>(traits_type::to_char_type(c))) ? c : traits_type::eof();
}

std::streamsize PrintableStreambuf::xsputn(const char* s, std::streamsize n) {
    for (std::streamsize i = 0; i < n; ++i) {
        if (!Put(static_cast<unsigned char>(s[i]))) return i;
    }
    return n;
}

int PrintableStreambuf::sync() {
    // A lone 0xC2 stays held until the next byte says what it is.
    return target_->pubsync();
}

void FilterTerminalOutput() {
    static bool installed = false;
    if (installed) return;
    installed = true;
    // Never destroyed: the standard streams are flushed after static objects are gone.
    std::cout.rdbuf(new PrintableStreambuf(std::cout.rdbuf()));
    std::cerr.rdbuf(new PrintableStreambuf(std::cerr.rdbuf()));
}

}  // namespace revisit
