#include "estimator/state_check.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>

namespace vio {
namespace {

// A window of three frames moving at 1 m/s, identity extrinsic, and one
// triangulated landmark.
struct Scene {
  Window window;
  FeatureManager features{1};

  Scene() {
    window.extrinsics[0] = PoseArray(Eigen::Isometry3d::Identity());
    for (int k = 0; k < 3; ++k) {
      auto f = std::make_unique<WindowFrame>();
      f->id = k;
      f->pose[0] = 0.05 * k;
      f->speed_bias[0] = 1.0;
      window.frames.push_back(std::move(f));
    }
    Landmark& l = features.landmarks()[7];
    l.feature_id = 7;
    l.sightings.push_back({0, 0, {0.1, 0.2}, {0, 0}});
    l.triangulated = true;
    l.inverse_depth = 0.25;
  }
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(CheckWindowState, APlausibleWindowMayBeSolved) {
  const Scene s;
  EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0), StateDefect::kNone);
}

TEST(CheckWindowState, FindsEveryKindOfDefect) {
  {
    Scene s;
    s.window.frames[1]->pose[4] = kNaN;  // a quaternion entry
    EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0),
              StateDefect::kNonFinite);
  }
  {
    Scene s;
    s.window.frames[2]->speed_bias[8] = std::numeric_limits<double>::infinity();
    EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0),
              StateDefect::kNonFinite);
  }
  {
    Scene s;
    s.features.landmarks()[7].inverse_depth = kNaN;
    EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0),
              StateDefect::kNonFinite);
  }
  {
    Scene s;
    s.window.t_d = kNaN;
    EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0),
              StateDefect::kNonFinite);
  }
  {
    Scene s;
    for (int i = 3; i < 7; ++i) s.window.frames[0]->pose[i] = 0.0;
    EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0),
              StateDefect::kBadRotation);
  }
  {
    // 5 ms of 1e6 m/s^2 (one glitched sample) is 5 km/s.
    Scene s;
    s.window.frames[2]->speed_bias[1] = 5000.0;
    EXPECT_EQ(CheckWindowState(s.window, s.features, 50.0),
              StateDefect::kTooFast);
    EXPECT_STREQ(StateDefectName(StateDefect::kTooFast),
                 "speed beyond the limit");
  }
}

}  // namespace
}  // namespace vio
