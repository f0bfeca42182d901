/// PCD v0.7 reader (ascii and binary; binary_compressed is refused with a clear message).
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/field_layout.hpp"

namespace revisit {
namespace {

std::vector<std::string> Tokens(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> tokens;
    for (std::string t; in >> t;) tokens.push_back(t);
    return tokens;
}

std::size_t ParseCount(const std::filesystem::path& file, const std::string& text, const char* what) {
    try {
        std::size_t used = 0;
        const long long value = std::stoll(text, &used);
        if (used == text.size() && value >= 0) return static_cast<std::size_t>(value);
    } catch (const std::exception&) {
    }
    throw DatasetError(file, std::string("PCD header: bad ") + what + " value '" + text + "'");
}

}  // namespace

CloudData LoadPcd(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw DatasetError(file, "cannot open for reading");
    std::vector<std::string> names, types;
    std::vector<std::size_t> sizes, counts;
    std::size_t num_points = 0, width = 0, height = 1;
    bool have_points = false;
    std::string line, data;
    for (std::size_t line_number = 1; data.empty(); ++line_number) {
        if (!std::getline(in, line)) throw DatasetError(file, "PCD header has no DATA line");
        const auto tokens = Tokens(line);
        if (tokens.empty() || tokens[0][0] == '#') continue;
        const std::string& key = tokens[0];
        const std::vector<std::string> rest(tokens.begin() + 1, tokens.end());
        if (key == "FIELDS") names = rest;
        else if (key == "SIZE") for (const auto& t : rest) sizes.push_back(ParseCount(file, t, "SIZE"));
        else if (key == "TYPE") types = rest;
        else if (key == "COUNT") for (const auto& t : rest) counts.push_back(ParseCount(file, t, "COUNT"));
        else if (key == "WIDTH" && rest.size() == 1) width = ParseCount(file, rest[0], "WIDTH");
        else if (key == "HEIGHT" && rest.size() == 1) height = ParseCount(file, rest[0], "HEIGHT");
        else if (key == "POINTS" && rest.size() == 1) { num_points = ParseCount(file, rest[0], "POINTS"); have_points = true; }
        else if (key == "DATA" && rest.size() == 1) data = rest[0];
        else if (key != "VERSION" && key != "VIEWPOINT") throw DatasetError(file, "PCD header: unexpected line", line_number);
    }
    // WIDTH * HEIGHT must not wrap (2^32 * 2^32 is 0 in 64 bits) and must agree with POINTS.
    if (height != 0 && width > std::numeric_limits<std::size_t>::max() / height) {
        throw DatasetError(file, "PCD header: WIDTH " + std::to_string(width) + " x HEIGHT " + std::to_string(height) +
                                     " overflows");
    }
    if (!have_points) num_points = width * height;
    else if (width != 0 && num_points != width * height) {
        throw DatasetError(file, "PCD header: POINTS " + std::to_string(num_points) + " is not WIDTH x HEIGHT = " +
                                     std::to_string(width * height));
    }
    if (counts.empty()) counts.assign(names.size(), 1);
    if (names.empty() || sizes.size() != names.size() || types.size() != names.size() || counts.size() != names.size()) {
        throw DatasetError(file, "PCD header: FIELDS, SIZE, TYPE and COUNT disagree in length");
    }
    FieldLayout layout;
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (types[i].size() != 1 || !layout.Append(Field{names[i], types[i][0], sizes[i], counts[i], 0})) {
            throw DatasetError(file, "PCD header: unsupported field '" + names[i] + "'");
        }
        if (types[i] != "F" && types[i] != "I" && types[i] != "U") {
            throw DatasetError(file, "PCD header: unknown TYPE '" + types[i] + "'");
        }
    }
    if (data == "binary_compressed") throw DatasetError(file, "PCD DATA binary_compressed is not supported; save as binary");
    if (data != "ascii" && data != "binary") throw DatasetError(file, "PCD header: unknown DATA '" + data + "'");
    return DecodePointRecords(file, layout, num_points, data == "binary", in);
}

}  // namespace revisit
