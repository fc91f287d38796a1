#include "ros_bag_structure.hpp"

#include <bzlib.h>
#include <roslz4/lz4s.h>

#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace scanloc::bag {
namespace {

// Record ops of the bag format 2.0.
constexpr std::uint8_t kMessageData = 2, kBagHeader = 3, kIndexData = 4, kChunk = 5,
                       kChunkInfo = 6, kConnection = 7;
constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::uint32_t kMaxHeaderBytes = 1u << 20;  // a record header holds a few short fields

// Bytes to walk: the file, or a chunk decompressed in memory; `base` is where they start in the
// file (for the messages), `inner` says which.
class Bytes {
 public:
  Bytes(std::ifstream& file, std::uint64_t size) : file_(&file), size_(size) {}
  explicit Bytes(std::vector<char> memory) : memory_(std::move(memory)), size_(memory_.size()) {}
  std::uint64_t size() const { return size_; }
  void Read(std::uint64_t offset, void* out, std::uint64_t n) const {
    if (file_ == nullptr) {
      std::memcpy(out, memory_.data() + offset, n);
      return;
    }
    file_->seekg(static_cast<std::streamoff>(offset));
    file_->read(static_cast<char*>(out), static_cast<std::streamsize>(n));
    if (!*file_) throw std::runtime_error("read error");
  }

 private:
  std::ifstream* file_ = nullptr;
  std::vector<char> memory_;
  std::uint64_t size_;
};

struct Record {
  std::uint64_t offset = 0;  // of its header length
  std::uint8_t op = 0;
  std::map<std::string, std::string> fields;
  std::uint64_t data_offset = 0;
  std::uint32_t data_len = 0;
  std::uint64_t end() const { return data_offset + data_len; }
};

[[noreturn]] void Fail(const std::string& where, std::uint64_t offset, const std::string& what) {
  throw std::runtime_error(where + ": at byte " + std::to_string(offset) + ": expected " + what);
}

std::uint32_t U32(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, 4);  // little-endian, as the format and this machine
  return v;
}

std::uint64_t U64(const char* p) {
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  return v;
}

// `name=value` fields packed as (length, bytes) pairs, the whole of `text`.
std::map<std::string, std::string> Fields(const std::string& text, const std::string& where,
                                          std::uint64_t offset) {
  std::map<std::string, std::string> fields;
  for (std::size_t at = 0; at < text.size();) {
    if (text.size() - at < 4) Fail(where, offset + at, "a field length");
    const std::uint32_t len = U32(text.data() + at);
    at += 4;
    if (len > text.size() - at) Fail(where, offset + at, "a field within its header");
    const std::string field = text.substr(at, len);
    const std::size_t equals = field.find('=');
    if (equals == std::string::npos) Fail(where, offset + at, "a field name=value");
    fields[field.substr(0, equals)] = field.substr(equals + 1);
    at += len;
  }
  return fields;
}

Record ReadRecord(const Bytes& bytes, std::uint64_t offset, const std::string& where) {
  Record r;
  r.offset = offset;
  char len[4];
  if (bytes.size() - offset < 4) Fail(where, offset, "a record header length");
  bytes.Read(offset, len, 4);
  const std::uint32_t header_len = U32(len);
  if (header_len > kMaxHeaderBytes || header_len > bytes.size() - offset - 4)
    Fail(where, offset, "a record header of at most 1 MiB within the bag, not " +
                            std::to_string(header_len) + " bytes");
  std::string header(header_len, '\0');
  bytes.Read(offset + 4, header.data(), header_len);
  r.fields = Fields(header, where, offset + 4);
  const auto op = r.fields.find("op");
  if (op == r.fields.end() || op->second.size() != 1) Fail(where, offset, "a record op");
  r.op = static_cast<std::uint8_t>(op->second[0]);
  const std::uint64_t data_len_at = offset + 4 + header_len;
  if (bytes.size() - data_len_at < 4) Fail(where, data_len_at, "a record data length");
  bytes.Read(data_len_at, len, 4);
  r.data_len = U32(len);
  r.data_offset = data_len_at + 4;
  if (r.data_len > bytes.size() - r.data_offset)
    Fail(where, data_len_at, "record data within the bag, not " + std::to_string(r.data_len) +
                                 " bytes");
  return r;
}

// A field of a fixed size (4 or 8 bytes), as an integer; a string field when size is 0.
std::uint64_t Number(const Record& r, const char* name, std::size_t size, const std::string& where) {
  const auto field = r.fields.find(name);
  if (field == r.fields.end() || field->second.size() != size)
    Fail(where, r.offset, std::string("a field '") + name + "' of " + std::to_string(size) +
                              " bytes in the record of op " + std::to_string(r.op));
  return size == 4 ? U32(field->second.data()) : U64(field->second.data());
}

