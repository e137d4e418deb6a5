#include "dataset/sim_folder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "config/euroc_sequence.h"
#include "dataset/csv.h"
#include "frontend/observation_builder.h"
#include "geometry/so3.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

using testing::TempFolder;

SimulatorOptions ShortStereo(double duration_s) {
  SimulatorOptions options;
  options.duration_s = duration_s;
  options.camera.stereo = true;
  return options;
}

std::string ReadBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Every file below `folder`, by relative path, with its bytes.
std::map<std::string, std::string> Files(const std::string& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) {
      files[std::filesystem::relative(entry.path(), folder).string()] =
          ReadBytes(entry.path());
    }
  }
  return files;
}

TEST(SimFolder, SameSeedAndConfigGiveTheSameBytes) {
  TempFolder dir;
  SimulatorOptions options = ShortStereo(6.0);
  options.camera.outlier_fraction = 0.05;
  SimulateToFolder(options, dir.Path("a"));
  SimulateToFolder(options, dir.Path("b"));
  const auto a = Files(dir.Path("a")), b = Files(dir.Path("b"));
  ASSERT_EQ(a.size(), 7u);  // imu0 x2, cam0 x2, cam1 x2, ground truth
  EXPECT_TRUE(a == b);
  options.seed = 2;
  SimulateToFolder(options, dir.Path("c"));
  const auto c = Files(dir.Path("c"));
  EXPECT_NE(a.at("mav0/imu0/data.csv"), c.at("mav0/imu0/data.csv"));
  EXPECT_NE(a.at("mav0/cam0/features.csv"), c.at("mav0/cam0/features.csv"));
  EXPECT_EQ(a.at("mav0/cam1/sensor.yaml"), c.at("mav0/cam1/sensor.yaml"));
}

TEST(SimFolder, RefusesToWriteOverAnExistingSequence) {
  TempFolder dir;
  dir.Write("mav0/cam1/features.csv", "");
  try {
    SimulateToFolder(ShortStereo(1.0), dir.path());
    ADD_FAILURE() << "no DatasetError";
  } catch (const DatasetError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("mav0: already exists"));
  }
}

TEST(SimFolder, TheEurocReaderLoadsWhatWasSimulated) {
  TempFolder dir;
  const Simulation sim = SimulateToFolder(ShortStereo(6.0), dir.path());
  const EurocSequence seq = LoadEurocSequence(dir.path());
  // IMU: exact (shortest round-trip printing).
  ASSERT_EQ(seq.data.imu.size(), sim.imu.size());
  for (size_t k = 0; k < sim.imu.size(); ++k) {
    ASSERT_EQ(seq.data.imu[k].t_ns, sim.imu[k].t_ns);
    ASSERT_EQ(seq.data.imu[k].acc, sim.imu[k].acc);
    ASSERT_EQ(seq.data.imu[k].gyr, sim.imu[k].gyr);
  }
  EXPECT_EQ(seq.imu.rate_hz, 200.0);
  EXPECT_EQ(seq.imu.noise.gyroscope_random_walk,
            sim.options.imu.noise.gyroscope_random_walk);
  // Calibrations.
  ASSERT_EQ(seq.cameras.size(), 2u);
  const CameraCalibration& cam1 = seq.cameras[1];
  EXPECT_EQ(cam1.fx, sim.options.camera.cam1.fx);
  EXPECT_EQ(cam1.distortion_coefficients,
            sim.options.camera.cam1.distortion_coefficients);
  EXPECT_EQ(cam1.t_b_c, sim.options.camera.cam1.t_b_c);
  EXPECT_LT(cam1.q_b_c.angularDistance(sim.options.camera.cam1.q_b_c), 1e-12);
  // features.csv round trip: one merged frame per camera stamp.
  const std::vector<FeatureFrame> frames = MergedFeatureFrames(seq.data);
  ASSERT_EQ(frames.size(), sim.frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    ASSERT_EQ(frames[i].t_ns, sim.frames[i].t_ns);
    ASSERT_EQ(frames[i].observations.size(), sim.frames[i].observations.size());
    for (size_t j = 0; j < frames[i].observations.size(); ++j) {
      const FeatureObservation& read = frames[i].observations[j];
      const FeatureObservation& made = sim.frames[i].observations[j];
      ASSERT_EQ(read.feature_id, made.feature_id);
      ASSERT_EQ(read.camera, made.camera);
      ASSERT_LT((read.uv - made.uv).cwiseAbs().maxCoeff(), 5.1e-7);  // 6 dp
    }
  }
  // Ground truth, 9 significant digits.
  ASSERT_EQ(seq.data.ground_truth.size(), sim.ground_truth.size());
  const StampedState& last = seq.data.ground_truth.back();
  EXPECT_LT((last.p_w_b - sim.ground_truth.back().p_w_b).norm(), 1e-7);
  EXPECT_LT((last.b_a - sim.ground_truth.back().b_a).norm(), 1e-9);
}

