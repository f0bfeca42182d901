#include "io/helipr.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "core/error.hpp"
#include "io/stamped_layout.hpp"

namespace revisit {
namespace fs = std::filesystem;
namespace {

/// The published Aeva files after this stamp [ns] carry a float32 intensity after line_index.
constexpr std::uint64_t kAevaIntensitySince = 1691936557946849179ull;

/// A sensor's packed point: its size, where x, y, z (float32) and the intensity and time fields are.
struct PointLayout {
    const char* sensor;
    std::size_t bytes;
    const char* fields;
    int intensity_at;         ///< byte offset of the intensity, -1: none
    bool intensity_is_u8;     ///< uint8 (Livox reflectivity) instead of float32
    int time_at;              ///< byte offset of the per-point time
    char time_type;           ///< 'u' uint32 ns, 'i' int32 ns, 'f' float32 s
};

constexpr PointLayout kOuster{"Ouster", 26, "float32 x, y, z, intensity, uint32 t [ns], uint16 reflectivity, ring, ambient", 12, false, 16, 'u'};
constexpr PointLayout kVelodyne{"Velodyne", 22, "float32 x, y, z, intensity, uint16 ring, float32 time [s]", 12, false, 18, 'f'};
constexpr PointLayout kAvia{"Avia", 19, "float32 x, y, z, uint8 reflectivity, tag, line, uint32 offset_time [ns]", 12, true, 15, 'u'};
constexpr PointLayout kAeva{"Aeva", 29, "float32 x, y, z, reflectivity, velocity, int32 time_offset_ns, uint8 line_index, float32 intensity", 25, false, 20, 'i'};
constexpr PointLayout kAevaEarly{"Aeva", 25, "float32 x, y, z, reflectivity, velocity, int32 time_offset_ns, uint8 line_index", 12, false, 20, 'i'};
constexpr const PointLayout* kSensors[] = {&kOuster, &kVelodyne, &kAvia, &kAeva};

const PointLayout& LayoutOf(const fs::path& file, const std::string& sensor) {
    if (sensor == "Aeva") {
        const auto stamp = DigitStamp(file.stem().string(), 1);
        return stamp && *stamp <= kAevaIntensitySince ? kAevaEarly : kAeva;
    }
    for (const PointLayout* layout : kSensors) {
        if (sensor == layout->sensor) return *layout;
    }
    throw DatasetError(file, "unknown HeLiPR sensor '" + sensor + "' (Ouster, Velodyne, Avia or Aeva)");
}

template <typename T>
T Field(const char* record, int offset) {
    T value;
    std::memcpy(&value, record + offset, sizeof value);  // little-endian, as the host
    return value;
}

CloudData LoadOuster(const fs::path& file) { return LoadHeLiPRBin(file, "Ouster"); }
CloudData LoadVelodyne(const fs::path& file) { return LoadHeLiPRBin(file, "Velodyne"); }
CloudData LoadAvia(const fs::path& file) { return LoadHeLiPRBin(file, "Avia"); }
CloudData LoadAeva(const fs::path& file) { return LoadHeLiPRBin(file, "Aeva"); }

/// ns x y z qx qy qz qw, space-separated, in a global frame: moved so the first position is the origin.
Trajectory ReadHeLiPRGroundTruth(const fs::path& file) {
    PoseTable table;
    table.lines = {8, "HeLiPR ground truth (ns x y z qx qy qz qw)"};
    table.move_to_first_position = true;
    table.to_pose = [&file](const std::vector<double>& v, std::size_t line) {
        const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);
        return std::make_pair(v[0] * 1e-9, CleanPose(q, Eigen::Vector3d(v[1], v[2], v[3]), file, line));
    };
    return ReadPoseTable(file, table);
}

/// The sequence root and the sensor a path names: ROOT itself, or one of its LiDAR/<sensor> folders.
std::pair<fs::path, std::string> RootAndFolder(const fs::path& path) {
    const fs::path trimmed = path.filename().empty() ? path.parent_path() : path;
    if (trimmed.parent_path().filename() == "LiDAR") {
        for (const PointLayout* layout : kSensors) {
            if (trimmed.filename() == layout->sensor) return {trimmed.parent_path().parent_path(), layout->sensor};
        }
    }
    return {path, {}};
}

std::string ChosenSensor(const fs::path& root, const std::string& wanted) {
    std::string lower = wanted;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    std::string present;
    for (const PointLayout* layout : kSensors) {
        std::string name = layout->sensor;
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
        const bool here = fs::is_directory(root / "LiDAR" / layout->sensor);
        if (here) present += std::string(present.empty() ? "" : ", ") + layout->sensor;
        if (here && (lower.empty() || lower == name)) return layout->sensor;
    }
    throw DatasetError(root / "LiDAR", "no LiDAR/" + (wanted.empty() ? std::string("<sensor>") : wanted) +
                                           " folder; the sensors here: " + (present.empty() ? "none" : present) +
                                           " (choose one with --sensor)");
}

/// Each sensor folder as `revisit info` lists a recording's streams: its record layout, file count,
/// rate from the stamps of the names, and whether it is the one read.
std::vector<TopicSummary> SensorFolders(const fs::path& root, const std::string& chosen) {
    std::vector<TopicSummary> folders;
    for (const PointLayout* layout : kSensors) {
        const fs::path folder = root / "LiDAR" / layout->sensor;
        std::error_code ec;
        if (!fs::is_directory(folder, ec)) continue;
        TopicSummary summary;
        summary.name = "LiDAR/" + std::string(layout->sensor);
        summary.type = (layout == &kAeva ? std::string("25/29") : std::to_string(layout->bytes)) + "-byte " + layout->sensor + " points";
        std::uint64_t first = UINT64_MAX, last = 0;
        for (const auto& entry : fs::directory_iterator(folder, ec)) {
            const auto stamp = entry.path().extension() == ".bin" ? DigitStamp(entry.path().stem().string(), 1) : std::nullopt;
            if (!stamp) continue;
            ++summary.messages;
            first = std::min(first, *stamp);
            last = std::max(last, *stamp);
        }
        if (summary.messages > 1 && last > first) summary.rate_hz = static_cast<double>(summary.messages - 1) / ((last - first) * 1e-9);
        summary.role = layout->sensor == chosen ? "points" : "unused (--sensor " + std::string(layout->sensor) + ")";
        folders.push_back(std::move(summary));
    }
    return folders;
}

}  // namespace

