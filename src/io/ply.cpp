/// PLY reader (ascii and binary_little_endian; the vertex element only) and binary writer.
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/cloud_files.hpp"
#include "io/field_layout.hpp"

namespace revisit {
namespace {

bool PlyType(const std::string& name, char& kind, std::size_t& size) {
    struct Entry { const char* name; char kind; std::size_t size; };
    static const Entry entries[] = {
        {"char", 'I', 1},  {"int8", 'I', 1},   {"uchar", 'U', 1},  {"uint8", 'U', 1},   {"short", 'I', 2},
        {"int16", 'I', 2}, {"ushort", 'U', 2}, {"uint16", 'U', 2}, {"int", 'I', 4},     {"int32", 'I', 4},
        {"uint", 'U', 4},  {"uint32", 'U', 4}, {"float", 'F', 4},  {"float32", 'F', 4}, {"double", 'F', 8},
        {"float64", 'F', 8}};
    for (const auto& e : entries) {
        if (name == e.name) { kind = e.kind; size = e.size; return true; }
    }
    return false;
}

}  // namespace

CloudData LoadPly(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw DatasetError(file, "cannot open for reading");
    const std::uint64_t file_bytes = BytesLeft(in);
    std::string line;
    if (!std::getline(in, line) || line.rfind("ply", 0) != 0) throw DatasetError(file, "not a PLY file (no 'ply' magic)");
    std::string format;
    std::string element;
    std::size_t num_vertices = 0, lines_before_vertices = 0;
    bool vertex_seen = false;
    FieldLayout layout;
    for (std::size_t line_number = 2;; ++line_number) {
        if (!std::getline(in, line)) throw DatasetError(file, "PLY header has no end_header");
        std::istringstream tokens(line);
        std::string key;
        tokens >> key;
        if (key == "end_header") break;
        if (key == "format") tokens >> format;
        else if (key == "element") {
            std::size_t count = 0;
            tokens >> element >> count;
            if (!tokens) throw DatasetError(file, "PLY header: bad element line", line_number);
            // Every record takes at least one byte: a larger count is damage, refused before it is used.
            if (count > file_bytes) {
                throw DatasetError(file, "PLY header: element '" + element + "' declares " + std::to_string(count) +
                                             " records, more than the file's " + std::to_string(file_bytes) +
                                             " bytes can hold", line_number);
            }
            if (element == "vertex") { num_vertices = count; vertex_seen = true; }
            else if (!vertex_seen) lines_before_vertices += count;
        } else if (key == "property" && element == "vertex") {
            std::string type, name;
            tokens >> type >> name;
            char kind = 'F';
            std::size_t size = 0;
            if (type == "list" || !PlyType(type, kind, size) || !layout.Append(Field{name, kind, size, 1, 0})) {
                throw DatasetError(file, "PLY header: unsupported vertex property '" + line + "'", line_number);
            }
        } else if (key != "comment" && key != "obj_info" && key != "property") {
            throw DatasetError(file, "PLY header: unexpected line", line_number);
        }
    }
    if (!vertex_seen) throw DatasetError(file, "PLY has no vertex element");
    const bool binary = format == "binary_little_endian";
    if (!binary && format != "ascii") {
        throw DatasetError(file, "PLY format '" + format + "' is not supported (ascii or binary_little_endian)");
    }
    if (lines_before_vertices > 0) {
        if (binary) throw DatasetError(file, "PLY elements before the vertex element are not supported in binary files");
        for (std::size_t i = 0; i < lines_before_vertices; ++i) {
            if (!std::getline(in, line)) {
                throw DatasetError(file, "data ends after " + std::to_string(i) + " of the " +
                                             std::to_string(lines_before_vertices) + " records before the vertices");
            }
        }
    }
    return DecodePointRecords(file, layout, num_vertices, binary, in);
}

void SavePly(const std::filesystem::path& file, const std::vector<Eigen::Vector3f>& points,
             const std::vector<float>& intensities) {
    const bool with_intensity = intensities.size() == points.size() && !points.empty();
    WriteFileAtomically(file, [&](std::ostream& out) {
        out << "ply\nformat binary_little_endian 1.0\ncomment written by revisit\nelement vertex " << points.size()
            << "\nproperty float x\nproperty float y\nproperty float z\n"
            << (with_intensity ? "property float intensity\n" : "") << "end_header\n";
        for (std::size_t i = 0; i < points.size(); ++i) {
            out.write(reinterpret_cast<const char*>(points[i].data()), 3 * sizeof(float));
            if (with_intensity) out.write(reinterpret_cast<const char*>(&intensities[i]), sizeof(float));
        }
    });
}

}  // namespace revisit