std::vector<Record> Walk(const Bytes& bytes, std::uint64_t from, const std::string& where) {
  std::vector<Record> records;
  for (std::uint64_t at = from; at < bytes.size(); at = records.back().end())
    records.push_back(ReadRecord(bytes, at, where));
  return records;
}

std::string ReadData(const Bytes& bytes, const Record& r) {
  std::string data(r.data_len, '\0');
  bytes.Read(r.data_offset, data.data(), r.data_len);
  return data;
}

// The chunk's records, decompressed when needed.
Bytes ChunkBytes(const Bytes& file, const Record& chunk, const std::string& where) {
  const auto compression = chunk.fields.find("compression");
  const std::uint64_t size = Number(chunk, "size", 4, where);
  if (compression == chunk.fields.end()) Fail(where, chunk.offset, "a chunk's compression");
  if (size > kMaxChunkBytes)
    Fail(where, chunk.offset, "a chunk of at most 256 MiB, not " + std::to_string(size));
  std::string data = ReadData(file, chunk);
  std::vector<char> out(size);
  if (compression->second == "none") {
    if (size != chunk.data_len) Fail(where, chunk.offset, "an uncompressed chunk of its size");
    out.assign(data.begin(), data.end());
  } else if (compression->second == "bz2") {
    unsigned int out_len = static_cast<unsigned int>(size);
    if (BZ2_bzBuffToBuffDecompress(out.data(), &out_len, data.data(),
                                   static_cast<unsigned int>(data.size()), 0, 0) != BZ_OK ||
        out_len != size)
      Fail(where, chunk.offset, "a bz2 chunk that decompresses to its size");
  } else if (compression->second == "lz4") {
    unsigned int out_len = static_cast<unsigned int>(size);
    if (roslz4_buffToBuffDecompress(data.data(), static_cast<unsigned int>(data.size()),
                                    out.data(), &out_len) != ROSLZ4_OK ||
        out_len != size)
      Fail(where, chunk.offset, "an lz4 chunk that decompresses to its size");
  } else {
    Fail(where, chunk.offset, "compression none, bz2 or lz4");
  }
  return Bytes(std::move(out));
}

// The bag header's fields, and the connections and chunk infos at its index position.
struct Index {
  std::set<std::uint64_t> connections;
  std::set<std::uint64_t> chunk_offsets;  // of the chunks the chunk infos point to
};

Index ReadIndex(const Bytes& file, const std::vector<Record>& records, const std::string& where) {
  if (records.empty() || records.front().op != kBagHeader)
    Fail(where, std::strlen(kMagic), "the bag header record first");
  const Record& header = records.front();
  const std::uint64_t index_pos = Number(header, "index_pos", 8, where);
  const std::uint64_t conn_count = Number(header, "conn_count", 4, where);
  const std::uint64_t chunk_count = Number(header, "chunk_count", 4, where);
  if (index_pos == 0) Fail(where, header.offset, "an indexed bag (rosbag reindex fixes it)");
  std::size_t k = 0;
  while (k < records.size() && records[k].offset != index_pos) ++k;
  if (k == records.size() || records.size() - k < conn_count + chunk_count)
    Fail(where, header.offset, "index_pos at a record followed by " + std::to_string(conn_count) +
                                   " connections and " + std::to_string(chunk_count) +
                                   " chunk infos");
  std::set<std::uint64_t> chunks;
  for (const Record& r : records)
    if (r.op == kChunk) chunks.insert(r.offset);
  Index index;
  for (std::size_t i = k; i < k + conn_count; ++i) {
    if (records[i].op != kConnection) Fail(where, records[i].offset, "a connection record");
    index.connections.insert(Number(records[i], "conn", 4, where));
    Fields(ReadData(file, records[i]), where, records[i].data_offset);
  }
  for (std::size_t i = k + conn_count; i < k + conn_count + chunk_count; ++i) {
    const Record& info = records[i];
    if (info.op != kChunkInfo) Fail(where, info.offset, "a chunk info record");
    const std::uint64_t chunk_pos = Number(info, "chunk_pos", 8, where);
    if (!chunks.count(chunk_pos)) Fail(where, info.offset, "chunk_pos at a chunk record");
    if (info.data_len != 8 * Number(info, "count", 4, where))
      Fail(where, info.offset, "8 bytes of data per connection counted");
    const std::string data = ReadData(file, info);
    for (std::size_t at = 0; at < data.size(); at += 8)
      if (!index.connections.count(U32(data.data() + at)))
        Fail(where, info.data_offset + at, "a connection of the index");
    index.chunk_offsets.insert(chunk_pos);
  }
  return index;
}

