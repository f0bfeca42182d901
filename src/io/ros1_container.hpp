#pragma once
/// The container of a ROS 1 bag (format 2.0, http://wiki.ros.org/Bags/Format/2.0) checked before
/// Debian's rosbag_storage reads it.
#include <filesystem>

namespace revisit {

/// rosbag_storage trusts every length and offset in a bag: it allocates what a header length says,
/// copies what a field length says and reads a message wherever an index entry points inside a
/// chunk, without a bound (a damaged bag crashes it). This walks the whole container once: every
/// record and header field inside the file, every chunk decompressed (none, bz2, lz4) to exactly its
/// declared size with every record inside it, every index entry pointing at a message record of
/// its chunk, and the index section (connections, chunk infos) where the bag header says. Throws
/// DatasetError naming the byte offset of the first damage found.
void CheckRos1Container(const std::filesystem::path& file);

}  // namespace revisit
