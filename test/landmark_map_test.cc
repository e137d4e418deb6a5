// The estimator's mapped landmarks (estimator/landmark_map.h) against the
// simulator's true landmarks: after the posyaw alignment that maps the
// estimated trajectory onto the truth, the well-triangulated landmarks must
// lie where the simulator put the landmarks their tracks followed. And the
// landmarks taken as the run goes (as vio_replay writes landmarks.csv) are
// those of the whole map.

#include "estimator/landmark_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "dataset/landmarks_io.h"
#include "estimator/sequence_runner.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "testing/sim_replay.h"
#include "testing/temp_folder.h"

namespace vio {
namespace {

TEST(LandmarkMap, MappedLandmarksLieOnTheSimulatedOnes) {
  const Simulation sim = Simulate(testing::ShortSimulation(10.0, false));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  Estimator estimator(testing::OptionsFor(sim.options), VisualFactorOptions(),
                      sim.options.imu.noise, PreintegrationOptions(),
                      prepared.cameras);
  const std::vector<EstimatorOutput> outputs =
      RunSequence(&estimator, sim.imu, prepared.frames);
  ASSERT_EQ(estimator.summary().resets, 0);

  Trajectory estimate, truth;
  for (const EstimatorOutput& o : outputs) {
    if (o.processed && o.initialized) {
      estimate.push_back({o.t_ns, o.p_w_b, o.q_w_b});
    }
  }
  for (const StampedState& s : sim.ground_truth) truth.push_back(PoseOf(s));
  const Association a = Associate(estimate, truth);
  const Alignment align =
      Align(a.estimate, a.ground_truth, AlignmentMode::kPosYaw);

  const std::map<int64_t, MappedLandmark> mapped = estimator.MappedLandmarks();
  std::vector<std::pair<double, double>> by_angle;
  for (const auto& [feature_id, m] : mapped) {
    const Eigen::Vector3d& p_e = m.p_w;
    ASSERT_LT(feature_id, static_cast<int64_t>(sim.landmark_of_feature.size()));
    const Eigen::Vector3d p_w = align.R_w_e * p_e + align.t_w_e;
    by_angle.push_back(
        {m.parallax_deg,
         (p_w - sim.landmarks_w[sim.landmark_of_feature[feature_id]]).norm()});
  }
  // Far more than a window holds: the marginalised ones are kept.
  const double most_in_window =
      estimator.summary().landmarks_per_step.Quantile(1.0);
  EXPECT_GT(static_cast<double>(mapped.size()), 3 * most_in_window)
      << mapped.size() << " mapped, at most " << most_in_window
      << " in the window";
  // The depth precision follows the triangulation angle: the landmarks
  // seen over a few degrees are where the simulator put them, the rest
  // (most of them, seen over less than 1 deg) can be metres off.
  const auto median_above = [&](double min_deg) {
    std::vector<double> e;
    for (const auto& [angle, error] : by_angle) {
      if (angle >= min_deg) e.push_back(error);
    }
    std::sort(e.begin(), e.end());
    return e.empty() ? 1e9 : e[e.size() / 2];
  };
  const double all = median_above(0.0);
  const double wide = median_above(5.0);
  EXPECT_LT(wide, 0.15) << "median error at >= 5 deg " << wide << " m";
  EXPECT_LT(wide, 0.5 * all) << "median error of all " << all << " m";
}

// One landmark seen from two frames 1 m apart (cameras at the body, looking
// along z), triangulated at (0.5, 0, 5) and recorded as frame 0 leaves.
struct TwoViewMap {
  FeatureManager features{1};
  LandmarkMap map;
  CameraPoseFn T_w_c = [](int64_t frame_id, int) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation().x() = static_cast<double>(frame_id);
    return T;
  };

