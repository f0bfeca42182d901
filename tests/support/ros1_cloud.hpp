#pragma once
/// A sensor_msgs/PointCloud2 of float32 fields, for the ROS 1 bags the tests and the fuzzer's seeds
/// write with rosbag.
#include <sensor_msgs/PointCloud2.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace revisit::test {

/// One row of points, each `fields.size()` float32 values in `values` (x, y, z, ...: datatype 7).
inline sensor_msgs::PointCloud2 Ros1Cloud(const ros::Time& stamp, const std::string& frame_id, const std::vector<std::string>& fields,
                                          const std::vector<float>& values) {
    sensor_msgs::PointCloud2 cloud;
    cloud.header.stamp = stamp;
    cloud.header.frame_id = frame_id;
    cloud.height = 1;
    cloud.point_step = 4 * std::uint32_t(fields.size());
    cloud.width = std::uint32_t(values.size() / fields.size());
    cloud.row_step = cloud.point_step * cloud.width;
    for (const std::string& name : fields) {
        sensor_msgs::PointField field;
        field.name = name, field.offset = 4 * std::uint32_t(cloud.fields.size()), field.datatype = 7, field.count = 1;
        cloud.fields.push_back(field);
    }
    cloud.data.resize(4 * values.size());
    std::memcpy(cloud.data.data(), values.data(), cloud.data.size());
    return cloud;
}

}  // namespace revisit::test
