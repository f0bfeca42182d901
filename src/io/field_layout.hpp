#pragma once
/// Per-point record layout shared by the PCD and PLY readers.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

#include "io/cloud_files.hpp"

namespace revisit {

struct Field {
    std::string name;
    char kind = 'F';          ///< 'F' float, 'I' signed integer, 'U' unsigned integer (PCD's TYPE letters)
    std::size_t size = 4;     ///< [bytes] per value
    std::size_t count = 1;    ///< values per point
    std::size_t offset = 0;   ///< [bytes] from the start of the point record
};

struct FieldLayout {
    std::vector<Field> fields;
    std::size_t record_size = 0;  ///< [bytes]
    std::size_t values_per_record = 0;

    /// Appends a field after the previous ones; returns false for a size the kind cannot have.
    bool Append(Field field);
    /// Index of the first field with one of these names, or -1.
    int Find(std::initializer_list<const char*> names) const;
    /// Index of the field's first value among the record's values (ascii column).
    std::size_t Column(int field) const;
};

/// Reads one little-endian value of the field's kind and size from `data`.
double ReadBinaryValue(const unsigned char* data, const Field& field);

/// Column indices of x, y, z, intensity and time in a layout (-1 when absent).
struct PointColumns {
    int x = -1, y = -1, z = -1, intensity = -1, time = -1;
};
PointColumns FindPointColumns(const FieldLayout& layout);

/// Bytes from the stream's position to its end (the position is kept).
std::uint64_t BytesLeft(std::istream& in);

/// Decodes `num_points` records from `in` (positioned at the first record): whitespace-separated
/// ascii values, one record per line, or packed little-endian binary. Needs x, y and z fields.
/// Throws DatasetError naming `file` when fields are missing, the count exceeds what the bytes left
/// can hold (checked before allocating), or the data ends early.
CloudData DecodePointRecords(const std::filesystem::path& file, const FieldLayout& layout, std::size_t num_points,
                             bool binary, std::istream& in);

}  // namespace revisit
