#include "config/estimator_config.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace vio {
namespace {

std::string ConfigPath(const std::string& name) {
  return std::string(VIO_SOURCE_DIR) + "/config/" + name;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The message of the ConfigError that loading `text` raises ("" if none).
std::string ErrorOf(const std::string& text) {
  try {
    ReadEstimatorOptions(YamlNode::LoadString(text, "test.yaml"));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string text, const std::string& from,
                    const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(EstimatorConfig, DefaultYamlEqualsTheBuiltInDefaults) {
  const EstimatorOptions o =
      ReadEstimatorOptions(YamlNode::LoadFile(ConfigPath("default.yaml")));
  const EstimatorOptions d;
  EXPECT_EQ(o.window_size, d.window_size);
  EXPECT_EQ(o.use_stereo, false);
  EXPECT_EQ(o.keyframe.min_parallax_px, d.keyframe.min_parallax_px);
  EXPECT_EQ(o.keyframe.min_tracked_features, d.keyframe.min_tracked_features);
  EXPECT_EQ(o.triangulation.min_parallax_deg, d.triangulation.min_parallax_deg);
  EXPECT_EQ(o.triangulation.max_depth_m, d.triangulation.max_depth_m);
  EXPECT_EQ(o.landmarks.outlier_threshold_px, d.landmarks.outlier_threshold_px);
  EXPECT_EQ(o.landmarks.max_landmarks, d.landmarks.max_landmarks);
  EXPECT_EQ(o.static_init.max_acc_std, d.static_init.max_acc_std);
  EXPECT_EQ(o.state_prior.tilt_rad, d.state_prior.tilt_rad);
  EXPECT_EQ(o.failure.max_position_jump_m, d.failure.max_position_jump_m);
  EXPECT_EQ(o.failure.max_speed_m_s, d.failure.max_speed_m_s);
  EXPECT_EQ(o.solver.linear_solver, d.solver.linear_solver);
  EXPECT_EQ(o.solver.trust_region, d.solver.trust_region);
  EXPECT_EQ(o.solver.max_iterations, d.solver.max_iterations);
  EXPECT_EQ(o.solver.num_threads, 1);
}

TEST(EstimatorConfig, StereoPresetTurnsStereoOn) {
  const EstimatorOptions o =
      ReadEstimatorOptions(YamlNode::LoadFile(ConfigPath("stereo.yaml")));
  EXPECT_TRUE(o.use_stereo);
  EXPECT_EQ(o.window_size, 10);
}

TEST(EstimatorConfig, ErrorsNameFileAndKey) {
  const std::string text = ReadText(ConfigPath("default.yaml"));
  EXPECT_EQ(ErrorOf(Replace(text, "window_size: 10", "window_size: 1")),
            "test.yaml: estimator.window_size must be >= 2 (got 1)");
  EXPECT_EQ(ErrorOf(Replace(text, "    max_landmarks: 120", "")),
            "test.yaml: estimator.landmarks.max_landmarks is missing");
  EXPECT_EQ(ErrorOf(Replace(text, "linear_solver: dense_schur",
                            "linear_solver: cholmod")),
            "test.yaml: estimator.solver.linear_solver must be a Ceres "
            "linear solver such as dense_schur, sparse_schur, dense_qr (got "
            "'cholmod')");
  EXPECT_NE(ErrorOf(Replace(text, "min_depth_m: 0.1", "min_depth_m: x"))
                .find("estimator.triangulation.min_depth_m"),
            std::string::npos);
  EXPECT_EQ(ErrorOf("imu: {}\n"), "test.yaml: estimator is missing");
}

}  // namespace
}  // namespace vio
