#include "closures/database_io.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <type_traits>

#include "core/input_file.hpp"
#include "core/error.hpp"
#include "core/png_size.hpp"
#include "core/atomic_file.hpp"

namespace revisit {
namespace {

constexpr char kMagic[8] = {'R', 'V', 'S', 'T', 'C', 'L', 'D', 'B'};
constexpr std::size_t kHeaderBytes = sizeof(kMagic) + sizeof(std::uint32_t) + sizeof(std::uint64_t);

std::uint64_t Fnv1a(const std::string& bytes) {
    std::uint64_t hash = 1469598103934665603ull;
    for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
    return hash;
}

class Writer {
  public:
    template <typename T>
    void Put(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.append(reinterpret_cast<const char*>(&value), sizeof(T));
    }
    void PutBytes(const void* data, std::size_t size) { out_.append(static_cast<const char*>(data), size); }
    void PutMatrix(const Eigen::Matrix4d& M) { PutBytes(M.data(), sizeof(double) * 16); }
    const std::string& bytes() const { return out_; }

  private:
    std::string out_;
};

class Parser {
  public:
    Parser(const std::string& bytes, const std::filesystem::path& file) : bytes_(bytes), file_(file) {}
    template <typename T>
    T Get() {
        T value;
        GetBytes(&value, sizeof(T));
        return value;
    }
    void GetBytes(void* data, std::size_t size) {
        if (size > bytes_.size() - pos_) {
            throw DatasetError(file_, "truncated closure database (payload ends at byte " + Offset() + ")");
        }
        std::memcpy(data, bytes_.data() + pos_, size);
        pos_ += size;
    }
    std::uint32_t GetCount(std::size_t element_size) {
        const auto count = Get<std::uint32_t>();
        if (std::size_t(count) * element_size > bytes_.size() - pos_) {
            throw DatasetError(file_, "corrupt closure database (the count " + std::to_string(count) + " at byte " +
                                          Offset() + " exceeds the bytes left)");
        }
        return count;
    }
    Eigen::Matrix4d GetMatrix() {
        Eigen::Matrix4d M;
        GetBytes(M.data(), sizeof(double) * 16);
        return M;
    }
    bool AtEnd() const { return pos_ == bytes_.size(); }
    /// Position in the file (the payload starts after the 20-byte header).
    std::string Offset() const { return std::to_string(pos_ + kHeaderBytes); }

