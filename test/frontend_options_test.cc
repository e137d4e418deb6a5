#include "frontend/frontend_options.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace vio {
namespace {

using ::testing::HasSubstr;

TEST(FrontendOptions, DefaultsAreValid) {
  std::string message;
  EXPECT_TRUE(FrontendOptions().Validate(&message)) << message;
  EXPECT_EQ(FeatureTrackerOptions().max_features, 150);
}

TEST(FrontendOptions, MessageNamesTheBlockAndTheField) {
  FrontendOptions options;
  options.tracker.klt.window_px = 20;
  std::string message;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "tracker.klt_window_px must be odd and >= 3 (got 20)");

  options = FrontendOptions();
  options.stereo_matcher.max_epipolar_px = -1.0;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message, "stereo_matcher.max_epipolar_px must be > 0 (got -1)");

  options = FrontendOptions();
  options.stereo_matcher.reverse_pyramid_levels = 4;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_EQ(message,
            "stereo_matcher.reverse_pyramid_levels must be in [0, "
            "klt_pyramid_levels = 3] (got 4)");
  options.stereo_matcher.reverse_pyramid_levels = -1;
  EXPECT_FALSE(options.Validate(&message));
  options.stereo_matcher.reverse_pyramid_levels = 3;
  EXPECT_TRUE(options.Validate(&message));
}

TEST(FrontendOptions, RejectsEachOutOfRangeTrackerField) {
  const auto invalid = [](auto mutate, const std::string& field) {
    FeatureTrackerOptions o;
    mutate(&o);
    std::string message;
    EXPECT_FALSE(o.Validate(&message)) << field;
    EXPECT_THAT(message, HasSubstr(field));
  };
  invalid([](FeatureTrackerOptions* o) { o->max_features = 0; },
          "max_features");
  invalid([](FeatureTrackerOptions* o) { o->refill_min_missing = 0; },
          "refill_min_missing");
  invalid([](FeatureTrackerOptions* o) { o->refill_min_missing = 151; },
          "refill_min_missing");
  invalid([](FeatureTrackerOptions* o) { o->min_distance_px = -1; },
          "min_distance_px");
  invalid([](FeatureTrackerOptions* o) { o->corner_quality = 1.5; },
          "corner_quality");
  invalid([](FeatureTrackerOptions* o) { o->klt.pyramid_levels = 9; },
          "klt_pyramid_levels");
  invalid([](FeatureTrackerOptions* o) { o->klt.epsilon_px = 0; },
          "klt_epsilon_px");
  invalid([](FeatureTrackerOptions* o) { o->max_forward_backward_px = NAN; },
          "max_forward_backward_px");
  invalid([](FeatureTrackerOptions* o) { o->fundamental_confidence = 1.0; },
          "fundamental_confidence");
  invalid([](FeatureTrackerOptions* o) { o->virtual_focal_px = 0; },
          "virtual_focal_px");
  invalid([](FeatureTrackerOptions* o) { o->clahe_tiles = 0; }, "clahe_tiles");
  invalid([](FeatureTrackerOptions* o) { o->fundamental_baseline_frames = -1; },
          "fundamental_baseline_frames");
  invalid([](FeatureTrackerOptions* o) { o->anchor_max_correction_px = 0; },
          "anchor_max_correction_px");
  invalid([](FeatureTrackerOptions* o) { o->anchor_min_correlation = 1.0; },
          "anchor_min_correlation");
}

}  // namespace
}  // namespace vio