// A chunk's records, and the index data records after it whose entries point into it.
void CheckChunk(const Bytes& file, const std::vector<Record>& records, std::size_t c,
                const Index& index, const std::string& where) {
  const Record& chunk = records[c];
  const Bytes inner = ChunkBytes(file, chunk, where);
  const std::string inside = where + " (chunk at byte " + std::to_string(chunk.offset) + ")";
  std::set<std::uint64_t> messages;
  for (const Record& r : Walk(inner, 0, inside)) {
    if (r.op == kMessageData) {
      if (!index.connections.count(Number(r, "conn", 4, inside)))
        Fail(inside, r.offset, "a message of a connection of the index");
      Number(r, "time", 8, inside);
      messages.insert(r.offset);
    } else if (r.op != kConnection) {
      Fail(inside, r.offset, "message data or connection records in a chunk");
    }
  }
  for (std::size_t i = c + 1; i < records.size() && records[i].op == kIndexData; ++i) {
    const Record& r = records[i];
    if (Number(r, "ver", 4, where) != 1 || !index.connections.count(Number(r, "conn", 4, where)))
      Fail(where, r.offset, "index data of version 1 for a connection of the index");
    if (r.data_len != 12 * Number(r, "count", 4, where))
      Fail(where, r.offset, "12 bytes of data per index entry");
    const std::string data = ReadData(file, r);
    for (std::size_t at = 0; at < data.size(); at += 12)
      if (!messages.count(U32(data.data() + at + 8)))
        Fail(where, r.data_offset + at, "an index entry pointing at a message of its chunk");
  }
}

// Reads a serialised message's parts, each bounded by the bytes left.
class Layout {
 public:
  Layout(const std::uint8_t* data, std::size_t size, const char* type)
      : data_(data), size_(size), type_(type) {}
  void Skip(std::uint64_t n, const char* what) {
    if (n > size_ - at_)
      throw std::runtime_error(std::string("malformed ") + type_ + ": " + what + " of " +
                               std::to_string(n) + " bytes, " + std::to_string(size_ - at_) +
                               " left");
    at_ += static_cast<std::size_t>(n);
  }
  std::uint32_t Length(const char* what) {
    Skip(4, what);
    std::uint32_t n;
    std::memcpy(&n, data_ + at_ - 4, 4);
    return n;
  }
  void String(const char* what) { Skip(Length(what), what); }
  void Header() {
    Skip(12, "header seq and stamp");
    String("frame_id");
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
  const char* type_;
};

}  // namespace

void CheckBagStructure(const std::string& path) {
  const std::string where = "ROS bag " + path;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  in.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  const Bytes file(in, size);
  const std::size_t magic = std::strlen(kMagic);
  std::string start(magic, '\0');
  if (size < magic || (file.Read(0, start.data(), magic), start != kMagic))
    Fail(where, 0, "'#ROSBAG V2.0' (a ROS 1 bag of format 2.0)");
  const std::vector<Record> records = Walk(file, magic, where);
  const Index index = ReadIndex(file, records, where);
  for (std::size_t c = 0; c < records.size(); ++c)
    if (records[c].op == kChunk) CheckChunk(file, records, c, index, where);
}

void CheckLaserScanBytes(const std::uint8_t* data, std::size_t size) {
  Layout layout(data, size, "sensor_msgs/LaserScan");
  layout.Header();
  layout.Skip(7 * 4, "angles, times and ranges");
  layout.Skip(4ull * layout.Length("ranges count"), "ranges");
  layout.Skip(4ull * layout.Length("intensities count"), "intensities");
}

void CheckOdometryBytes(const std::uint8_t* data, std::size_t size) {
  Layout layout(data, size, "nav_msgs/Odometry");
  layout.Header();
  layout.String("child_frame_id");
  layout.Skip((7 + 36 + 6 + 36) * 8, "pose and twist with covariances");
}

void CheckTfMessageBytes(const std::uint8_t* data, std::size_t size) {
  Layout layout(data, size, "tf2_msgs/TFMessage");
  const std::uint32_t count = layout.Length("transforms count");
  for (std::uint32_t i = 0; i < count; ++i) {
    layout.Header();
    layout.String("child_frame_id");
    layout.Skip(7 * 8, "transform");
  }
}

}  // namespace scanloc::bag