// Trapezoidal strapdown integration of the file's IMU from a ground-truth
// state over `steps` samples, with the ground truth's (constant) biases.
StampedState Integrate(const std::vector<ImuSample>& imu, size_t first,
                       size_t steps, const StampedState& start, double g) {
  const Eigen::Vector3d g_w(0.0, 0.0, -g);
  StampedState s = start;
  for (size_t k = first; k < first + steps; ++k) {
    const double dt = static_cast<double>(imu[k + 1].t_ns - imu[k].t_ns) * 1e-9;
    const Eigen::Vector3d w = 0.5 * (imu[k].gyr + imu[k + 1].gyr) - start.b_g;
    const Eigen::Quaterniond q_next =
        (s.q_w_b * ExpQuaternion(w * dt)).normalized();
    const Eigen::Vector3d a0 = s.q_w_b * (imu[k].acc - start.b_a) + g_w;
    const Eigen::Vector3d a1 = q_next * (imu[k + 1].acc - start.b_a) + g_w;
    s.p_w_b += s.v_w * dt + 0.25 * (a0 + a1) * dt * dt;
    s.v_w += 0.5 * (a0 + a1) * dt;
    s.q_w_b = q_next;
    s.t_ns = imu[k + 1].t_ns;
  }
  return s;
}

TEST(SimFolder, NoiselessImuIntegratesBackToTheGroundTruth) {
  TempFolder dir;
  SimulatorOptions options;
  options.duration_s = 20.0;
  options.imu.add_noise = false;
  SimulateToFolder(options, dir.path());
  const EurocSequence seq = LoadEurocSequence(dir.path());
  const std::vector<ImuSample>& imu = seq.data.imu;
  const std::vector<StampedState>& gt = seq.data.ground_truth;
  ASSERT_EQ(imu.size(), gt.size());
  // One-second windows over the still start, the blend and the motion.
  double worst_p = 0.0, worst_v = 0.0, worst_r = 0.0;
  constexpr size_t kWindow = 200;
  for (size_t first = 0; first + kWindow < imu.size(); first += kWindow) {
    const StampedState end =
        Integrate(imu, first, kWindow, gt[first], options.gravity_m_s2);
    const StampedState& truth = gt[first + kWindow];
    ASSERT_EQ(end.t_ns, truth.t_ns);
    worst_p = std::max(worst_p, (end.p_w_b - truth.p_w_b).norm());
    worst_v = std::max(worst_v, (end.v_w - truth.v_w).norm());
    worst_r = std::max(worst_r, end.q_w_b.angularDistance(truth.q_w_b));
  }
  // Trapezoidal steps of 5 ms leave O(dt^2) errors: ~1e-5 relative to the
  // motion's scales over a second; a wrong sign or frame would leave metres.
  EXPECT_LT(worst_p, 1e-4);
  EXPECT_LT(worst_v, 1e-4);
  EXPECT_LT(worst_r, 1e-5);
  std::cout << "worst errors: p " << worst_p << " m, v " << worst_v
            << " m/s, R " << worst_r << " rad\n";
}

TEST(SimFolder, ObservationBuilderRecoversTheTrueBearingsAndVelocities) {
  TempFolder dir;
  SimulatorOptions options = ShortStereo(4.0);
  options.camera.pixel_noise_px = 0.0;
  const Simulation sim = SimulateToFolder(options, dir.path());
  const EurocSequence seq = LoadEurocSequence(dir.path());
  std::vector<CameraModel> models;
  for (const CameraCalibration& c : seq.cameras) models.emplace_back(c);
  ObservationBuilder builder(models);
  std::map<int64_t, StampedState> truth;
  for (const StampedState& s : sim.ground_truth) truth[s.t_ns] = s;
  // True normalised coordinates of a feature in a camera at a stamp.
  auto true_xy = [&](const FeatureObservation& obs, int64_t t_ns) {
    const StampedState& s = truth.at(t_ns);
    const CameraCalibration& c = seq.cameras[obs.camera];
    const Eigen::Vector3d p_c =
        c.q_b_c.conjugate() *
        (s.q_w_b.conjugate() *
             (sim.landmarks_w[sim.landmark_of_feature[obs.feature_id]] -
              s.p_w_b) -
         c.t_b_c);
    return Eigen::Vector2d(p_c.head<2>() / p_c.z());
  };
  int with_velocity = 0;
  for (FeatureFrame frame : MergedFeatureFrames(seq.data)) {
    builder.Process(&frame);
    for (const FeatureObservation& obs : frame.observations) {
      ASSERT_LT((obs.xy - true_xy(obs, frame.t_ns)).norm(), 1e-8);
      if (obs.velocity.isZero()) continue;
      ++with_velocity;
      const Eigen::Vector2d expected =
          (true_xy(obs, frame.t_ns) - true_xy(obs, frame.t_ns - 50000000)) /
          0.05;
      ASSERT_LT((obs.velocity - expected).norm(), 1e-6);
    }
  }
  EXPECT_GT(with_velocity, 10000);
  EXPECT_EQ(builder.summary().failed_undistortion, 0);
}

}  // namespace
}  // namespace vio
