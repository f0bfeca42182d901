#include "runfolder/planar_scans.hpp"

#include <fstream>

#include <cstdint>
#include <cstring>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"

namespace revisit {
namespace fs = std::filesystem;

namespace {

// Layout (little-endian): "RVPS" u32 version, u32 scan count; per scan: u64 position, u32 point count,
// then count x (f32 x, f32 y).
constexpr char kMagic[4] = {'R', 'V', 'P', 'S'};
constexpr std::uint32_t kVersion = 1;

template <typename T>
void Put(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

/// Reads from a byte buffer, naming the offset of whatever is cut short.
class ByteReader {
  public:
    ByteReader(const fs::path& file, const std::string& bytes) : file_(file), bytes_(bytes) {}
    template <typename T>
    T Get(const char* what) {
        Need(sizeof(T), what);
        T value;
        std::memcpy(&value, bytes_.data() + offset_, sizeof(T));
        offset_ += sizeof(T);
        return value;
    }
    void Need(std::size_t size, const char* what) const {
        if (bytes_.size() - offset_ < size) {
            throw DatasetError(file_, std::string("cut short at byte ") + std::to_string(offset_) + ": " + what + " needs " +
                                          std::to_string(size) + " bytes, " + std::to_string(bytes_.size() - offset_) + " left");
        }
    }
    std::size_t offset() const { return offset_; }
    bool done() const { return offset_ == bytes_.size(); }

  private:
    const fs::path& file_;
    const std::string& bytes_;
    std::size_t offset_ = 0;
};

}  // namespace

fs::path PlanarScansFile(const RunFolder& run, int map_id) {
    std::ostringstream name;
    name << "scans_" << std::setw(4) << std::setfill('0') << map_id << ".bin";
    return run.maps_dir() / name.str();
}

void PlanarScanWriter::Add(int map_id, std::size_t position, const std::vector<Eigen::Vector3f>& points_in_sensor) {
    if (map_id != map_id_) {
        Flush();
        map_id_ = map_id;
    }
    PlanarScan scan;
    scan.position = position;
    scan.points_in_sensor.reserve(points_in_sensor.size());
    for (const auto& p : points_in_sensor) scan.points_in_sensor.emplace_back(p.x(), p.y());
    scans_.push_back(std::move(scan));
}

void PlanarScanWriter::Finish() { Flush(); }

void PlanarScanWriter::Flush() {
    if (map_id_ < 0 || scans_.empty()) return;
    std::string bytes(kMagic, sizeof(kMagic));
    Put<std::uint32_t>(bytes, kVersion);
    Put<std::uint32_t>(bytes, static_cast<std::uint32_t>(scans_.size()));
    for (const auto& scan : scans_) {
        Put<std::uint64_t>(bytes, scan.position);
        Put<std::uint32_t>(bytes, static_cast<std::uint32_t>(scan.points_in_sensor.size()));
        for (const auto& p : scan.points_in_sensor) {
            Put<float>(bytes, p.x());
            Put<float>(bytes, p.y());
        }
    }
    WriteFileAtomically(PlanarScansFile(run_, map_id_), bytes);
    scans_.clear();
}

std::vector<PlanarScan> ReadPlanarScans(const RunFolder& run, int map_id) {
    const fs::path file = PlanarScansFile(run, map_id);
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(file, ec))) return {};
    std::ifstream in = OpenForReading(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ByteReader reader(file, bytes);
    reader.Need(sizeof(kMagic), "the header");
    if (std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) throw DatasetError(file, "not a revisit scans file (no RVPS header)");
    reader.Get<std::uint32_t>("the header");
    if (const auto version = reader.Get<std::uint32_t>("the version"); version != kVersion) {
        throw DatasetError(file, "version " + std::to_string(version) + ", this revisit reads version " + std::to_string(kVersion));
    }
    const auto count = reader.Get<std::uint32_t>("the scan count");
    std::vector<PlanarScan> scans;
    // Each scan takes at least 12 bytes: a count beyond what the file holds is damage, not a reason to allocate.
    reader.Need(std::size_t(count) * 12, "the scans counted in the header");
    scans.reserve(count);
    for (std::uint32_t s = 0; s < count; ++s) {
        PlanarScan scan;
        scan.position = reader.Get<std::uint64_t>("a scan's position");
        const auto points = reader.Get<std::uint32_t>("a scan's point count");
        reader.Need(std::size_t(points) * 8, "a scan's points");
        scan.points_in_sensor.resize(points);
        for (auto& p : scan.points_in_sensor) {
            p.x() = reader.Get<float>("a point");
            p.y() = reader.Get<float>("a point");
        }
        scans.push_back(std::move(scan));
    }
    if (!reader.done()) throw DatasetError(file, std::to_string(bytes.size() - reader.offset()) + " bytes after the last scan at byte " + std::to_string(reader.offset()));
    return scans;
}

}  // namespace revisit
