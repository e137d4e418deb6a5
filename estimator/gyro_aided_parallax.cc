#include "estimator/gyro_aided_parallax.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace vio {

double TrackParallaxPx(const GyroAidedProblem& problem,
                       const GyroAidedSolution& solution,
                       const GyroAidedTrack& track) {
  const Eigen::Matrix3d R_b_c = problem.T_b_c.linear();
  const GyroAidedSighting& a = track.sightings.front();
  const Eigen::Matrix3d R_v_ca =
      FrameState(problem, solution, a.frame).R_v_b * R_b_c;
  const Eigen::Vector3d ray_v =
      R_v_ca * Eigen::Vector3d(a.xy.x(), a.xy.y(), 1.0);
  double largest = 0.0;
  for (size_t i = 1; i < track.sightings.size(); ++i) {
    const GyroAidedSighting& s = track.sightings[i];
    const Eigen::Matrix3d R_v_c =
        FrameState(problem, solution, s.frame).R_v_b * R_b_c;
    const Eigen::Vector3d ray_c = R_v_c.transpose() * ray_v;
    const double px =
        ray_c.z() > 0.0 ? problem.focal_px * (ray_c.hnormalized() - s.xy).norm()
                        : std::numeric_limits<double>::infinity();
    largest = std::max(largest, px);
  }
  return largest;
}

double MedianRotationParallaxPx(const GyroAidedProblem& problem,
                                const Eigen::Vector3d& b_g) {
  if (problem.tracks.empty()) return 0.0;
  // Only the attitudes matter: v_0, g and b_a stay zero.
  GyroAidedSolution at;
  at.b_g = b_g;
  std::vector<double> parallax;
  parallax.reserve(problem.tracks.size());
  for (const GyroAidedTrack& t : problem.tracks) {
    parallax.push_back(TrackParallaxPx(problem, at, t));
  }
  const size_t mid = parallax.size() / 2;
  std::nth_element(parallax.begin(), parallax.begin() + mid, parallax.end());
  return parallax[mid];
}

}  // namespace vio
