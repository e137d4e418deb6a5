#include "estimator/sighting_outliers.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace vio {
namespace {

TEST(SightingOutliers, BadSightingsGoAloneWhileMostAreGood) {
  const SightingVerdict v = ClassifySightings({1.0, 9.0, 2.0, 5.0, 30.0}, 5.0);
  EXPECT_FALSE(v.whole);
  // At the threshold a sighting is kept: only beyond it is it bad.
  EXPECT_EQ(v.bad, (std::vector<int>{1, 4}));
}

TEST(SightingOutliers, HalfBadKeepsTheLandmarkMoreThanHalfRemovesIt) {
  const SightingVerdict half = ClassifySightings({1.0, 9.0}, 5.0);
  EXPECT_FALSE(half.whole);
  EXPECT_EQ(half.bad, (std::vector<int>{1}));
  const SightingVerdict most = ClassifySightings({1.0, 9.0, 7.0}, 5.0);
  EXPECT_TRUE(most.whole);
  EXPECT_TRUE(most.bad.empty());
  EXPECT_TRUE(ClassifySightings({9.0}, 5.0).whole);
}

TEST(SightingOutliers, AnErrorThatCouldNotBeEvaluatedRemovesTheLandmark) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(ClassifySightings({1.0, nan, 1.0, 1.0}, 5.0).whole);
  EXPECT_TRUE(
      ClassifySightings({1.0, std::numeric_limits<double>::infinity()}, 5.0)
          .whole);
  const SightingVerdict none = ClassifySightings({}, 5.0);
  EXPECT_FALSE(none.whole);
  EXPECT_TRUE(none.bad.empty());
}

}  // namespace
}  // namespace vio
