#pragma once
// Rule 2's bound from place to place on a saved map. A map's signature (map_signature.hpp) is one
// bound for the whole map, learned from the scans the session laid, judged on the finished map.
// Where the session laid a place's walls twice (a revisit a few centimetres off, a loop closed
// late), the finished map fits the scans seen there worse than its median: on ACES's default
// map the sampled scans around its start have a median EV of 0.12 m against the map's 0.075 m,
// and the true posture of a scan taken there refines to an EV above the map's bound. So a place's
// bound is the prior raised by how much worse than the map's median its nearest sampled scans
// fit: prior + max(0, their median EV − the map's median EV). It is never lower than the prior.

#include <vector>

#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/session/map_signature.hpp"

namespace scanloc {

class PlaceBound {
 public:
  // No samples: every place has the prior.
  PlaceBound() = default;
  // `median_expect_value_m`: the map's median EV over all its samples.
  PlaceBound(std::vector<MapSignatureSample> samples, double median_expect_value_m,
             int neighbours = 5);

  // How much the nearest `neighbours` samples' median EV exceeds the map's median (>= 0), m.
  double Excess(const Pose2D& T_world_robot) const;
  double At(const Pose2D& T_world_robot, double prior_m) const {
    return prior_m + Excess(T_world_robot);
  }
  bool empty() const { return samples_.empty(); }

 private:
  std::vector<MapSignatureSample> samples_;
  double median_expect_value_m_ = 0.0;
  int neighbours_ = 5;
};

}  // namespace scanloc
