#include "scanloc/maps/point_map_io.hpp"

#include <pcl/PCLPointCloud2.h>
#include <pcl/io/pcd_io.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <istream>
#include <iterator>
#include <limits>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "pcd_header.hpp"
#include "scanloc/common/atomic_file.hpp"

namespace scanloc {
namespace {

// The spacing given to points of a PCD without a `spacing` field when de-duplication is off.
constexpr double kDefaultSpacingM = 0.05;
// A float is nudged by at most this many ulps to stay in its cell; more means the cell is finer
// than float precision at that coordinate, and the point is stored as rounded.
constexpr int kMaxNudgeUlps = 8;

// The float nearest `value_m` that lies in the same de-duplication cell, computed exactly as
// PointMap computes cells (floor(v / cell_size_m) in double).
float FloatInSameCell(double value_m, double cell_size_m) {
  float stored = static_cast<float>(value_m);
  if (cell_size_m <= 0.0) return stored;
  const double cell = std::floor(value_m / cell_size_m);
  for (int ulp = 0; ulp < kMaxNudgeUlps; ++ulp) {
    const double stored_cell = std::floor(static_cast<double>(stored) / cell_size_m);
    if (stored_cell == cell) break;
    const float towards = stored_cell > cell ? -std::numeric_limits<float>::infinity()
                                             : std::numeric_limits<float>::infinity();
    stored = std::nextafter(stored, towards);
  }
  return stored;
}

pcl::PCLPointField FloatField(const std::string& name, std::uint32_t offset) {
  pcl::PCLPointField field;
  field.name = name;
  field.offset = offset;
  field.datatype = pcl::PCLPointField::FLOAT32;
  field.count = 1;
  return field;
}

// Why a field cannot hold a coordinate or spacing, or "" when it can.
std::string FieldProblem(const pcl::PCLPointCloud2& cloud, const pcl::PCLPointField& field) {
  const bool is_float = field.datatype == pcl::PCLPointField::FLOAT32;
  const bool is_double = field.datatype == pcl::PCLPointField::FLOAT64;
  if (!is_float && !is_double)
    return "field '" + field.name + "' has PCL datatype " + std::to_string(field.datatype) +
           ", float or double expected";
  if (field.count < 1 || field.offset + (is_double ? 8u : 4u) > cloud.point_step)
    return "field '" + field.name + "' does not fit in a point of " +
           std::to_string(cloud.point_step) + " bytes";
  return "";
}

// Reads one float or double field (checked with FieldProblem) of the cloud's points.
class FieldReader {
 public:
  FieldReader(const pcl::PCLPointCloud2& cloud, const pcl::PCLPointField& field)
      : cloud_(cloud),
        offset_(field.offset),
        is_double_(field.datatype == pcl::PCLPointField::FLOAT64) {}
  double operator()(std::size_t point) const {
    const std::uint8_t* bytes = cloud_.data.data() + point * cloud_.point_step + offset_;
    if (is_double_) {
      double value;
      std::memcpy(&value, bytes, sizeof value);
      return value;
    }
    float value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
  }

