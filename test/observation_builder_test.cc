#include "frontend/observation_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

namespace vio {
namespace {

// EuRoC cam0 (the CameraCalibration defaults) and a copy shifted like cam1.
std::vector<CameraModel> StereoModels() {
  CameraCalibration cam1;
  cam1.fx = 457.587;
  cam1.fy = 456.134;
  cam1.cx = 379.999;
  cam1.cy = 255.238;
  cam1.distortion_coefficients = {-0.28368365, 0.07451284, -0.00010473,
                                  -3.55590700e-05};
  return {CameraModel(CameraCalibration()), CameraModel(cam1)};
}

FeatureObservation Seen(const CameraModel& model, int64_t id, int camera,
                        const Eigen::Vector3d& p_c) {
  FeatureObservation obs;
  obs.feature_id = id;
  obs.camera = camera;
  EXPECT_TRUE(model.Project(p_c, &obs.uv));
  return obs;
}

TEST(ObservationBuilder, UndistortsPixelsBackToTheNormalisedPoint) {
  const std::vector<CameraModel> models = StereoModels();
  ObservationBuilder builder(models);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> lateral(-0.6, 0.6), depth(1.0, 8.0);
  FeatureFrame frame;
  frame.t_ns = 1000;
  std::vector<Eigen::Vector2d> truth;
  for (int i = 0; i < 200; ++i) {
    const int camera = i % 2;
    const double z = depth(rng);
    const Eigen::Vector3d p_c(lateral(rng) * z, 0.6 * lateral(rng) * z, z);
    frame.observations.push_back(Seen(models[camera], i, camera, p_c));
    truth.push_back(p_c.head<2>() / z);
  }
  builder.Process(&frame);
  ASSERT_EQ(frame.observations.size(), 200u);
  for (size_t i = 0; i < truth.size(); ++i) {
    EXPECT_LT((frame.observations[i].xy - truth[i]).norm(), 1e-9) << i;
    EXPECT_EQ(frame.observations[i].velocity, Eigen::Vector2d::Zero());
  }
}

TEST(ObservationBuilder, VelocityIsTheDifferenceOverThePreviousFramePerCamera) {
  const std::vector<CameraModel> models = StereoModels();
  ObservationBuilder builder(models);
  const Eigen::Vector3d p0(0.3, -0.2, 3.0), p1(0.36, -0.17, 3.0);
  FeatureFrame a;
  a.t_ns = 1403715273262142976;
  a.observations = {Seen(models[0], 7, 0, p0), Seen(models[1], 7, 1, p0),
                    Seen(models[0], 8, 0, p0)};
  builder.Process(&a);
  FeatureFrame b;
  b.t_ns = a.t_ns + 50000000;  // 50 ms
  b.observations = {Seen(models[0], 7, 0, p1), Seen(models[1], 7, 1, p1),
                    Seen(models[0], 9, 0, p1)};
  builder.Process(&b);
  const Eigen::Vector2d expected = (p1 - p0).head<2>() / 3.0 / 0.05;
  EXPECT_LT((b.observations[0].velocity - expected).norm(), 1e-7);
  EXPECT_LT((b.observations[1].velocity - expected).norm(), 1e-7);
  EXPECT_EQ(b.observations[2].velocity, Eigen::Vector2d::Zero());  // new id
  // Feature 8 skips frame b: when it returns it is a new track.
  FeatureFrame c;
  c.t_ns = b.t_ns + 50000000;
  c.observations = {Seen(models[0], 8, 0, p1), Seen(models[0], 9, 0, p0)};
  builder.Process(&c);
  EXPECT_EQ(c.observations[0].velocity, Eigen::Vector2d::Zero());
  EXPECT_LT((c.observations[1].velocity + expected).norm(), 1e-7);
}

TEST(ObservationBuilder, RemovesAndCountsUnknownCamerasAndOutOfOrderIsAnError) {
  const std::vector<CameraModel> models = StereoModels();
  ObservationBuilder builder({models[0]});
  FeatureFrame frame;
  frame.t_ns = 2000;
  frame.observations = {Seen(models[0], 1, 0, {0, 0, 1}),
                        Seen(models[1], 2, 1, {0, 0, 1})};
  frame.observations[1].camera = 1;  // no model for camera 1
  builder.Process(&frame);
  EXPECT_EQ(frame.observations.size(), 1u);
  EXPECT_EQ(builder.summary().unknown_camera, 1);
  EXPECT_EQ(builder.summary().observations, 1);
  FeatureFrame same = frame;
  EXPECT_THROW(builder.Process(&same), std::invalid_argument);
}

TEST(ObservationBuilder, RemovesAndCountsPixelsOutsideTheImage) {
  const std::vector<CameraModel> models = StereoModels();
  ObservationBuilder builder({models[0]});
  FeatureFrame frame;
  frame.t_ns = 3000;
  const Eigen::Vector2d bad[] = {{-300.0, 200.0},
                                 {1e6, 200.0},
                                 {400.0, 480.0},  // one past the last row
                                 {std::nan(""), 200.0}};
  for (const Eigen::Vector2d& uv : bad) {
    FeatureObservation o;
    o.feature_id = static_cast<int64_t>(frame.observations.size());
    o.uv = uv;
    frame.observations.push_back(o);
  }
  frame.observations.push_back(Seen(models[0], 10, 0, {0.1, 0.1, 2.0}));
  builder.Process(&frame);
  ASSERT_EQ(frame.observations.size(), 1u);
  EXPECT_EQ(frame.observations[0].feature_id, 10);
  EXPECT_EQ(builder.summary().outside_image, 4);
  EXPECT_EQ(builder.summary().failed_undistortion, 0);
  EXPECT_EQ(builder.summary().observations, 1);
}

}  // namespace
}  // namespace vio