bool IsHeLiPRFolder(const fs::path& given) {
    const fs::path path = RootAndFolder(given).first;
    return std::any_of(std::begin(kSensors), std::end(kSensors),
                       [&path](const PointLayout* layout) { return HasFileWithExtension(path / "LiDAR" / layout->sensor, ".bin"); });
}

CloudData LoadHeLiPRBin(const fs::path& file, const std::string& sensor) {
    const PointLayout& layout = LayoutOf(file, sensor);
    const std::string data = ReadPointRecords(file, layout.bytes, std::string("HeLiPR ") + layout.sensor + ": " + layout.fields);
    const std::size_t n = data.size() / layout.bytes;
    CloudData cloud;
    cloud.has_intensity = layout.intensity_at >= 0;
    cloud.has_time = true;
    cloud.points.reserve(n);
    if (cloud.has_intensity) cloud.intensities.reserve(n);
    cloud.point_times.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
        const char* record = data.data() + i * layout.bytes;
        const float intensity = layout.intensity_at < 0 ? 0.f
                                : layout.intensity_is_u8 ? static_cast<float>(Field<std::uint8_t>(record, layout.intensity_at))
                                                         : Field<float>(record, layout.intensity_at);
        const float time = layout.time_type == 'f' ? Field<float>(record, layout.time_at)
                           : layout.time_type == 'i' ? static_cast<float>(Field<std::int32_t>(record, layout.time_at) * 1e-9)
                                                     : static_cast<float>(Field<std::uint32_t>(record, layout.time_at) * 1e-9);
        cloud.Add(Field<float>(record, 0), Field<float>(record, 4), Field<float>(record, 8), intensity, time);
    }
    return cloud;
}

std::unique_ptr<Reader> OpenHeLiPR(const fs::path& given, const ReaderOptions& options) {
    const auto [path, folder] = RootAndFolder(given);
    if (!folder.empty() && !options.sensor_label.empty() && ChosenSensor(path, options.sensor_label) != folder) {
        throw DatasetError(given, "this is the " + folder + " folder, but --sensor asks for " + options.sensor_label);
    }
    const std::string sensor = folder.empty() ? ChosenSensor(path, options.sensor_label) : folder;
    std::string label = sensor;
    std::transform(label.begin(), label.end(), label.begin(), [](unsigned char c) { return std::toupper(c); });
    fs::path reference;
    for (const fs::path& candidate : {path / "LiDAR_GT" / (sensor + "_gt.txt"), path / "LiDAR_GT" / ("global_" + sensor + "_gt.txt"),
                                      path / (sensor + "_gt.txt")}) {
        if (fs::is_regular_file(candidate)) {
            reference = candidate;
            break;
        }
    }
    const CloudLoader loader = sensor == "Ouster"     ? &LoadOuster
                               : sensor == "Velodyne" ? &LoadVelodyne
                               : sensor == "Avia"     ? &LoadAvia
                                                      : &LoadAeva;
    return OpenStampedLayout({"helipr", given,
                              ListStampedFiles(path / "LiDAR" / sensor, ".bin", &NanosecondStem, kNanosecondNames),
                              loader, label, reference, &ReadHeLiPRGroundTruth, SensorFolders(path, sensor)},
                             options);
}

}  // namespace revisit