  private:
    const std::string& bytes_;
    const std::filesystem::path& file_;
    std::size_t pos_ = 0;
};

}  // namespace

std::string DatabaseFingerprint(const ClosureDetectorConfig& c) {
    std::ostringstream s;
    s << "ground=" << c.align_ground << " res=" << c.density.resolution << " min_density=" << c.density.min_density
      << " threshold=" << int(c.density.threshold) << " scaling=" << int(c.density.scaling)
      << " percentile=" << c.density.scale_percentile << " elevation=" << c.density.elevation_instead
      << " target_px=" << c.density.target_extent_pixels << " res_range=" << c.density.min_resolution << ","
      << c.density.max_resolution << " orb=" << c.features.max_features << "," << c.features.edge_threshold << ","
      << c.features.patch_size << "," << c.features.wta_k << "," << c.features.fast_threshold << ","
      << c.features.harris_score << "," << c.features.min_keypoints << "," << c.features.min_fast_threshold << ","
      << c.features.pad_border << "," << c.features.self_similar_distance << " tree=" << c.tree.leaf_capacity << ","
      << c.tree.split_tolerance;
    return s.str();
}

void SaveDatabase(const ClosureDetector& detector, const std::filesystem::path& file) {
    Writer w;
    const std::string fingerprint = DatabaseFingerprint(detector.config());
    w.Put(std::uint32_t(fingerprint.size()));
    w.PutBytes(fingerprint.data(), fingerprint.size());
    const auto descriptors = detector.AllDescriptors();
    const auto& maps = detector.maps();
    w.Put(std::uint32_t(maps.size()));
    for (std::size_t i = 0; i < maps.size(); ++i) {
        const MapRecord& r = maps[i];
        w.Put(std::int32_t(r.id));
        w.Put(std::int32_t(r.session));
        w.Put(std::uint64_t(r.scans.first));
        w.Put(std::uint64_t(r.scans.last));
        w.Put(r.travel_start);
        w.Put(r.travel_end);
        w.PutMatrix(r.T_world_map.matrix());
        w.PutMatrix(r.T_ground_map.matrix());
        w.Put(r.origin.x());
        w.Put(r.origin.y());
        w.Put(r.resolution);
        w.Put(std::int32_t(r.rows));
        w.Put(std::int32_t(r.cols));
        w.Put(std::uint32_t(r.keypoints.size()));
        for (const auto& k : r.keypoints) w.PutBytes(k.data(), sizeof(float) * 2);
        for (const auto& d : descriptors[i]) w.PutBytes(d.data(), sizeof(Descriptor));
        w.Put(std::uint32_t(r.image_png.size()));
        w.PutBytes(r.image_png.data(), r.image_png.size());
    }
    const std::uint32_t version = kDatabaseVersion;
    const std::uint64_t size = w.bytes().size();
    const std::uint64_t checksum = Fnv1a(w.bytes());
    WriteFileAtomically(file, [&](std::ostream& out) {
        out.write(kMagic, sizeof(kMagic));
        out.write(reinterpret_cast<const char*>(&version), sizeof(version));
        out.write(reinterpret_cast<const char*>(&size), sizeof(size));
        out.write(w.bytes().data(), std::streamsize(size));
        out.write(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
    });
}

ClosureDetector LoadDatabase(const std::filesystem::path& file, const ClosureDetectorConfig& config) {
    std::ifstream in = OpenForReading(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    constexpr std::size_t header = sizeof(kMagic) + sizeof(std::uint32_t) + sizeof(std::uint64_t);
    if (bytes.size() < header || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
        throw DatasetError(file, "not a revisit closure database (bad magic)");
    }
    std::uint32_t version = 0;
    std::uint64_t size = 0;
    std::memcpy(&version, bytes.data() + sizeof(kMagic), sizeof(version));
    std::memcpy(&size, bytes.data() + sizeof(kMagic) + sizeof(version), sizeof(size));
    if (version != kDatabaseVersion) {
        throw DatasetError(file, "closure database version " + std::to_string(version) + ", this build reads version " +
                                     std::to_string(kDatabaseVersion));
    }
    if (size != bytes.size() - header - sizeof(std::uint64_t) || bytes.size() < header + sizeof(std::uint64_t)) {
        throw DatasetError(file, "truncated or padded closure database (size does not match its header)");
    }
    const std::string payload = bytes.substr(header, size);
    std::uint64_t checksum = 0;
    std::memcpy(&checksum, bytes.data() + header + size, sizeof(checksum));
    if (checksum != Fnv1a(payload)) throw DatasetError(file, "corrupt closure database (checksum mismatch)");

    Parser p(payload, file);
    std::string fingerprint(p.GetCount(1), '\0');
    p.GetBytes(fingerprint.data(), fingerprint.size());
    if (fingerprint != DatabaseFingerprint(config)) {
        throw DatasetError(file, "closure database was built with a different configuration: file has [" + fingerprint +
                                     "], current is [" + DatabaseFingerprint(config) + "]");
    }
    ClosureDetector detector(config);
    const std::uint32_t num_maps = p.GetCount(1);
    for (std::uint32_t i = 0; i < num_maps; ++i) {
        MapRecord r;
        r.id = p.Get<std::int32_t>();
        r.session = p.Get<std::int32_t>();
        r.scans.first = p.Get<std::uint64_t>();
        r.scans.last = p.Get<std::uint64_t>();
        r.travel_start = p.Get<double>();
        r.travel_end = p.Get<double>();
        r.T_world_map.matrix() = p.GetMatrix();
        r.T_ground_map.matrix() = p.GetMatrix();
        r.origin.x() = p.Get<double>();
        r.origin.y() = p.Get<double>();
        r.resolution = p.Get<double>();
        r.rows = p.Get<std::int32_t>();
        r.cols = p.Get<std::int32_t>();
        const std::uint32_t num_keypoints = p.GetCount(sizeof(float) * 2 + sizeof(Descriptor));
        r.keypoints.resize(num_keypoints);
        for (auto& k : r.keypoints) p.GetBytes(k.data(), sizeof(float) * 2);
        std::vector<Descriptor> descriptors(num_keypoints);
        for (auto& d : descriptors) p.GetBytes(d.data(), sizeof(Descriptor));
        r.image_png.resize(p.GetCount(1));
        p.GetBytes(r.image_png.data(), r.image_png.size());
        if (r.session < 0 || !(r.resolution > 0.0)) throw DatasetError(file, "corrupt closure database (map record)");
        if (!r.image_png.empty()) {
            // The image is decoded later (matching, report pictures): its declared size is checked now.
            const PngSize png = ReadPngSize(r.image_png.data(), r.image_png.size(), file);
            CheckPngSize(png, config.density.max_image_side, file);
            if (int(png.width) != r.cols || int(png.height) != r.rows) {
                throw DatasetError(file, "corrupt closure database (map " + std::to_string(r.id) + ": image size differs from its record)");
            }
        }
        detector.Restore(std::move(r), descriptors);
    }
    if (!p.AtEnd()) throw DatasetError(file, "corrupt closure database (trailing bytes in payload)");
    if (num_maps > 0) detector.StartSession();
    return detector;
}

}  // namespace revisit
