#include "estimator/estimator_options.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace vio {
namespace {

TEST(EstimatorOptions, DefaultsAreValidAndMatchTheDesign) {
  const EstimatorOptions o;
  std::string message;
  EXPECT_TRUE(o.Validate(&message)) << message;
  EXPECT_EQ(o.window_size, 10);
  EXPECT_EQ(o.solver.num_threads, 1);
  EXPECT_DOUBLE_EQ(o.gravity_magnitude, 9.81);
  // Offline by default: no wall-clock budget, so the load cannot change the
  // trajectory.
  EXPECT_EQ(o.solver.max_time_s, 0.0);
  // Start wherever the vehicle is; hold still when still.
  EXPECT_EQ(o.init.method, InitMethod::kAuto);
  EXPECT_FALSE(o.init.reinitialize_after_reset);
  EXPECT_TRUE(o.zero_velocity.enabled);
}

TEST(InitMethod, NamesParseBack) {
  for (InitMethod m : {InitMethod::kAuto, InitMethod::kStatic,
                       InitMethod::kMono, InitMethod::kStereo}) {
    InitMethod parsed = InitMethod::kAuto;
    EXPECT_TRUE(ParseInitMethod(InitMethodName(m), &parsed));
    EXPECT_EQ(parsed, m);
  }
  // The gyroscope-aided start is named, but not a choice of init.method.
  InitMethod g = InitMethod::kMono;
  EXPECT_STREQ(InitMethodName(InitMethod::kGyroAided), "gyro-aided");
  EXPECT_FALSE(ParseInitMethod("gyro-aided", &g));
  InitMethod m = InitMethod::kMono;
  EXPECT_FALSE(ParseInitMethod("dynamic", &m));
  EXPECT_EQ(m, InitMethod::kMono);
}

TEST(ReanchoredTracks, NamesParseBack) {
  for (ReanchoredTracks r :
       {ReanchoredTracks::kReuse, ReanchoredTracks::kKeepPoint,
        ReanchoredTracks::kKeepPointFirstEstimate}) {
    ReanchoredTracks parsed = ReanchoredTracks::kReuse;
    EXPECT_TRUE(ParseReanchoredTracks(ReanchoredTracksName(r), &parsed));
    EXPECT_EQ(parsed, r);
  }
  ReanchoredTracks r = ReanchoredTracks::kReuse;
  EXPECT_FALSE(ParseReanchoredTracks("skip_prior", &r));
}

// The world points have a timed factor (factors/timed_world_point_factor.h):
// every landmark choice goes with an estimated time offset.
TEST(EstimatorOptions, KeptPointsGoWithAnEstimatedTimeOffset) {
  for (ReanchoredTracks r :
       {ReanchoredTracks::kReuse, ReanchoredTracks::kKeepPoint,
        ReanchoredTracks::kKeepPointFirstEstimate}) {
    EstimatorOptions o;
    o.landmarks.reanchored_tracks = r;
    o.estimate_time_offset = true;
    std::string message;
    EXPECT_TRUE(o.Validate(&message))
        << ReanchoredTracksName(r) << ": " << message;
  }
}

TEST(EstimatorOptions, ValidateNamesTheOffendingField) {
  struct Case {
    void (*spoil)(EstimatorOptions*);
    const char* expected;
  } cases[] = {
      {[](EstimatorOptions* o) { o->window_size = 1; },
       "window_size must be >= 2 (got 1)"},
      {[](EstimatorOptions* o) { o->gravity_magnitude = -9.81; },
       "gravity_magnitude must be > 0"},
      {[](EstimatorOptions* o) {
         o->triangulation.max_depth_m = o->triangulation.min_depth_m;
       },
       "triangulation.max_depth_m must be > triangulation.min_depth_m"},
      {[](EstimatorOptions* o) {
         o->landmarks.outlier_threshold_px =
             std::numeric_limits<double>::quiet_NaN();
       },
       "landmarks.outlier_threshold_px must be > 0"},
      {[](EstimatorOptions* o) { o->solver.max_time_s = -0.01; },
       "solver.max_time_s must be >= 0"},
      {[](EstimatorOptions* o) { o->solver.function_tolerance = -1e-3; },
       "solver.function_tolerance must be in [0, 1)"},
      {[](EstimatorOptions* o) { o->solver.num_threads = 0; },
       "solver.num_threads must be >= 1"},
      {[](EstimatorOptions* o) { o->failure.max_gyro_bias = 0.0; },
       "failure.max_gyro_bias must be > 0"},
      {[](EstimatorOptions* o) { o->static_init.window_s = -1.0; },
       "static_init.window_s must be > 0"},
      {[](EstimatorOptions* o) { o->init.method = InitMethod::kStereo; },
       "init.method stereo needs use_stereo: true"},
      {[](EstimatorOptions* o) { o->init.mono.max_frames = 12; },
       "init.mono.max_frames must be <= window_size + 1 (got 12)"},
      {[](EstimatorOptions* o) { o->init.mono.min_span_s = 3.0; },
       "init.mono.min_span_s must be <= init.mono.window_s"},
      {[](EstimatorOptions* o) { o->init.mono.min_inliers = 5; },
       "init.mono.min_inliers must be >= 8 (got 5)"},
      {[](EstimatorOptions* o) { o->init.mono.gyro_min_tracks = 7; },
       "init.mono.gyro_min_tracks must be >= 8 (got 7)"},
      {[](EstimatorOptions* o) { o->init.mono.gyro_min_parallax_px = 0.0; },
       "init.mono.gyro_min_parallax_px must be > 0"},
      {[](EstimatorOptions* o) { o->init.stereo.min_span_s = 0.0; },
       "init.stereo.min_span_s must be > 0"},
      {[](EstimatorOptions* o) { o->init.refine_iterations = -1; },
       "init.refine_iterations must be >= 0"},
      {[](EstimatorOptions* o) { o->zero_velocity.block_s = 0.4; },
       "zero_velocity.block_s must be in (0, zero_velocity.imu_window_s / 2]"},
      {[](EstimatorOptions* o) {
         o->zero_velocity.sigma_velocity_m_s =
             std::numeric_limits<double>::infinity();
       },
       "zero_velocity.sigma_velocity_m_s must be > 0"},
      {[](EstimatorOptions* o) { o->failure.max_speed_m_s = 0.0; },
       "failure.max_speed_m_s must be > 0"},
      {[](EstimatorOptions* o) { o->imu_stream.rate_hz = 0.0; },
       "imu_stream.rate_hz must be > 0"},
      {[](EstimatorOptions* o) { o->imu_stream.range.gyroscope_range = -1.0; },
       "imu_stream.gyroscope_range must be > 0 (got -1)"},
  };
  for (const Case& c : cases) {
    EstimatorOptions o;
    c.spoil(&o);
    std::string message;
    EXPECT_FALSE(o.Validate(&message)) << c.expected;
    EXPECT_EQ(message.rfind(c.expected, 0), 0u)
        << "got '" << message << "', expected it to start with '" << c.expected
        << "'";
  }
}

}  // namespace
}  // namespace vio
