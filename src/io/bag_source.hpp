#pragma once
/// What the ROS bag reader (io/bag_reader.hpp) needs from a container format: its topics and passes
/// over their raw messages in recording order. MCAP, rosbag2 sqlite3 and ROS 1 bags implement it.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "io/reader.hpp"
#include "io/ros_wire.hpp"

namespace revisit {

struct BagTopic {
    std::string name;
    std::string type;  ///< as the file names it: "sensor_msgs/msg/PointCloud2" or "sensor_msgs/PointCloud2"
    RosWire wire = RosWire::kCdr;
    std::size_t count = 0;                   ///< messages
    std::int64_t first_ns = 0, last_ns = 0;  ///< [ns] receive (log) times
};

struct BagMessage {
    std::size_t topic = 0;  ///< index into Topics()
    std::int64_t log_time_ns = 0;
    const std::uint8_t* data = nullptr;  ///< valid until the next Next()
    std::size_t size = 0;
    std::uint64_t position = 0;  ///< where it is, for Where(): a byte offset or a row id
    std::uint64_t inner = ~0ull;  ///< MCAP: the byte inside the chunk at `position` (~0: not in a chunk)
};

class BagSource {
  public:
    virtual ~BagSource() = default;
    virtual std::string Format() const = 0;
    /// The topics met so far, with their message counts: complete after the first whole pass
    /// (MCAP declares channels as it goes; the other formats list them up front).
    virtual const std::vector<BagTopic>& Topics() const = 0;
    /// Begins a pass over the messages of the topics `wanted` accepts (by index into Topics()), in
    /// recording order.
    virtual void Start(std::function<bool(std::size_t topic)> wanted) = 0;
    /// The next message of the pass; false at the end. Damage throws DatasetError naming the place.
    virtual bool Next(BagMessage& message) = 0;
    /// Where a message is, for error messages: "byte offset N", "row N".
    virtual std::string Where(const BagMessage& message) const = 0;
};

/// The bag reader over a source: scans from the points topic, the odometry prior and the reference
/// poses paired by stamp (io/bag_poses.hpp), topics chosen from `options` or automatically.
std::unique_ptr<Reader> OpenBag(std::unique_ptr<BagSource> source, const std::filesystem::path& path,
                                const ReaderOptions& options);

/// The formats: an .mcap file, a rosbag2 folder (metadata.yaml + .db3 files), a ROS 1 .bag file.
std::unique_ptr<BagSource> OpenMcapSource(const std::filesystem::path& file, const ReaderOptions& options);
std::unique_ptr<BagSource> OpenDb3Source(const std::filesystem::path& folder);
std::unique_ptr<BagSource> OpenRos1Source(const std::filesystem::path& file);
/// A folder holding metadata.yaml and at least one .db3 file.
bool IsRosbag2Folder(const std::filesystem::path& folder);

}  // namespace revisit
