#include "io/field_layout.hpp"

#include <cstdint>
#include <algorithm>
#include <cstring>
#include <sstream>
#include <string>

#include "core/error.hpp"

namespace revisit {

bool FieldLayout::Append(Field field) {
    const bool valid_size = field.kind == 'F' ? (field.size == 4 || field.size == 8)
                                              : (field.size == 1 || field.size == 2 || field.size == 4 || field.size == 8);
    if (!valid_size || field.count == 0 || field.count > 1024) return false;
    field.offset = record_size;
    record_size += field.size * field.count;
    values_per_record += field.count;
    fields.push_back(field);
    return true;
}

int FieldLayout::Find(std::initializer_list<const char*> names) const {
    for (std::size_t i = 0; i < fields.size(); ++i) {
        for (const char* name : names) {
            if (fields[i].name == name) return static_cast<int>(i);
        }
    }
    return -1;
}

std::size_t FieldLayout::Column(int field) const {
    std::size_t column = 0;
    for (int i = 0; i < field; ++i) column += fields[i].count;
    return column;
}

double ReadBinaryValue(const unsigned char* data, const Field& field) {
    // memcpy: records are packed, so values may be unaligned.
    switch (field.kind) {
        case 'F':
            if (field.size == 4) { float v; std::memcpy(&v, data, 4); return v; }
            { double v; std::memcpy(&v, data, 8); return v; }
        case 'I':
            switch (field.size) {
                case 1: { std::int8_t v; std::memcpy(&v, data, 1); return v; }
                case 2: { std::int16_t v; std::memcpy(&v, data, 2); return v; }
                case 4: { std::int32_t v; std::memcpy(&v, data, 4); return v; }
                default: { std::int64_t v; std::memcpy(&v, data, 8); return static_cast<double>(v); }
            }
        default:
            switch (field.size) {
                case 1: { std::uint8_t v; std::memcpy(&v, data, 1); return v; }
                case 2: { std::uint16_t v; std::memcpy(&v, data, 2); return v; }
                case 4: { std::uint32_t v; std::memcpy(&v, data, 4); return v; }
                default: { std::uint64_t v; std::memcpy(&v, data, 8); return static_cast<double>(v); }
            }
    }
}

PointColumns FindPointColumns(const FieldLayout& layout) {
    PointColumns columns;
    columns.x = layout.Find({"x"});
    columns.y = layout.Find({"y"});
    columns.z = layout.Find({"z"});
    columns.intensity = layout.Find({"intensity", "i", "reflectance", "scalar_intensity"});
    columns.time = layout.Find({"t", "time", "timestamp", "offset_time"});
    return columns;
}

namespace {
constexpr std::size_t kMaxPoints = 100'000'000;  // a header claiming more is corrupt, not a scan
}

std::uint64_t BytesLeft(std::istream& in) {
    const auto here = in.tellg();
    if (here < 0) return 0;
    in.seekg(0, std::ios::end);
    const auto end = in.tellg();
    in.seekg(here);
    return end > here ? static_cast<std::uint64_t>(end - here) : 0;
}

CloudData DecodePointRecords(const std::filesystem::path& file, const FieldLayout& layout, std::size_t num_points,
                             bool binary, std::istream& in) {
    const PointColumns c = FindPointColumns(layout);
    if (c.x < 0 || c.y < 0 || c.z < 0) throw DatasetError(file, "no x, y, z fields");
    if (num_points > kMaxPoints) throw DatasetError(file, "implausible point count " + std::to_string(num_points));
    // The header's count is checked against the bytes that follow it before anything is allocated:
    // a binary record is record_size bytes, an ascii record at least one character and one separator
    // per value.
    const std::uint64_t offset = static_cast<std::uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
    const std::uint64_t left = BytesLeft(in);
    const std::uint64_t min_record = binary ? layout.record_size : 2 * layout.values_per_record;
    if (num_points > (binary ? left : left + 1) / min_record) {
        throw DatasetError(file, "header declares " + std::to_string(num_points) + " points, but the " +
                                     std::to_string(left) + " bytes after the header (from byte " +
                                     std::to_string(offset) + ") hold at most " +
                                     std::to_string((binary ? left : left + 1) / min_record));
    }
    CloudData cloud;
    cloud.has_intensity = c.intensity >= 0;
    cloud.has_time = c.time >= 0;
    cloud.points.reserve(num_points);
    const auto value_of = [&](int field, const auto& get) { return field < 0 ? 0.f : static_cast<float>(get(field)); };
    if (binary) {
        std::vector<unsigned char> record(layout.record_size);
        for (std::size_t i = 0; i < num_points; ++i) {
            if (!in.read(reinterpret_cast<char*>(record.data()), static_cast<std::streamsize>(record.size()))) {
                throw DatasetError(file, "data ends after " + std::to_string(i) + " of " +
                                             std::to_string(num_points) + " points");
            }
            const auto get = [&](int f) { return ReadBinaryValue(record.data() + layout.fields[f].offset, layout.fields[f]); };
            cloud.Add(value_of(c.x, get), value_of(c.y, get), value_of(c.z, get), value_of(c.intensity, get),
                      value_of(c.time, get));
        }
        return cloud;
    }
    std::string line;
    std::vector<double> values(layout.values_per_record);
    for (std::size_t i = 0; i < num_points;) {
        if (!std::getline(in, line)) {
            throw DatasetError(file, "data ends after " + std::to_string(i) + " of " + std::to_string(num_points) +
                                         " points");
        }
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream tokens(line);
        for (auto& v : values) {
            std::string token;
            if (!(tokens >> token)) throw DatasetError(file, "point " + std::to_string(i) + " has too few values");
            // strtod accepts nan/inf, which are then dropped as non-finite points like in binary files.
            char* end = nullptr;
            v = std::strtod(token.c_str(), &end);
            if (end == token.c_str()) throw DatasetError(file, "point " + std::to_string(i) + ": not a number: " + token);
        }
        const auto get = [&](int f) { return values[layout.Column(f)]; };
        cloud.Add(value_of(c.x, get), value_of(c.y, get), value_of(c.z, get), value_of(c.intensity, get),
                  value_of(c.time, get));
        ++i;
    }
    return cloud;
}

}  // namespace revisit
