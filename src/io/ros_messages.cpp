#include "io/ros_messages.hpp"

#include <cmath>

namespace revisit {
namespace {

/// geometry_msgs Point/Vector3 then Quaternion (x, y, z, w): the same layout for Pose and Transform.
Eigen::Isometry3d ReadPose(WireReader& in) {
    Eigen::Vector3d t;
    for (int i = 0; i < 3; ++i) t[i] = in.F64();
    double q[4];
    for (double& v : q) v = in.F64();
    const Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);
    const double norm = rotation.norm();
    if (!t.allFinite() || !std::isfinite(norm) || std::abs(norm - 1.0) > 1e-2) {
        throw WireError("pose with a non-finite position or a quaternion of norm " + std::to_string(norm) +
                        " (ends at message byte " + std::to_string(in.offset()) + ")");
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = rotation.normalized().toRotationMatrix();
    T.translation() = t;
    return T;
}

PoseMsg ReadPoseStamped(WireReader& in) {
    PoseMsg pose;
    pose.stamp_ns = in.Header(pose.frame_id);
    pose.T = ReadPose(in);
    return pose;
}

}  // namespace

std::string RosTypeName(const std::string& type) {
    const auto at = type.find("/msg/");
    return at == std::string::npos ? type : type.substr(0, at) + "/" + type.substr(at + 5);
}

PointCloud2Msg DecodePointCloud2(const std::uint8_t* data, std::size_t size, RosWire wire) {
    WireReader in(data, size, wire);
    PointCloud2Msg msg;
    msg.stamp_ns = in.Header(msg.frame_id);
    msg.height = in.U32();
    msg.width = in.U32();
    // A field is at least a name length, offset, datatype and count.
    msg.fields.resize(in.Length(13));
    for (auto& field : msg.fields) {
        field.name = in.String();
        field.offset = in.U32();
        field.datatype = in.U8();
        field.count = in.U32();
    }
    msg.is_bigendian = in.U8() != 0;
    msg.point_step = in.U32();
    msg.row_step = in.U32();
    msg.data_size = in.Length(1);
    msg.data = in.Bytes(msg.data_size);
    return msg;
}

LaserScanMsg DecodeLaserScan(const std::uint8_t* data, std::size_t size, RosWire wire) {
    WireReader in(data, size, wire);
    LaserScanMsg msg;
    msg.stamp_ns = in.Header(msg.frame_id);
    msg.angle_min = in.F32();
    msg.angle_max = in.F32();
    msg.angle_increment = in.F32();
    in.F32();  // time_increment
    in.F32();  // scan_time
    msg.range_min = in.F32();
    msg.range_max = in.F32();
    msg.ranges.resize(in.Length(4));
    for (float& r : msg.ranges) r = in.F32();
    return msg;
}

PoseMsg DecodeOdometry(const std::uint8_t* data, std::size_t size, RosWire wire) {
    WireReader in(data, size, wire);
    PoseMsg pose;
    pose.stamp_ns = in.Header(pose.frame_id);
    pose.child_frame_id = in.String();
    pose.T = ReadPose(in);
    return pose;
}

PoseMsg DecodePoseStamped(const std::uint8_t* data, std::size_t size, RosWire wire) {
    WireReader in(data, size, wire);
    return ReadPoseStamped(in);
}

std::vector<PoseMsg> DecodePath(const std::uint8_t* data, std::size_t size, RosWire wire) {
    WireReader in(data, size, wire);
    std::string frame_id;
    const std::int64_t stamp_ns = in.Header(frame_id);
    // A PoseStamped is at least a stamp, a frame_id length and 7 float64.
    std::vector<PoseMsg> poses(in.Length(8 + 4 + 56));
    for (auto& pose : poses) {
        pose = ReadPoseStamped(in);
        if (pose.stamp_ns == 0) pose.stamp_ns = stamp_ns;
        if (pose.frame_id.empty()) pose.frame_id = frame_id;
    }
    return poses;
}

std::vector<PoseMsg> DecodeTfMessage(const std::uint8_t* data, std::size_t size, RosWire wire) {
    WireReader in(data, size, wire);
    std::vector<PoseMsg> transforms(in.Length(8 + 4 + 4 + 56));
    for (auto& transform : transforms) {
        transform.stamp_ns = in.Header(transform.frame_id);
        transform.child_frame_id = in.String();
        transform.T = ReadPose(in);
    }
    return transforms;
}

}  // namespace revisit
