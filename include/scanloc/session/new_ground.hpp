#pragma once
// New ground: where the map does not reach, a scan cannot be confirmed, and a session that extends
// its map only with confirmed scans stops growing it there for good. A robot whose scans fail the
// rules for a while (a laser that sees 120° of a cluttered hall, where rule 2's E_max was learned
// on cleaner first scans) drives out of its map, and from then on no scan has anything to match:
// acapulco seen over 120° confirmed 34 of its 861 scans and ended 12.9 m off on average. Such a
// scan keeps the odometry's prediction (the data cannot disprove it); when the map seen from there
// covers too little of it to judge it at all, it extends the map at the prediction, so that the
// scans after it have a map to be judged on: the session maps on along the odometry where it
// has no map, as it did at its first scan, and is never worse than that odometry. Not while the
// session is lost: a wrong posture's view also shows an empty map.

#include <cstddef>

#include "scanloc/likelihood/likelihood_test.hpp"

namespace scanloc {

// Whether the map, seen from the prediction, covers too little of a scan to judge it: fewer of its
// beams pair with the map (both ranges valid) than rule 1 asks to match, min_match_ratio of the
// scan's valid beams, so that rule 1 would fail even if every pair matched.
bool CoversTooLittle(const LikelihoodTestResult& prediction_test, std::size_t scan_valid_beams,
                     double min_match_ratio);

}  // namespace scanloc
