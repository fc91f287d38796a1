#pragma once
// A ROS 1 bag's structure checked before rosbag reads it, and a message's serialised layout before
// roscpp deserialises it. rosbag and roscpp believe the lengths a file announces: a record header
// of 4 GB is allocated as such, a LaserScan announcing 10⁹ ranges is resized to them before the
// bytes are looked for. Here every length is bounded by the bytes that hold it, so that a damaged
// or hostile bag is refused with the byte offset and what was expected (docs/FUZZING.md).
// Private to io/ros_bag_source.cpp; free of rosbag's headers.

#include <cstddef>
#include <cstdint>
#include <string>

namespace scanloc::bag {

// The largest chunk a bag may announce, uncompressed (rosbag's default chunks are 768 KiB).
inline constexpr std::uint32_t kMaxChunkBytes = 256u << 20;

// Walks the whole bag (format 2.0): the records at the top level, the records inside every chunk
// (decompressed when bz2 or lz4), the connections and chunk infos at the index position, and the
// index entries; throws std::runtime_error("ROS bag PATH: at byte N: expected ...") at the first
// thing rosbag would misread.
void CheckBagStructure(const std::string& path);

// The serialised layouts of the messages scanloc reads; each throws std::runtime_error saying
// what does not fit in `size` bytes.
void CheckLaserScanBytes(const std::uint8_t* data, std::size_t size);
void CheckOdometryBytes(const std::uint8_t* data, std::size_t size);
void CheckTfMessageBytes(const std::uint8_t* data, std::size_t size);

}  // namespace scanloc::bag
