// The whole image pipeline on real data: the V1_01 excerpt's images tracked
// by the frontend (stereo), turned into observations, and replayed through
// the estimator with config/euroc_stereo.yaml, as vio_replay does.

#include <gtest/gtest.h>

#include <algorithm>

#include "config/estimator_config.h"
#include "config/euroc_sequence.h"
#include "config/frontend_config.h"
#include "config/imu_config.h"
#include "config/visual_config.h"
#include "dataset/fault_injection.h"
#include "estimator/sequence_runner.h"
#include "tools/image_tracks.h"

namespace vio {
namespace {

TEST(ImageReplay, RealStaticStereoStartInitialisesAndDoesNotDrift) {
  const YamlNode root = YamlNode::LoadFile(std::string(VIO_SOURCE_DIR) +
                                           "/config/euroc_stereo.yaml");
  const ImuConfig imu = LoadImuConfig(root);
  EstimatorOptions options = ReadEstimatorOptions(root);
  options.gravity_magnitude = imu.gravity_magnitude;
  const FrontendOptions frontend = ReadFrontendOptions(root.Child("frontend"));
  ASSERT_TRUE(options.use_stereo && frontend.stereo);

  const EurocSequence seq = LoadEurocSequence(std::string(VIO_SHARED_DIR) +
                                              "/data/euroc_V1_01_first5s");
  ImageTrackingSummary images;
  const std::vector<FeatureFrame> frames =
      ImageObservations(seq, frontend, &images);
  EXPECT_EQ(frames.size(), 95u);
  EXPECT_EQ(images.stereo_frames, 95);
  EXPECT_EQ(images.cameras[1].missing, 4) << "cam1 lists 4 absent images";
  EXPECT_EQ(images.skipped(), 4);

  std::vector<EstimatorCamera> cameras(2);
  for (int c = 0; c < 2; ++c) {
    cameras[c].T_b_c.linear() = seq.cameras[c].q_b_c.toRotationMatrix();
    cameras[c].T_b_c.translation() = seq.cameras[c].t_b_c;
    cameras[c].focal_px = CameraModel(seq.cameras[c]).focal();
  }
  Estimator estimator(options, ReadVisualOptions(root), seq.imu.noise,
                      imu.preintegration, cameras);
  const std::vector<EstimatorOutput> outputs =
      RunSequence(&estimator, seq.data.imu, frames);

  // The vehicle stands still: after the static start the estimate must stay
  // where it began.
  const auto first = std::find_if(outputs.begin(), outputs.end(),
                                  [](const auto& o) { return o.initialized; });
  ASSERT_NE(first, outputs.end()) << "never initialised";
  double drift_m = 0.0;
  int initialised = 0;
  for (auto it = first; it != outputs.end(); ++it) {
    if (!it->initialized) continue;
    ++initialised;
    drift_m = std::max(drift_m, (it->p_w_b - first->p_w_b).norm());
  }
  std::printf("initialised after %td frames; %d estimates; drift %.4f m\n",
              first - outputs.begin(), initialised, drift_m);
  EXPECT_GE(initialised, 70);  // the static start needs about 1 s of IMU
  EXPECT_LT(drift_m, 0.03);    // measured 0.0027 m
  EXPECT_EQ(estimator.summary().resets, 0);
  EXPECT_GT(estimator.summary().landmarks_triangulated, 50);
}

// The same real stereo sequence with 100 IMU samples (0.5 s) missing 3 s in:
// the frames across the gap are placed by vision alone (the stereo pairs
// give depths even standing still), and the estimate still does not move.
TEST(ImageReplay, RealStereoImagesBridgeAnImuGap) {
  const YamlNode root = YamlNode::LoadFile(std::string(VIO_SOURCE_DIR) +
                                           "/config/euroc_stereo.yaml");
  const ImuConfig imu = LoadImuConfig(root);
  EstimatorOptions options = ReadEstimatorOptions(root);
  ApplyImuConfig(imu, &options);
  const EurocSequence seq = LoadEurocSequence(std::string(VIO_SHARED_DIR) +
                                              "/data/euroc_V1_01_first5s");
  ImageTrackingSummary images;
  const std::vector<FeatureFrame> frames = ImageObservations(
      seq, ReadFrontendOptions(root.Child("frontend")), &images);
  std::vector<EstimatorCamera> cameras(2);
  for (int c = 0; c < 2; ++c) {
    cameras[c].T_b_c.linear() = seq.cameras[c].q_b_c.toRotationMatrix();
    cameras[c].T_b_c.translation() = seq.cameras[c].t_b_c;
    cameras[c].focal_px = CameraModel(seq.cameras[c]).focal();
  }
  ImuFault gap;
  gap.kind = ImuFaultKind::kDrop;
  gap.t_s = 3.0;
  gap.count = 100;
  Estimator estimator(options, ReadVisualOptions(root), seq.imu.noise,
                      imu.preintegration, cameras);
  const std::vector<EstimatorOutput> outputs =
      RunSequence(&estimator, WithImuFault(seq.data.imu, gap), frames);

  const EstimatorSummary& s = estimator.summary();
  ASSERT_EQ(s.imu_gaps.size(), 1u);
  EXPECT_NEAR(s.imu_gaps[0].length_s(), 0.505, 1e-3);
  EXPECT_EQ(s.imu_gaps[0].frames_visual, 11);  // measured: every frame in it
  EXPECT_EQ(s.imu_gaps[0].frames_lost, 0);
  EXPECT_EQ(s.resets, 0);
  const auto first = std::find_if(outputs.begin(), outputs.end(),
                                  [](const auto& o) { return o.initialized; });
  ASSERT_NE(first, outputs.end());
  double drift_m = 0.0;
  int initialised = 0;
  for (auto it = first; it != outputs.end(); ++it) {
    if (!it->processed || !it->initialized) continue;
    ++initialised;
    drift_m = std::max(drift_m, (it->p_w_b - first->p_w_b).norm());
  }
  std::printf("gap: %d estimates; drift %.4f m\n", initialised, drift_m);
  EXPECT_GE(initialised, 70);
  EXPECT_LT(drift_m, 0.03);  // measured 0.0028 m (0.0027 m without the gap)
}

}  // namespace
}  // namespace vio
