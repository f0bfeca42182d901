#pragma once
/// The ROS messages revisit reads, decoded from either wire format (io/ros_wire.hpp): the layouts of
/// sensor_msgs, nav_msgs, geometry_msgs and tf2_msgs are the same in ROS 1 and ROS 2 apart from the
/// header's seq and the encoding itself.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "io/ros_wire.hpp"

namespace revisit {

/// "sensor_msgs/msg/PointCloud2" (ROS 2) and "sensor_msgs/PointCloud2" (ROS 1) alike: "sensor_msgs/PointCloud2".
std::string RosTypeName(const std::string& type);

struct PointFieldMsg {
    std::string name;
    std::uint32_t offset = 0;   ///< [bytes] from the start of the point
    std::uint8_t datatype = 0;  ///< 1 INT8, 2 UINT8, 3 INT16, 4 UINT16, 5 INT32, 6 UINT32, 7 FLOAT32, 8 FLOAT64
    std::uint32_t count = 0;
};

struct PointCloud2Msg {
    std::int64_t stamp_ns = 0;
    std::string frame_id;
    std::uint32_t height = 0, width = 0;
    std::vector<PointFieldMsg> fields;
    bool is_bigendian = false;
    std::uint32_t point_step = 0, row_step = 0;  ///< [bytes]
    const std::uint8_t* data = nullptr;          ///< into the message bytes
    std::size_t data_size = 0;
};

struct LaserScanMsg {
    std::int64_t stamp_ns = 0;
    std::string frame_id;
    float angle_min = 0, angle_max = 0, angle_increment = 0;  ///< [rad]
    float range_min = 0, range_max = 0;                       ///< [m]
    std::vector<float> ranges;                                ///< [m]
};

/// A stamped pose or transform: T_frame_child (child_frame_id empty for PoseStamped).
struct PoseMsg {
    std::int64_t stamp_ns = 0;
    std::string frame_id, child_frame_id;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
};

/// Each throws WireError on a message the bytes cannot hold.
PointCloud2Msg DecodePointCloud2(const std::uint8_t* data, std::size_t size, RosWire wire);
LaserScanMsg DecodeLaserScan(const std::uint8_t* data, std::size_t size, RosWire wire);
PoseMsg DecodeOdometry(const std::uint8_t* data, std::size_t size, RosWire wire);  ///< pose only
PoseMsg DecodePoseStamped(const std::uint8_t* data, std::size_t size, RosWire wire);
std::vector<PoseMsg> DecodePath(const std::uint8_t* data, std::size_t size, RosWire wire);
std::vector<PoseMsg> DecodeTfMessage(const std::uint8_t* data, std::size_t size, RosWire wire);

}  // namespace revisit