 private:
  const pcl::PCLPointCloud2& cloud_;
  std::uint32_t offset_;
  bool is_double_;
};

// The reader of the named field; nullopt when the cloud has none. Throws fail(problem) when the
// field is there but unusable.
template <class Fail>
std::optional<FieldReader> FindField(const pcl::PCLPointCloud2& cloud, const std::string& name,
                                     const Fail& fail) {
  for (const pcl::PCLPointField& field : cloud.fields) {
    if (field.name != name) continue;
    const std::string problem = FieldProblem(cloud, field);
    if (!problem.empty()) throw fail(problem);
    return FieldReader(cloud, field);
  }
  return std::nullopt;
}

// Reads the header, then the points unless there are none; returns the point count. PCL 1.13
// accepts a file without FIELDS or DATA line as an empty header and then crashes reading its
// body, so the header is checked before the body is read.
template <class Fail>
std::size_t ReadPcd(const std::string& path, pcl::PCLPointCloud2& cloud, const Fail& fail) {
  pcl::PCDReader reader;
  // PCL reports most problems by status, some by exception (pcl::IOException, std::bad_alloc).
  const auto call_pcl = [&](const auto& read) {
    try {
      return read();
    } catch (const std::exception& error) {
      throw fail(error.what());
    }
  };
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int pcd_version = 0, data_type = 0;
  unsigned int data_offset = 0;
  if (call_pcl([&] {
        return reader.readHeader(path, cloud, origin, orientation, pcd_version, data_type,
                                 data_offset);
      }) < 0)
    throw fail("not a readable PCD header");
  if (data_offset == 0) throw fail("no DATA line, not a PCD file");
  if (cloud.fields.empty() || cloud.point_step == 0) throw fail("no FIELDS in the PCD header");
  const std::size_t point_count = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (point_count == 0) return 0;
  if (call_pcl([&] { return reader.read(path, cloud); }) < 0)
    throw fail("the PCD body does not match its header");
  if (cloud.data.size() < point_count * cloud.point_step)
    throw fail(std::to_string(point_count) + " points announced, " +
               std::to_string(cloud.data.size()) + " bytes of data");
  return point_count;
}

}  // namespace

void SavePointMapPcd(const PointMap& map, const std::string& path) {
  constexpr std::uint32_t kPointStep = 6 * sizeof(float);
  pcl::PCLPointCloud2 cloud;
  cloud.fields = {FloatField("x", 0),         FloatField("y", 4),
                  FloatField("z", 8),         FloatField("spacing", 12),
                  FloatField("normal_x", 16), FloatField("normal_y", 20)};
  cloud.width = static_cast<std::uint32_t>(map.live_size());  // carved points are not saved
  cloud.height = 1;
  cloud.point_step = kPointStep;
  cloud.row_step = kPointStep * cloud.width;
  cloud.is_bigendian = false;
  cloud.is_dense = true;
  cloud.data.resize(static_cast<std::size_t>(cloud.row_step));
  const double cell_size_m = map.options().cell_size_m;
  std::size_t row = 0;
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!map.alive(i)) continue;
    const Eigen::Vector2d normal = map.normal(i);
    const float values[6] = {FloatInSameCell(map.point(i).x(), cell_size_m),
                             FloatInSameCell(map.point(i).y(), cell_size_m),
                             0.0f,
                             static_cast<float>(map.spacing(i)),
                             static_cast<float>(normal.x()),
                             static_cast<float>(normal.y())};
    std::memcpy(cloud.data.data() + row++ * kPointStep, values, sizeof values);
  }

  // The bytes of PCL's PCDWriter::writeBinary, written with plain buffered writes: PCL maps the
  // file into memory, which dies of SIGBUS when the disk fills. PCL sizes its file to one page
  // plus the points, so after the header and the points come zeros up to that size (a map
  // without points is the header alone, as PCL refuses to write it).
  const std::string header = pcl::PCDWriter().generateHeaderBinary(cloud, Eigen::Vector4f::Zero(),
                                                                   Eigen::Quaternionf::Identity()) +
                             "DATA binary\n";
  const std::size_t page_bytes = static_cast<std::size_t>(::getpagesize());
  const std::size_t padding_bytes =
      cloud.data.empty() || header.size() >= page_bytes ? 0 : page_bytes - header.size();
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << header;
    out.write(reinterpret_cast<const char*>(cloud.data.data()),
              static_cast<std::streamsize>(cloud.data.size()));
    std::fill_n(std::ostreambuf_iterator<char>(out), padding_bytes, '\0');
  });
}

PointMapPcdLoad LoadPointMapPcdWithReport(const std::string& path, PointMapOptions options) {
  const auto fail = [&path](const std::string& what) {
    return std::runtime_error("cannot read point map " + path + ": " + what);
  };
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw fail("no such file");
  if (!std::filesystem::is_regular_file(path, error)) throw fail("not a regular file");
  // PCL believes the header's counts and allocates for them before reading: check them first.
  CheckPcdHeader(path);
  pcl::PCLPointCloud2 cloud;
  const std::size_t point_count = ReadPcd(path, cloud, fail);
  const std::optional<FieldReader> x = FindField(cloud, "x", fail);
  const std::optional<FieldReader> y = FindField(cloud, "y", fail);
  if (!x || !y) throw fail(std::string("no '") + (x ? "y" : "x") + "' field");
  const std::optional<FieldReader> spacing = FindField(cloud, "spacing", fail);
  const std::optional<FieldReader> normal_x = FindField(cloud, "normal_x", fail);
  const std::optional<FieldReader> normal_y = FindField(cloud, "normal_y", fail);
  const double default_spacing_m =
      options.cell_size_m > 0.0 ? options.cell_size_m : kDefaultSpacingM;

  PointMapPcdLoad load{PointMap(options)};
  load.points_in_file = point_count;
  std::vector<Eigen::Vector2d> points, normals;
  std::vector<double> spacings_m;
  points.reserve(point_count);
  spacings_m.reserve(point_count);
  for (std::size_t i = 0; i < point_count; ++i) {
    const Eigen::Vector2d point((*x)(i), (*y)(i));
    if (!point.allFinite()) {
      ++load.non_finite_points_skipped;
      continue;
    }
    if (!IsPlausiblePose(Pose2D(point.x(), point.y(), 0.0)))
      throw fail("point " + std::to_string(i) + " at (" + std::to_string(point.x()) + ", " +
                 std::to_string(point.y()) + ") lies beyond ±" +
                 std::to_string(static_cast<long>(kMaxCoordinateM)) + " m");
    double spacing_m = spacing ? (*spacing)(i) : default_spacing_m;
    if (!spacing || !(spacing_m > 0.0) || !std::isfinite(spacing_m)) {
      spacing_m = default_spacing_m;
      ++load.default_spacings_used;
    }
    points.push_back(point);
    spacings_m.push_back(spacing_m);
    // A missing or non-finite normal is "unknown" (zero): the point is then a disc.
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();
    if (normal_x && normal_y) normal = {(*normal_x)(i), (*normal_y)(i)};
    normals.push_back(normal.allFinite() ? normal : Eigen::Vector2d::Zero());
  }
  // A saved map comes back point for point: its points are cell means already.
  load.points_merged = points.size() - load.map.Restore(points, spacings_m, normals);
  return load;
}

PointMap LoadPointMapPcd(const std::string& path, PointMapOptions options) {
  return std::move(LoadPointMapPcdWithReport(path, options).map);
}

}  // namespace scanloc
