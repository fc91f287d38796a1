#include "scanloc/session/new_ground.hpp"

namespace scanloc {

bool CoversTooLittle(const LikelihoodTestResult& prediction_test, std::size_t scan_valid_beams,
                     double min_match_ratio) {
  return scan_valid_beams > 0 && static_cast<double>(prediction_test.valid_pairs) <
                                     min_match_ratio * static_cast<double>(scan_valid_beams);
}

}  // namespace scanloc
