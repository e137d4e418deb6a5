#include "dataset/flight_simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>

#include "config/recorded_flight.h"
#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "dataset/sim_folder.h"
#include "dataset/trajectory_io.h"
#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"
#include "testing/temp_folder.h"

namespace vio {
namespace {

std::string Data(const std::string& sequence) {
  return std::string(VIO_SHARED_DIR) + "/data/" + sequence;
}

// The first `seconds` of the flight's ground truth only (keeps tests fast).
RecordedFlight Shortened(RecordedFlight flight, double seconds) {
  const int64_t end =
      flight.ground_truth.front().t_ns + static_cast<int64_t>(seconds * 1e9);
  while (flight.ground_truth.back().t_ns > end) flight.ground_truth.pop_back();
  return flight;
}

TEST(FlightSimulation, SyntheticImuIntegratesBackToTheCurve) {
  // MH_01's hand-held start: 6.9 s of 200 Hz TUM ground truth, no IMU. A
  // noise-free synthetic IMU, preintegrated over 0.5 s intervals, must carry
  // the curve's state at the start of an interval to its state at the end.
  const RecordedFlight flight =
      LoadRecordedFlight(Data("euroc_MH_01_moving_6s"), "");
  ASSERT_TRUE(flight.imu.empty());
  SimulatorOptions preset;
  preset.imu.add_noise = false;
  const FlightSimulation f = SimulateFlight(preset, FlightOptions(), flight);
  const Simulation& sim = f.simulation;
  ASSERT_GT(sim.imu.size(), 1000u);
  const Eigen::Vector3d g_w(0.0, 0.0, -preset.gravity_m_s2);
  double worst_p = 0.0, worst_v = 0.0, worst_r = 0.0;
  for (size_t i = 0; i + 100 < sim.ground_truth.size(); i += 100) {
    const StampedState& a = sim.ground_truth[i];
    const StampedState& b = sim.ground_truth[i + 100];
    const ImuPreintegration pre(a.t_ns, b.t_ns, sim.imu, a.b_a, a.b_g,
                                preset.imu.noise, PreintegrationOptions());
    const double T = pre.sum_dt();
    const ImuDelta& d = pre.delta();
    const Eigen::Matrix3d R = a.q_w_b.toRotationMatrix();
    const Eigen::Vector3d p = a.p_w_b + a.v_w * T + 0.5 * g_w * T * T + R * d.p;
    const Eigen::Vector3d v = a.v_w + g_w * T + R * d.v;
    worst_p = std::max(worst_p, (p - b.p_w_b).norm());
    worst_v = std::max(worst_v, (v - b.v_w).norm());
    worst_r =
        std::max(worst_r, Log(b.q_w_b.conjugate() * a.q_w_b * d.q).norm());
  }
  // Midpoint integration at 200 Hz of up to 23 deg/s and 3 m/s^2.
  EXPECT_LT(worst_p, 1e-4);  // [m]
  EXPECT_LT(worst_v, 1e-3);  // [m/s]
  EXPECT_LT(worst_r, 1e-4);  // [rad]
  // The cameras and frame stamps are the folder's.
  EXPECT_TRUE(f.cameras_from_folder);
  EXPECT_EQ(f.recorded_frames, 120);
  // Close to the budget of 150 (the floor, half a metre below the
  // hand-held camera, fills the image's lower part only sparsely).
  EXPECT_GT(sim.summary.mean_cam0_observations, 110.0);
}

TEST(FlightSimulation, RecordedImuPassesThroughUnchanged) {
  // V1_01: the whole IMU (145.6 s), the ground truth cut to 10 s.
  const RecordedFlight flight =
      Shortened(LoadRecordedFlight(Data("euroc_V1_01_first5s"), ""), 10.0);
  FlightOptions options;
  options.imu = FlightImu::kRecorded;
  SimulatorOptions preset;
  preset.camera.stereo = true;
  const FlightSimulation f = SimulateFlight(preset, options, flight);
  const Simulation& sim = f.simulation;
  const int64_t first = flight.ground_truth.front().t_ns;
  const int64_t last = flight.ground_truth.back().t_ns;
  std::vector<ImuSample> expected;
  for (const ImuSample& s : flight.imu) {
    if (s.t_ns >= first && s.t_ns <= last) expected.push_back(s);
  }
  ASSERT_EQ(sim.imu.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k) {
    ASSERT_EQ(sim.imu[k].t_ns, expected[k].t_ns);
    ASSERT_EQ(sim.imu[k].acc, expected[k].acc) << k;
    ASSERT_EQ(sim.imu[k].gyr, expected[k].gyr) << k;
  }
  // ... and through the written folder, bit for bit.
  testing::TempFolder folder;
  WriteSimulationFolder(sim, folder.path());
  const std::vector<ImuSample> read =
      ReadEurocImu(JoinPath(folder.path(), "mav0/imu0/data.csv"));
  ASSERT_EQ(read.size(), expected.size());
  for (size_t k = 0; k < read.size(); ++k) {
    ASSERT_EQ(read[k].acc, expected[k].acc) << k;
    ASSERT_EQ(read[k].gyr, expected[k].gyr) << k;
  }
  // The ground truth carries the recorded biases; the IMU noise written is
  // the folder's sensor.yaml's.
  EXPECT_LT(
      (sim.ground_truth.front().b_g - flight.ground_truth.front().b_g).norm(),
      1e-9);
  EXPECT_EQ(sim.options.imu.noise.accelerometer_noise_density,
            flight.imu_noise.accelerometer_noise_density);
  // 95 recorded frames (4.7 s), then 20 Hz up to 10 s (both ends).
  EXPECT_EQ(f.recorded_frames, 95);
  EXPECT_EQ(sim.frames.size(), 201u);
}

TEST(FlightSimulation, RoomEnclosesTheFlightAndClutterKeepsClear) {
  const RecordedFlight flight =
      Shortened(LoadRecordedFlight(Data("euroc_MH_05_imu_gt"), ""), 30.0);
  const FlightSimulation f =
      SimulateFlight(SimulatorOptions(), FlightOptions(), flight);
  const FlightRoomOptions room;
  for (const StampedState& s : f.simulation.ground_truth) {
    const Eigen::Vector3d lo = f.room.min_corner, hi = f.room.max_corner;
    ASSERT_TRUE((s.p_w_b.array() >= lo.array() + room.floor_margin_m).all());
    ASSERT_TRUE((s.p_w_b.array() <= hi.array() - room.floor_margin_m).all());
  }
  const std::vector<Eigen::Vector3d>& l = f.simulation.landmarks_w;
  ASSERT_EQ(static_cast<int>(l.size()),
            f.room.surface_landmarks + f.room.clutter_landmarks);
  EXPECT_GT(f.room.clutter_landmarks, 100);
  for (size_t k = f.room.surface_landmarks; k < l.size(); k += 7) {
    for (size_t i = 0; i < f.simulation.ground_truth.size(); i += 20) {
      ASSERT_GE((l[k] - f.simulation.ground_truth[i].p_w_b).norm(),
                room.clutter_clearance_m - 0.05);
    }
  }
}

// With the curve fitted to the ground truth and the IMU, the folder is
// consistent: the written IMU, less the written (fitted) biases, integrates
// to the written ground truth's rotation over every second.
TEST(FlightSimulation, JointCurveMovesAsTheRecordedImuSays) {
  const RecordedFlight flight =
      Shortened(LoadRecordedFlight(Data("euroc_MH_05_imu_gt"), ""), 3.0);
  FlightOptions options;
  options.imu = FlightImu::kRecorded;
  options.fit = FlightCurve::kGroundTruthAndImu;
  const FlightSimulation f =
      SimulateFlight(SimulatorOptions(), options, flight);
  ASSERT_TRUE(f.imu_fitted);
  EXPECT_LT(f.imu_fit.position_rms_m, 6e-3);
  const std::vector<ImuSample>& imu = f.simulation.imu;
  const std::vector<StampedState>& truth = f.simulation.ground_truth;
  ASSERT_EQ(imu.size(), truth.size());
  double worst = 0.0;
  for (size_t first = 0; first + 200 < imu.size(); first += 50) {
    Eigen::Quaterniond integrated = Eigen::Quaterniond::Identity();
    for (size_t k = first; k < first + 200; ++k) {
      const double dt =
          static_cast<double>(imu[k + 1].t_ns - imu[k].t_ns) * 1e-9;
      const Eigen::Vector3d w = 0.5 * (imu[k].gyr + imu[k + 1].gyr) -
                                0.5 * (truth[k].b_g + truth[k + 1].b_g);
      integrated = integrated * ExpQuaternion(w * dt);
    }
    const Eigen::Quaterniond moved =
        truth[first].q_w_b.conjugate() * truth[first + 200].q_w_b;
    worst = std::max(worst, Log(integrated.conjugate() * moved).norm());
  }
  // Measured 0.05 mrad; the ground truth's own curve gives 0.33 mrad.
  EXPECT_LT(worst, 1.5e-4) << "worst second " << worst << " rad";
  FlightOptions synthetic = options;
  synthetic.imu = FlightImu::kSynthetic;
  try {
    SimulateFlight(SimulatorOptions(), synthetic, flight);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("needs the recorded IMU"),
              std::string::npos)
        << e.what();
  }
}

TEST(FlightSimulation, BadFlightsAreErrorsThatNameTheFolder) {
  EXPECT_THROW(LoadRecordedFlight("/nonexistent/flight", ""), DatasetError);
  const RecordedFlight no_imu =
      LoadRecordedFlight(Data("euroc_MH_01_moving_6s"), "");
  FlightOptions recorded;
  recorded.imu = FlightImu::kRecorded;
  try {
    SimulateFlight(SimulatorOptions(), recorded, no_imu);
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("euroc_MH_01_moving_6s: no IMU"),
              std::string::npos)
        << e.what();
  }
  try {
    LoadRecordedFlight(Data("euroc_MH_01_moving_6s"), "/nonexistent/gt.tum");
    ADD_FAILURE() << "no exception";
  } catch (const DatasetError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/gt.tum"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vio
