#include "estimator/gyro_aided_parallax.h"

#include <algorithm>
#include <limits>
#include <vector>

namespace vio {

double TrackParallaxPx(const std::vector<Eigen::Matrix3d>& R_v_c,
                       double focal_px, const GyroAidedTrack& track) {
  const GyroAidedSighting& a = track.sightings.front();
  const Eigen::Vector3d ray_v =
      R_v_c[a.frame] * Eigen::Vector3d(a.xy.x(), a.xy.y(), 1.0);
  double largest = 0.0;
  for (size_t i = 1; i < track.sightings.size(); ++i) {
    const GyroAidedSighting& s = track.sightings[i];
    const Eigen::Vector3d ray_c = R_v_c[s.frame].transpose() * ray_v;
    const double px = ray_c.z() > 0.0
                          ? focal_px * (ray_c.hnormalized() - s.xy).norm()
                          : std::numeric_limits<double>::infinity();
    largest = std::max(largest, px);
  }
  return largest;
}

double TrackParallaxPx(const GyroAidedProblem& problem,
                       const GyroAidedSolution& solution,
                       const GyroAidedTrack& track) {
  std::vector<Eigen::Matrix3d> R_v_c(problem.NumFrames());
  for (const GyroAidedSighting& s : track.sightings) {
    R_v_c[s.frame] =
        FrameState(problem, solution, s.frame).R_v_b * problem.T_b_c.linear();
  }
  return TrackParallaxPx(R_v_c, problem.focal_px, track);
}

double MedianRotationParallaxPx(const GyroAidedProblem& problem,
                                const GyroAidedAttitudes& attitudes,
                                const Eigen::Vector3d& b_g) {
  if (problem.tracks.empty()) return 0.0;
  const std::vector<Eigen::Matrix3d> R_v_c =
      attitudes.CameraAttitudes(b_g, problem.T_b_c.linear());
  std::vector<double> parallax;
  parallax.reserve(problem.tracks.size());
  for (const GyroAidedTrack& t : problem.tracks) {
    parallax.push_back(TrackParallaxPx(R_v_c, problem.focal_px, t));
  }
  const size_t mid = parallax.size() / 2;
  std::nth_element(parallax.begin(), parallax.begin() + mid, parallax.end());
  return parallax[mid];
}

}  // namespace vio
