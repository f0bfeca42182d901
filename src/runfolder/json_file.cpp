#include "runfolder/json_file.hpp"

#include <cstdio>

#include "core/atomic_file.hpp"

namespace revisit {
namespace fs = std::filesystem;
using nlohmann::json;

bool IsValidUtf8(const std::string& text) {
    std::size_t i = 0;
    const auto byte = [&text](std::size_t k) { return static_cast<unsigned char>(text[k]); };
    while (i < text.size()) {
        const unsigned char c = byte(i);
        std::size_t extra = 0;
        unsigned min = 0;
        if (c < 0x80) {
            ++i;
            continue;
        } else if ((c & 0xE0) == 0xC0) {
            extra = 1, min = 0x80;
        } else if ((c & 0xF0) == 0xE0) {
            extra = 2, min = 0x800;
        } else if ((c & 0xF8) == 0xF0) {
            extra = 3, min = 0x10000;
        } else {
            return false;
        }
        if (i + extra >= text.size()) return false;
        unsigned code = c & (0x3F >> extra);
        for (std::size_t k = 1; k <= extra; ++k) {
            if ((byte(i + k) & 0xC0) != 0x80) return false;
            code = (code << 6) | (byte(i + k) & 0x3F);
        }
        // Overlong forms, UTF-16 surrogates and code points past U+10FFFF are not UTF-8 either.
        if (code < min || (code >= 0xD800 && code <= 0xDFFF) || code > 0x10FFFF) return false;
        i += extra + 1;
    }
    return true;
}

std::string JsonText(const json& value, int indent) { return value.dump(indent, ' ', false, json::error_handler_t::replace); }

void WriteJsonFile(const fs::path& file, const json& value) { WriteFileAtomically(file, JsonText(value) + '\n'); }

void PutPath(json& object, const std::string& key, const fs::path& path) {
    const std::string bytes = path.string();
    if (IsValidUtf8(bytes)) {
        object[key] = bytes;
        return;
    }
    // The readable form for people and other tools, the bytes for revisit to open the file again.
    object[key] = json::parse(JsonText(json(bytes)));
    std::string hex;
    for (const unsigned char c : bytes) {
        char two[3];
        std::snprintf(two, sizeof(two), "%02x", c);
        hex += two;
    }
    object[key + "_bytes"] = hex;
}

fs::path GetPath(const json& object, const std::string& key) {
    const auto bytes = object.find(key + "_bytes");
    if (bytes == object.end() || !bytes->is_string()) return object.at(key).get<std::string>();
    const std::string hex = bytes->get<std::string>();
    const auto nibble = [](char c) { return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1; };
    std::string raw;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
        const int high = nibble(hex[i]), low = nibble(hex[i + 1]);
        if (high < 0 || low < 0 || hex.size() % 2 != 0) return object.at(key).get<std::string>();  // damaged: the readable form
        raw.push_back(static_cast<char>(high * 16 + low));
    }
    return raw;
}

}  // namespace revisit
