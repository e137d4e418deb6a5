#include "test/testing/cut_simulation.h"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <string>

namespace vio {
namespace testing {
namespace {

// The first element of `v` (sorted by t_ns) with t_ns >= t0_ns.
template <typename T>
typename std::vector<T>::const_iterator FirstFrom(const std::vector<T>& v,
                                                  int64_t t0_ns) {
  return std::lower_bound(
      v.begin(), v.end(), t0_ns,
      [](const T& element, int64_t t) { return element.t_ns < t; });
}

}  // namespace

Simulation CutSimulation(const Simulation& simulation, int64_t t0_ns) {
  Simulation cut;
  cut.options = simulation.options;
  cut.landmarks_w = simulation.landmarks_w;
  cut.landmark_of_feature = simulation.landmark_of_feature;
  const auto imu = FirstFrom(simulation.imu, t0_ns);
  const size_t first_imu = static_cast<size_t>(imu - simulation.imu.begin());
  if (simulation.imu.size() < first_imu + 2) {
    throw std::invalid_argument("CutSimulation: t0 " + std::to_string(t0_ns) +
                                " ns leaves fewer than two IMU samples");
  }
  cut.imu.assign(imu, simulation.imu.end());
  cut.imu_true.assign(simulation.imu_true.begin() + first_imu,
                      simulation.imu_true.end());
  cut.ground_truth.assign(FirstFrom(simulation.ground_truth, t0_ns),
                          simulation.ground_truth.end());
  const auto frame = FirstFrom(simulation.frames, t0_ns);
  if (frame == simulation.frames.end()) {
    throw std::invalid_argument("CutSimulation: no frame at or after t0 " +
                                std::to_string(t0_ns) + " ns");
  }
  const size_t first_frame =
      static_cast<size_t>(frame - simulation.frames.begin());
  cut.frames.assign(frame, simulation.frames.end());
  for (FeatureFrame& f : cut.frames) {
    for (FeatureObservation& o : f.observations) {
      o.xy.setZero();
      o.velocity.setZero();
    }
  }
  cut.is_outlier.assign(simulation.is_outlier.begin() + first_frame,
                        simulation.is_outlier.end());

  cut.options.start_time_ns = cut.imu.front().t_ns;
  cut.options.duration_s =
      1e-9 * static_cast<double>(cut.imu.back().t_ns - cut.imu.front().t_ns);
  SimulationSummary& s = cut.summary;
  s.duration_s = cut.options.duration_s;
  s.imu_samples = static_cast<int64_t>(cut.imu.size());
  s.frames = static_cast<int64_t>(cut.frames.size());
  int64_t cam0 = 0;
  std::set<int64_t> ids;  // the tracks seen after t0
  for (size_t i = 0; i < cut.frames.size(); ++i) {
    int n0 = 0;
    for (size_t j = 0; j < cut.frames[i].observations.size(); ++j) {
      const FeatureObservation& o = cut.frames[i].observations[j];
      ++s.observations;
      if (cut.is_outlier[i][j]) ++s.outliers;
      if (o.camera == 0) ++n0;
      ids.insert(o.feature_id);
    }
    cam0 += n0;
    s.max_cam0_observations = std::max(s.max_cam0_observations, n0);
  }
  s.mean_cam0_observations =
      static_cast<double>(cam0) / static_cast<double>(cut.frames.size());
  s.tracks = static_cast<int64_t>(ids.size());
  if (s.tracks > 0) {
    s.mean_track_length =
        static_cast<double>(cam0) / static_cast<double>(s.tracks);
  }
  return cut;
}

}  // namespace testing
}  // namespace vio
