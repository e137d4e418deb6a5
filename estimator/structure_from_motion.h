#ifndef VIO_ESTIMATOR_STRUCTURE_FROM_MOTION_H_
#define VIO_ESTIMATOR_STRUCTURE_FROM_MOTION_H_

// Up-to-scale structure from motion over a few consecutive monocular frames
// (camera 0), the first step of the monocular start in motion (as in
// VINS-Mono's initial SfM, Qin et al., T-RO 2018, sec. V-A):
//   1. the reference pair: the oldest frame l whose features, shared with the
//      newest frame, show enough parallax once the rotation that best
//      explains them is taken out (a pure rotation leaves almost none), and
//      whose essential matrix (OpenCV, RANSAC) has enough inliers in front
//      of both cameras; the relative pose comes from it (|t| = 1);
//   2. the inliers triangulated (estimator/triangulation.h);
//   3. every other frame placed by PnP (OpenCV, RANSAC) on the points known
//      so far, newest-side first, more points triangulated after each;
//   4. a bundle adjustment with Ceres over all poses and inverse depths
//      (the project's ReprojectionFactor with an identity extrinsic, frame l
//      held fixed, the scale left to the damping), Huber-robust;
//   5. outlier sightings out: after the adjustment, the sightings whose
//      reprojection error exceeds outlier_threshold_px are removed (a point
//      with more than half of its sightings bad, whole: ClassifySightings,
//      the rule the running window uses) and the adjustment run again on the
//      rest, up to outlier_rounds times; the RMS check is then on the
//      sightings kept, and the share removed and the points left are
//      checked too, so that a reconstruction that is mostly outliers is
//      still refused, with its own reason.
// The frame v of the result is camera l's; its unit of length is arbitrary.
// The estimator links OpenCV core and calib3d only for this (DESIGN.md).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/init_attempt.h"

namespace vio {

// One frame's camera-0 features: normalised coordinates by feature id.
struct SfmFrame {
  std::map<int64_t, Eigen::Vector2d> xy;
};

struct SfmOptions {
  double focal_px = 460.0;  // turns the pixel thresholds into normalised ones
  double min_parallax_px = 25.0;
  int min_correspondences = 40;
  int min_inliers = 30;
  double ransac_threshold_px = 1.0;
  int min_pnp_inliers = 15;
  double pnp_threshold_px = 3.0;
  double max_reprojection_rms_px = 2.0;
  int bundle_iterations = 15;
  double outlier_threshold_px = 10.0;  // a sighting's error, after the BA
  int outlier_rounds = 3;             // 0: none removed
  double max_outlier_share = 0.2;     // of the sightings adjusted
  double min_ray_angle_deg = 0.5;  // a point's widest pair of rays [deg]
};

struct SfmResult {
  // kNone on success; otherwise why, with the measured value and the limit.
  InitFailure failure = InitFailure::kNone;
  double value = 0.0;
  double limit = 0.0;
  int reference = -1;        // l, paired with the newest frame
  double parallax_px = 0.0;  // of the pair (or the best candidate) [px]
  int inliers = 0;           // essential-matrix inliers in front
  double reprojection_rms_px = 0.0;  // over the sightings kept
  // The outlier rounds: sightings adjusted at first, removed (those of the
  // points removed whole included), and their share.
  int sightings = 0;
  int outlier_sightings = 0;
  double outlier_share = 0.0;
  std::vector<Eigen::Isometry3d> T_v_c;  // per frame, camera in v
  std::map<int64_t, Eigen::Vector3d> points_v;
  // The sightings removed as outliers, as (index into frames, feature id):
  // the start must not hand them on to the window.
  std::vector<std::pair<int, int64_t>> removed;
};

// frames oldest first, at least two. Never throws on bad data: a failure is
// returned as data.
SfmResult SolveStructureFromMotion(const std::vector<SfmFrame>& frames,
                                   const SfmOptions& options);

// Places a camera by PnP (OpenCV solvePnPRansac) on the known points of
// `points` it sees. True with *T_v_c (the camera's pose in v) when at least
// options.min_pnp_inliers agree within options.pnp_threshold_px; *inliers is
// their number either way.
//   - guess == nullptr (the stereo start): RANSAC without a guess, then the
//     points that agree with the pose it returns counted again and the pose
//     refined on them (Levenberg-Marquardt), counted once more.
//   - a guess (the camera's pose in v; the mono SfM, the neighbour's pose):
//     OpenCV's extrinsic guess, its inliers as it reports them. OpenCV 4.6
//     then starts its final refinement from RANSAC's last minimal sample, not
//     its best, and may return a pose its inliers do not agree with: with 5 %
//     outlier sightings, 33-178 deg off (docs/initialisation.md, "The stereo
//     start with outliers"), and 4.5 % of the mono SfM's placements. Kept for
//     the mono start, whose figures and tests were measured with it (without
//     it two of its tests' single trials moved past their bounds and
//     motion_mono's worst start scale went from 28.5 to 34.6 %), but when
//     fewer than options.min_pnp_inliers agree with the pose it returns (or
//     it fails), the camera is placed again as without a guess: on the clean
//     presets that changes no start (docs/initialisation.md, "The mono start
//     in motion with outliers").
bool PlaceCameraByPnp(const SfmFrame& frame,
                      const std::map<int64_t, Eigen::Vector3d>& points,
                      const Eigen::Isometry3d* guess, const SfmOptions& options,
                      Eigen::Isometry3d* T_v_c, int* inliers);

// The median over the correspondences (x_a[i], x_b[i], normalised) of the
// distance left by the rotation R_b_a that best maps the bearings of a onto
// those of b (Kabsch, least squares on unit vectors) [normalised units].
double RotationCompensatedParallax(const std::vector<Eigen::Vector2d>& x_a,
                                   const std::vector<Eigen::Vector2d>& x_b);

}  // namespace vio

#endif  // VIO_ESTIMATOR_STRUCTURE_FROM_MOTION_H_
