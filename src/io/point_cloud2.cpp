#include "io/point_cloud2.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace revisit {
namespace {

constexpr std::uint8_t kFloat32 = 7, kFloat64 = 8;

std::size_t DatatypeSize(std::uint8_t datatype) {
    static constexpr std::size_t kSizes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
    return datatype <= 8 ? kSizes[datatype] : 0;
}

template <typename T>
T Load(const std::uint8_t* p, bool swap) {
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, p, sizeof(T));
    if (swap) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

double Value(const std::uint8_t* p, std::uint8_t datatype, bool swap) {
    switch (datatype) {
        case 1: return Load<std::int8_t>(p, swap);
        case 2: return Load<std::uint8_t>(p, swap);
        case 3: return Load<std::int16_t>(p, swap);
        case 4: return Load<std::uint16_t>(p, swap);
        case 5: return Load<std::int32_t>(p, swap);
        case 6: return Load<std::uint32_t>(p, swap);
        case 7: return Load<float>(p, swap);
        default: return Load<double>(p, swap);
    }
}

bool HostIsBigEndian() {
    const std::uint16_t one = 1;
    std::uint8_t first;
    std::memcpy(&first, &one, 1);
    return first == 0;
}

const PointFieldMsg* FindField(const PointCloud2Msg& msg, std::initializer_list<const char*> names) {
    for (const char* name : names) {
        for (const auto& field : msg.fields) {
            if (field.name == name) return &field;
        }
    }
    return nullptr;
}

/// Seconds per unit of a time field, from its type and the span of its values (see the header).
double TimeScale(std::uint8_t datatype, double span) {
    if (datatype == kFloat32 || datatype == kFloat64) return 1.0;
    return span >= 1e3 && span < 1e6 ? 1e-6 : 1e-9;
}

}  // namespace

CloudData PointsFromCloud2(const PointCloud2Msg& msg) {
    const PointFieldMsg* x = FindField(msg, {"x"});
    const PointFieldMsg* y = FindField(msg, {"y"});
    const PointFieldMsg* z = FindField(msg, {"z"});
    if (!x || !y || !z) throw WireError("PointCloud2 without x, y and z fields");
    const PointFieldMsg* intensity = FindField(msg, {"intensity", "i", "reflectance"});
    const PointFieldMsg* time = FindField(msg, {"t", "time", "timestamp", "offset_time"});
    for (const PointFieldMsg* f : {x, y, z, intensity, time}) {
        if (!f) continue;
        const std::size_t size = DatatypeSize(f->datatype);
        if (size == 0) throw WireError("PointCloud2 field '" + f->name + "' has unknown datatype " + std::to_string(f->datatype));
        if (std::uint64_t(f->offset) + size > msg.point_step) {
            throw WireError("PointCloud2 field '" + f->name + "' at offset " + std::to_string(f->offset) +
                            " does not fit point_step " + std::to_string(msg.point_step));
        }
    }
    for (const PointFieldMsg* f : {x, y, z}) {
        if (f->datatype != kFloat32 && f->datatype != kFloat64) throw WireError("PointCloud2 field '" + f->name + "' is not float32/float64");
    }
    const std::uint64_t row_bytes = std::uint64_t(msg.width) * msg.point_step;
    if (msg.height > 0 && msg.width > 0 &&
        (msg.row_step < row_bytes || std::uint64_t(msg.height - 1) * msg.row_step + row_bytes > msg.data_size)) {
        throw WireError("PointCloud2 of " + std::to_string(msg.height) + " x " + std::to_string(msg.width) +
                        " points of " + std::to_string(msg.point_step) + " bytes (row_step " + std::to_string(msg.row_step) +
                        ") does not fit its " + std::to_string(msg.data_size) + " data bytes");
    }
    const bool swap = msg.is_bigendian != HostIsBigEndian();
    const std::size_t n = std::size_t(msg.height) * msg.width;
    CloudData cloud;
    cloud.has_intensity = intensity != nullptr;
    cloud.has_time = time != nullptr;
    cloud.points.reserve(n);
    if (intensity) cloud.intensities.reserve(n);
    std::vector<double> times;
    if (time) times.reserve(n);
    const bool fast_xyz = !swap && x->datatype == kFloat32 && y->datatype == kFloat32 && z->datatype == kFloat32;
    // A cloud of no columns has no points whatever its rows claim (found by fuzz_db3: 4e9 empty rows).
    for (std::uint32_t row = 0; msg.width > 0 && row < msg.height; ++row) {
        const std::uint8_t* p = msg.data + std::size_t(row) * msg.row_step;
        for (std::uint32_t col = 0; col < msg.width; ++col, p += msg.point_step) {
            Eigen::Vector3f point;
            if (fast_xyz) {
                std::memcpy(&point[0], p + x->offset, 4);
                std::memcpy(&point[1], p + y->offset, 4);
                std::memcpy(&point[2], p + z->offset, 4);
            } else {
                point = Eigen::Vector3f(float(Value(p + x->offset, x->datatype, swap)), float(Value(p + y->offset, y->datatype, swap)),
                                        float(Value(p + z->offset, z->datatype, swap)));
            }
            if (!point.allFinite()) {
                cloud.non_finite++;
                continue;
            }
            cloud.points.push_back(point);
            if (intensity) {
                float value;
                if (!swap && intensity->datatype == kFloat32) {
                    std::memcpy(&value, p + intensity->offset, 4);
                } else {
                    value = float(Value(p + intensity->offset, intensity->datatype, swap));
                }
                cloud.intensities.push_back(value);
            }
            if (time) times.push_back(Value(p + time->offset, time->datatype, swap));
        }
    }
    if (time && !times.empty()) {
        const auto [lo, hi] = std::minmax_element(times.begin(), times.end());
        const double scale = TimeScale(time->datatype, *hi - *lo);
        // Absolute (epoch) times: relative to the stamp, subtracted in the field's own unit.
        const double offset = std::abs(*lo * scale) > 1e8 ? double(msg.stamp_ns) * 1e-9 / scale : 0.0;
        cloud.point_times.resize(times.size());
        for (std::size_t i = 0; i < times.size(); ++i) cloud.point_times[i] = float((times[i] - offset) * scale);
    }
    return cloud;
}

Scan ScanFromLaserScan(const LaserScanMsg& msg, double aperture, std::size_t& non_finite) {
    Scan scan;
    const std::size_t n = msg.ranges.size();
    const double increment = msg.angle_increment;
    const double stated = n > 1 ? std::abs(increment) * double(n - 1) : 0.0;
    const double used = aperture > 0.0 ? aperture : stated;
    const double middle = double(msg.angle_min) + increment * double(n > 0 ? n - 1 : 0) / 2.0;
    const double step = n > 1 ? used / double(n - 1) : 0.0;
    PlanarBeams beams;
    beams.ranges.assign(n, 0.f);
    beams.aperture = used;
    beams.stated_aperture = stated;
    for (std::size_t k = 0; k < n; ++k) {
        // Beams in order of increasing angle, whatever the sign of angle_increment.
        const std::size_t i = increment < 0 ? n - 1 - k : k;
        const float range = msg.ranges[i];
        if (!std::isfinite(range) || range < msg.range_min || range > msg.range_max) {
            if (std::isnan(range)) non_finite++;
            continue;
        }
        beams.ranges[k] = range;
        const double angle = middle - used / 2.0 + step * double(k);
        scan.points.emplace_back(float(range * std::cos(angle)), float(range * std::sin(angle)), 0.f);
    }
    scan.planar_beams = std::move(beams);
    return scan;
}

}  // namespace revisit
