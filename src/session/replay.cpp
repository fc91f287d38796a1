#include "scanloc/session/replay.hpp"

#include <sstream>

#include "scanloc/session/scan_processor.hpp"

namespace scanloc {
namespace {

template <typename T>
std::string Differs(const char* field, const T& replayed, const T& recorded) {
  std::ostringstream out;
  out.precision(17);
  out << field << " is " << replayed << " on replay but " << recorded << " in the record";
  return out.str();
}

std::string PoseText(const Pose2D& p) {
  std::ostringstream out;
  out.precision(17);
  out << "(" << p.x_m << ", " << p.y_m << ", " << p.yaw_rad << ")";
  return out.str();
}

}  // namespace

std::string DescribeReplayMismatch(const IterationRecord& now, const RecordedIteration& then) {
  if (now.index != then.index) return Differs("the index", now.index, then.index);
  if (now.timestamp_s != then.timestamp_s)
    return Differs("the timestamp", now.timestamp_s, then.timestamp_s);
  if (now.first != then.first) return Differs("first", now.first, then.first);
  if (now.skipped != then.skipped) return Differs("skipped", now.skipped, then.skipped);
  if (now.localisation.has_value() != then.localised)
    return Differs("localised", now.localisation.has_value(), then.localised);
  // A posture the replay computed itself (the prediction) must be the recorded one to the bit.
  if (!then.localised && !SamePosture(now.T_world_robot, then.T_world_robot))
    return Differs("the posture", PoseText(now.T_world_robot), PoseText(then.T_world_robot));
  if (then.localised && now.signature_expect_value_m != then.signature_expect_value_m)
    return Differs("the laser signature's bound", now.signature_expect_value_m,
                   then.signature_expect_value_m);
  if (now.search.has_value() != then.searched)
    return Differs("searched", now.search.has_value(), then.searched);
  if (now.lost != then.lost) return Differs("lost", now.lost, then.lost);
  if (now.recovered != then.recovered) return Differs("recovered", now.recovered, then.recovered);
  if (now.inserted != then.inserted) return Differs("inserted", now.inserted, then.inserted);
  if (now.carved != then.carved) return Differs("carved", now.carved, then.carved);
  if (now.map_points != then.map_points)
    return Differs("map_points", now.map_points, then.map_points);
  if (now.closure.has_value() != then.closure_tried)
    return Differs("closure tried", now.closure.has_value(), then.closure_tried);
  if (now.closure && now.closure->accepted != then.closure_accepted)
    return Differs("closure accepted", now.closure->accepted, then.closure_accepted);
  if (now.closure && now.closure->rendered != then.closure_rendered)
    return Differs("closure rendered", now.closure->rendered, then.closure_rendered);
  return "";
}

}  // namespace scanloc
