#include "scanloc/session/new_ground.hpp"

#include <gtest/gtest.h>

namespace scanloc {
namespace {

LikelihoodTestResult Paired(int valid_pairs) {
  LikelihoodTestResult test;
  test.valid_pairs = valid_pairs;
  test.match_pairs = valid_pairs;  // every pair matched: the cover alone decides
  return test;
}

// Rule 1 asks 0.3 of the pairs to match: with 100 valid beams, fewer than 30 pairs cannot pass it
// even if all of them matched.
TEST(NewGround, TheMapCoversTooLittleWhenFewerBeamsPairThanRuleOneAsksToMatch) {
  EXPECT_TRUE(CoversTooLittle(Paired(0), 100, 0.3));
  EXPECT_TRUE(CoversTooLittle(Paired(29), 100, 0.3));
  EXPECT_FALSE(CoversTooLittle(Paired(30), 100, 0.3));
  EXPECT_FALSE(CoversTooLittle(Paired(90), 100, 0.3));
  // A stricter rule 1 asks for more of the scan on the map.
  EXPECT_TRUE(CoversTooLittle(Paired(45), 100, 0.5));
}

// A scan without a valid beam shows nothing, not new ground.
TEST(NewGround, AScanWithoutAValidBeamIsNotNewGround) {
  EXPECT_FALSE(CoversTooLittle(Paired(0), 0, 0.3));
}

}  // namespace
}  // namespace scanloc
