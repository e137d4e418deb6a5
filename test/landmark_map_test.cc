// The estimator's mapped landmarks (estimator/landmark_map.h) against the
// simulator's true landmarks: after the posyaw alignment that maps the
// estimated trajectory onto the truth, the well-triangulated landmarks must
// lie where the simulator put the landmarks their tracks followed. And the
// landmarks taken as the run goes (as vio_replay writes landmarks.csv) are
// those of the whole map.

#include "estimator/landmark_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "config/estimator_config.h"
#include "dataset/landmarks_io.h"
#include "estimator/sequence_runner.h"
#include "eval/alignment.h"
#include "eval/association.h"
#include "testing/sim_replay.h"
#include "testing/temp_folder.h"

namespace vio {
namespace {

// The estimator options of the mono simulation: reuse, or the variant
// config/stereo.yaml ships (world points, at most 50).
EstimatorOptions MonoOptions(const Simulation& sim, bool world_points) {
  EstimatorOptions o = testing::OptionsFor(sim.options);
  if (world_points) {
    o.landmarks.reanchored_tracks = ReanchoredTracks::kKeepPointFirstEstimate;
    o.landmarks.world_points_in_max_landmarks = false;
    o.landmarks.max_world_points = 50;
  }
  return o;
}

class LandmarkMapBoth : public ::testing::TestWithParam<bool> {};

TEST_P(LandmarkMapBoth, MappedLandmarksLieOnTheSimulatedOnes) {
  const Simulation sim = Simulate(testing::ShortSimulation(10.0, false));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  Estimator estimator(MonoOptions(sim, GetParam()), VisualFactorOptions(),
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

// A world point (keep_point): recorded at conversion, then as each solve
// leaves it, replacing its earlier record whatever the sightings still in
// the window; its angle over every sighting it had. Capped (forgotten by
// the window) while its track goes on, the restarted landmark under the
// same id is the same point: one record, the better triangulated.
TEST(LandmarkMap, WorldPointKeepsItsLatestEstimateAndOneRecordPerTrack) {
  TwoViewMap m;  // recorded at (0.5, 0, 5) as frame 0 leaves
  Landmark& l = m.features.landmarks().at(7);
  l.world_point = true;  // converted as the window does
  l.triangulated = false;
  l.p_w = {0.5, 0.0, 5.0};
  m.map.RecordAnchoredIn(m.features, 0, m.T_w_c);
  m.features.RemoveFrame(0, m.T_w_c);
  // Seen again from x = 2; the solve moves the point to z = 4.9.
  FeatureObservation o;
  o.feature_id = 7;
  o.xy = {(0.5 - 2.0) / 4.9, 0.0};
  m.features.AddFrame(2, {o});
  m.features.landmarks().at(7).p_w = {0.5, 0.0, 4.9};
  m.map.RecordWorldPoints(m.features, m.T_w_c, {7});
  const auto angle_deg = [](double z, double x0, double x1) {
    return (std::atan(std::abs(0.5 - x0) / z) +
            std::atan(std::abs(0.5 - x1) / z)) *
           180.0 / M_PI;
  };
  MappedLandmark now = m.map.WithWindow(m.features, m.T_w_c).at(7);
  EXPECT_LT((now.p_w - Eigen::Vector3d(0.5, 0.0, 4.9)).norm(), 1e-12);
  // Over x = 0 and x = 2 (frame 0 has left): wider than frames 1 and 2.
  EXPECT_NEAR(now.parallax_deg, angle_deg(4.9, 0.0, 2.0), 1e-9);
  EXPECT_EQ(now.sightings, 3);
  // The next solve moves it away to z = 5.2: a narrower angle over the same
  // sightings, still the better estimate.
  m.features.landmarks().at(7).p_w = {0.5, 0.0, 5.2};
  m.map.RecordWorldPoints(m.features, m.T_w_c, {7});
  now = m.map.WithWindow(m.features, m.T_w_c).at(7);
  EXPECT_LT((now.p_w - Eigen::Vector3d(0.5, 0.0, 5.2)).norm(), 1e-12);
  EXPECT_NEAR(now.parallax_deg, angle_deg(5.2, 0.0, 2.0), 1e-9);
  // Capped: the window forgets it; its track restarts in frames 3 and 4,
  // triangulated at z = 5 over a narrower angle.
  m.features.Forget(7);
  for (int64_t frame = 3; frame < 5; ++frame) {
    o.xy = {(0.5 - static_cast<double>(frame)) / 5.0, 0.0};
    m.features.AddFrame(frame, {o});
  }
  EXPECT_EQ(m.features.TriangulateNew(m.T_w_c, TriangulationOptions()), 1);
  m.map.Retire(m.features, {7});
  EXPECT_TRUE(m.map.TakeFinished().empty());  // the track goes on
  now = m.map.WithWindow(m.features, m.T_w_c).at(7);
  EXPECT_LT((now.p_w - Eigen::Vector3d(0.5, 0.0, 5.2)).norm(), 1e-12);
  m.map.RecordAnchoredIn(m.features, 3, m.T_w_c);
  m.features.Clear();
  m.map.Retire(m.features, {});
  const std::map<int64_t, MappedLandmark> taken = m.map.TakeFinished();
  ASSERT_EQ(taken.size(), 1u);
  EXPECT_LT((taken.at(7).p_w - Eigen::Vector3d(0.5, 0.0, 5.2)).norm(), 1e-12);
  EXPECT_NEAR(taken.at(7).parallax_deg, angle_deg(5.2, 0.0, 2.0), 1e-9);
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
TEST_P(LandmarkMapBoth, LandmarksTakenAsTheRunGoesAreTheWholeMap) {
  const Simulation sim = Simulate(testing::ShortSimulation(10.0, false));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  const auto make = [&] {
    return Estimator(MonoOptions(sim, GetParam()), VisualFactorOptions(),
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

INSTANTIATE_TEST_SUITE_P(ReuseAndWorldPoints, LandmarkMapBoth,
                         ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? "KeepPointFej" : "Reuse";
                         });

// What a run's map holds against the simulator's truth, streamed as
// vio_replay writes landmarks.csv (TakeFinishedLandmarks after every frame,
// MappedLandmarks at the end).
struct MapFigures {
  size_t triangulated = 0;  // ids the window ever held triangulated
  size_t mapped = 0;        // ids written
  size_t written_twice = 0;
  double median_error_m = 0.0;       // all, after the posyaw alignment
  double median_error_wide_m = 0.0;  // triangulation angle >= 5 deg
  size_t wide = 0;
  double median_late = 0.0;  // frames from a track's last sighting to its
  double worst_late = 0.0;   // hand-over, of those handed over in the run
  size_t taken_during_run = 0;
  int64_t capped = 0;
};

enum class Tracks { kAsShipped, kVariant, kReuse };

MapFigures MeasureMap(bool stereo, const std::string& config, Tracks tracks) {
  const Simulation sim = Simulate(testing::ShortSimulation(10.0, stereo));
  const testing::PreparedSimulation prepared = testing::Prepare(sim);
  EstimatorOptions options = ReadEstimatorOptions(
      YamlNode::LoadFile(std::string(VIO_SOURCE_DIR) + "/config/" + config));
  options.gravity_magnitude = sim.options.gravity_m_s2;
  if (tracks == Tracks::kReuse) {
    options.landmarks.reanchored_tracks = ReanchoredTracks::kReuse;
  }
  if (tracks == Tracks::kVariant) {  // the three keys as in stereo.yaml
    options.landmarks.reanchored_tracks =
        ReanchoredTracks::kKeepPointFirstEstimate;
    options.landmarks.world_points_in_max_landmarks = false;
    options.landmarks.max_world_points = 50;
  }
  Estimator estimator(options, VisualFactorOptions(), sim.options.imu.noise,
                      PreintegrationOptions(), prepared.cameras);
  std::map<int64_t, size_t> last_seen;  // frame index
  std::set<int64_t> triangulated;
  std::map<int64_t, MappedLandmark> written;
  std::vector<double> late;
  MapFigures f;
  const auto take = [&](const std::map<int64_t, MappedLandmark>& taken) {
    for (const auto& [id, m] : taken) {
      if (written.count(id) != 0) ++f.written_twice;
      written[id] = m;
    }
  };
  const std::vector<EstimatorOutput> outputs = RunSequence(
      &estimator, sim.imu, prepared.frames,
      [&](size_t k, const EstimatorOutput&) {
        for (const FeatureObservation& o : prepared.frames[k].observations) {
          last_seen[o.feature_id] = k;
        }
        const std::map<int64_t, MappedLandmark> taken =
            estimator.TakeFinishedLandmarks();
        for (const auto& [id, m] : taken) {
          late.push_back(static_cast<double>(k - last_seen[id]));
        }
        f.taken_during_run += taken.size();
        take(taken);
        for (const auto& [id, m] : estimator.MappedLandmarks()) {
          triangulated.insert(id);
        }
      });
  take(estimator.TakeFinishedLandmarks());
  take(estimator.MappedLandmarks());
  EXPECT_EQ(estimator.summary().resets, 0);
  for (const auto& [id, m] : written) triangulated.insert(id);
  f.triangulated = triangulated.size();
  f.mapped = written.size();
  f.capped = estimator.summary().points_capped;

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
  std::vector<double> all, wide;
  for (const auto& [id, m] : written) {
    const Eigen::Vector3d p_w = align.R_w_e * m.p_w + align.t_w_e;
    const double e =
        (p_w - sim.landmarks_w[sim.landmark_of_feature[id]]).norm();
    all.push_back(e);
    if (m.parallax_deg >= 5.0) wide.push_back(e);
  }
  const auto median = [](std::vector<double> v) {
    if (v.empty()) return 1e9;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  f.median_error_m = median(all);
  f.median_error_wide_m = median(wide);
  f.wide = wide.size();
  f.median_late = median(late);
  f.worst_late =
      late.empty() ? 0.0 : *std::max_element(late.begin(), late.end());
  std::printf(
      "%s %s: %zu of %zu triangulated mapped, %zu written twice, median "
      "error %.3f m (%zu at >= 5 deg: %.3f m), %zu handed over in the run "
      "%.0f frames after the last sighting (median, worst %.0f), %lld "
      "capped\n",
      config.c_str(),
      tracks == Tracks::kReuse
          ? "reuse"
          : (tracks == Tracks::kVariant ? "keep_point_fej 50" : "as shipped"),
      f.mapped, f.triangulated, f.written_twice, f.median_error_m, f.wide,
      f.median_error_wide_m, f.taken_during_run, f.median_late, f.worst_late,
      static_cast<long long>(f.capped));
  return f;
}

// The map of a run whose world points (keep_point_fej, at most 50 after a
// marginalisation, some capped) are converted, marginalised and capped:
// every landmark the window triangulated is in it, once, the well
// triangulated ones where the simulator put them.
void ExpectWholeMap(const MapFigures& f) {
  EXPECT_GT(f.capped, 0) << "no world point capped: the case is not run";
  EXPECT_GE(static_cast<double>(f.mapped), 0.92 * f.triangulated)
      << f.mapped << " of " << f.triangulated;
  EXPECT_EQ(f.written_twice, 0u);
  EXPECT_GT(f.wide, 30u);
  EXPECT_LT(f.median_error_wide_m, 0.10);
  EXPECT_GT(f.taken_during_run, f.mapped / 2);
}

TEST(LandmarkMap, StereoWorldPointsLieOnTheSimulatedOnes) {
  ExpectWholeMap(MeasureMap(true, "stereo.yaml", Tracks::kAsShipped));
}

// Held out (the bounds above were chosen on the stereo run): the mono
// configuration with the three landmark keys of stereo.yaml.
TEST(LandmarkMap, MonoWorldPointsLieOnTheSimulatedOnes) {
  ExpectWholeMap(MeasureMap(false, "default.yaml", Tracks::kVariant));
}

// The figures of reuse, for docs/ (not a bound: reuse is tested above).
TEST(LandmarkMap, ReuseFigures) {
  MeasureMap(true, "stereo.yaml", Tracks::kReuse);
  MeasureMap(false, "default.yaml", Tracks::kAsShipped);
}

}  // namespace
}  // namespace vio