  TwoViewMap() {
    for (int64_t frame = 0; frame < 2; ++frame) {
      FeatureObservation o;
      o.feature_id = 7;
      o.xy = {(0.5 - static_cast<double>(frame)) / 5.0, 0.0};
      features.AddFrame(frame, {o});
    }
    EXPECT_EQ(features.TriangulateNew(T_w_c, TriangulationOptions()), 1);
    map.RecordAnchoredIn(features, 0, T_w_c);
  }
};

// A record is handed over once its landmark has left the window and its
// track has ended, never while the newest frame still observes it (an
// outlier removed from the window whose track goes on comes back under the
// same id, and its later record may replace this one).
TEST(LandmarkMap, FinishedOnceOutOfTheWindowAndNoLongerTracked) {
  TwoViewMap m;
  m.map.Retire(m.features, {});  // still in the window
  EXPECT_TRUE(m.map.TakeFinished().empty());
  m.features.RemoveLandmark(7);         // as an outlier
  m.map.Retire(m.features, {3, 7, 9});  // the newest frame still tracks it
  EXPECT_TRUE(m.map.TakeFinished().empty());
  EXPECT_EQ(m.map.WithWindow(m.features, m.T_w_c).size(), 1u);
  m.map.Retire(m.features, {3, 9});  // its track ended
  const std::map<int64_t, MappedLandmark> taken = m.map.TakeFinished();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_LT((taken.at(7).p_w - Eigen::Vector3d(0.5, 0.0, 5.0)).norm(), 1e-9);
  // Handed over once: forgotten afterwards.
  EXPECT_TRUE(m.map.TakeFinished().empty());
  EXPECT_TRUE(m.map.WithWindow(m.features, m.T_w_c).empty());
}

// The lines of a file after its header, sorted: the rows as a set.
std::vector<std::string> SortedRows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> rows;
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) rows.push_back(line);
  std::sort(rows.begin(), rows.end());
  return rows;
}

// vio_replay takes the finished landmarks after every frame and writes them
// at once (LandmarksCsvWriter), then the rest of the map at the end; the
// file must hold the rows of the whole map written at the end, as it did
// before the landmarks were streamed, each once.
TEST(LandmarkMap, LandmarksTakenAsTheRunGoesAreTheWholeMap) {
  const Simulation sim = Simulate(testing::ShortSimulation(10.0, false));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  const auto make = [&] {
    return Estimator(testing::OptionsFor(sim.options), VisualFactorOptions(),
                     sim.options.imu.noise, PreintegrationOptions(),
                     prepared.cameras);
  };
  testing::TempFolder dir;

  Estimator whole = make();
  RunSequence(&whole, sim.imu, prepared.frames);
  ASSERT_GT(whole.summary().outlier_landmarks_removed +
                whole.summary().landmarks_behind_removed,
            0);
  std::vector<LandmarkRow> rows;
  for (const auto& [id, m] : whole.MappedLandmarks()) {
    rows.push_back({m.p_w, m.parallax_deg});
  }
  WriteLandmarksCsv(dir.Path("whole.csv"), rows);

  Estimator streamed = make();
  LandmarksCsvWriter writer(dir.Path("streamed.csv"));
  std::vector<int64_t> ids;  // every id written
  const auto write = [&](const std::map<int64_t, MappedLandmark>& taken) {
    for (const auto& [id, m] : taken) {
      writer.Write({m.p_w, m.parallax_deg});
      ids.push_back(id);
    }
  };
  RunSequence(&streamed, sim.imu, prepared.frames,
              [&](size_t, const EstimatorOutput&) {
                write(streamed.TakeFinishedLandmarks());
              });
  const size_t taken_during_run = ids.size();
  write(streamed.TakeFinishedLandmarks());
  write(streamed.MappedLandmarks());
  writer.Close();

  // Most were written during the run: the map does not hold them to the end.
  EXPECT_GT(taken_during_run, rows.size() / 2)
      << taken_during_run << " of " << rows.size();
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(std::adjacent_find(ids.begin(), ids.end()), ids.end())
      << "a landmark written twice";
  const std::vector<std::string> expected = SortedRows(dir.Path("whole.csv"));
  EXPECT_EQ(SortedRows(dir.Path("streamed.csv")), expected);
  EXPECT_EQ(expected.size(), rows.size());
}

}  // namespace
}  // namespace vio
