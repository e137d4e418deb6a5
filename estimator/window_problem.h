#ifndef VIO_ESTIMATOR_WINDOW_PROBLEM_H_
#define VIO_ESTIMATOR_WINDOW_PROBLEM_H_

// One step's Ceres problem over the window: the IMU factors between
// consecutive frames, the visual factors of the triangulated landmarks (with
// the configured robust kernel) and the marginalisation prior. The problem
// does not own its cost functions: they stay alive here after the solve so
// that the outlier test and the marginalisation can evaluate them at the
// solution.
//
// Visual factors per landmark, from its anchor a (first camera-0 sighting,
// frame i) to each later sighting s (frame j, camera c):
//   j == i, c == 1: StereoReprojectionFactor
//                   blocks T_b_c0, T_b_c1, rho
//   j != i, c == 0: ReprojectionFactor
//                   blocks pose_i, pose_j, T_b_c0, rho
//                   (TimedReprojectionFactor, with t_d after rho, when the
//                   time offset is estimated)
//   j != i, c == 1: StereoTwoFrameReprojectionFactor
//                   blocks pose_i, pose_j, T_b_c0, T_b_c1, rho
//                   (TimedStereoTwoFrameReprojectionFactor, with t_d after
//                   rho, when the time offset is estimated)
// Sightings older than the anchor (camera 1 only) are not used, so only the
// landmarks anchored in a frame have residuals touching that frame: the
// marginalisation of the oldest frame then removes exactly those landmarks,
// and the prior holds no landmark.
//
// With keep_points (landmarks.reanchored_tracks keep_point) a world-point
// landmark (feature_manager.h) has one WorldPointReprojectionFactor per
// sighting, blocks pose_j, T_b_c, p_w (TimedWorldPointReprojectionFactor,
// with t_d after p_w, when the time offset is estimated, camera 0's and
// camera 1's sightings alike); its p_w is a block of the dense
// (not eliminated) system, as the prior may hold it. Its factors come first
// and are always in the problem (they count against max_landmarks unless
// points_in_max_landmarks is false). The
// marginalisation of the oldest frame then folds only that frame's
// sightings of a track that goes on: see OldestFrameMarginalization
// (window_problem_points.cc).

#include <ceres/ceres.h>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>
#include <vector>

#include "estimator/estimator_options.h"
#include "estimator/feature_manager.h"
#include "estimator/marginalization.h"
#include "estimator/window.h"
#include "estimator/window_solver.h"
#include "factors/marginalization_prior.h"
#include "factors/pose_manifold.h"
#include "factors/tangent_jacobians.h"
#include "factors/visual_factor_options.h"

namespace vio {

struct WindowProblemSettings {
  std::array<double, kMaxCameras> focal_px{460.0, 460.0};  // [px]
  VisualFactorOptions visual;
  double gravity_magnitude = 9.81;  // [m/s^2]
  bool estimate_extrinsics = false;
  // Factors between frames become timed (TimedReprojectionFactor,
  // TimedStereoTwoFrameReprojectionFactor) on the window's t_d block; the
  // same-frame stereo factor needs no shift (both cameras, one instant).
  bool estimate_time_offset = false;
  double max_time_offset_s = 0.02;  // |t_d| bound while estimated [s]
  int max_landmarks = 120;
  // landmarks.reanchored_tracks keep_point (see the header comment).
  bool keep_points = false;
  // keep_points: the world-point factors' Jacobians at the point's first
  // estimate (Landmark::p_w_first, factors/world_point_factor.h).
  bool point_first_estimates = false;
  // keep_points: the world points take places of max_landmarks
  // (LandmarkOptions::world_points_in_max_landmarks).
  bool points_in_max_landmarks = true;
  // keep_points: world points left after OldestFrameMarginalization at most
  // (LandmarkOptions::max_world_points; 0: no bound).
  int max_points = 0;
};

// What the outlier test found.
struct OutlierReport {
  struct BadSighting {
    int64_t feature_id = -1;
    int64_t frame_id = -1;
    int camera = 0;
  };
  std::vector<int64_t> landmarks;      // to remove whole, by feature id
  std::vector<BadSighting> sightings;  // to remove, their landmark kept
  // Landmarks whose inverse depth is not positive after the solve: the point
  // lies behind its anchor camera (or at infinity on the wrong side), where
  // the residuals keep pulling on the poses through a projective depth that
  // still looks valid. To remove whole, counted apart from the outliers.
  std::vector<int64_t> behind;
  bool Involves(int64_t feature_id) const;
  bool empty() const {
    return landmarks.empty() && sightings.empty() && behind.empty();
  }
  // Removes what it reports from features: the landmarks and the ones behind
  // whole, then the sightings (a step's slide, the stereo start's rounds).
  void RemoveFrom(FeatureManager* features) const;
};

class WindowProblem {
 public:
  // window and features must outlive this object and must not change shape
  // (frames, landmarks) while it lives; their values are what it solves.
  WindowProblem(Window* window, FeatureManager* features,
                const WindowProblemSettings& settings);

  // The prior (not owned) on its blocks, which must be window blocks.
  void AddPrior(const MarginalizationPrior* prior,
                const std::vector<double*>& blocks);
  // IMU factors between consecutive window frames (none across an IMU gap,
  // where a frame has no interval). Returns false (and adds none) when one
  // cannot be built (a covariance not positive definite).
  bool AddImuFactors();
  // Visual factors of up to max_landmarks landmarks, those with the most
  // sightings first (ties by feature id). Returns the landmarks used.
  int AddVisualFactors();
  // A factor (owned from now on) between two consecutive window frames whose
  // older one is `start_frame`, on window blocks: it leaves with that frame
  // at its marginalisation, like the IMU factor (the zero-motion factor).
  void AddFrameLink(std::unique_ptr<ceres::CostFunction> cost,
                    const std::vector<double*>& blocks, int64_t start_frame);

  // Solves with the options' backend: tcvio's window solver (the inverse
  // depths eliminated, estimator/window_solver.h) or ceres::Solve (threads
  // as given). Either way the summary is a ceres::Solver::Summary. `solver`
  // (optional) is a window solver whose buffers outlive this problem, so
  // that a run of steps does not allocate them again each step.
  ceres::Solver::Summary Solve(const SolverOptions& options,
                               WindowSolver* solver = nullptr);

  // Sightings whose reprojection error at the current values exceeds
  // threshold_px [px]. A landmark where most of its residuals are bad (its
  // anchor is the likely culprit) or one fails to evaluate is listed whole;
  // one with inverse depth <= 0 is listed in `behind`.
  OutlierReport Outliers(double threshold_px) const;

  // The marginalisation of the oldest window frame: its IMU factor, the prior
  // and every visual factor of the landmarks anchored in it; marginalised are
  // its pose and speed-bias blocks and those landmarks' inverse depths.
  // Landmarks with outliers (about to be removed) are left out.
  // With keep_points, a landmark anchored there whose track goes on (a
  // sighting in another frame) is converted into a world point instead
  // (Landmark::world_point and p_w set in the feature manager, at the current
  // estimate): only its sightings in the oldest frame are folded, as
  // world-point factors (owned here, so this problem must outlive the
  // marginalisation), and its point is kept. A world point's factors in the
  // oldest frame are folded too; its point is marginalised when it has no
  // sighting in another frame. With max_points > 0 and more world points
  // left than that, the excess (see CapWorldPoints) is marginalised too,
  // with every sighting it has in the window.
  MarginalizationProblem OldestFrameMarginalization(
      const OutlierReport& excluded) const;
  // The world points the last OldestFrameMarginalization marginalised to
  // keep within max_points (by feature id): the caller forgets them once the
  // marginalisation has succeeded (their sightings are in the prior).
  const std::vector<int64_t>& capped_points() const { return capped_points_; }

  // The problem as a ceres::Problem on the window's blocks, as the Ceres
  // backend solves it (for estimator/pose_covariance.h).
  std::unique_ptr<ceres::Problem> CeresProblem() const;

  int num_visual_residuals() const { return num_visual_; }
  int landmarks_used() const { return landmarks_used_; }
  // Every residual of the problem: visual, IMU, priors and frame links.
  int num_residuals() const { return static_cast<int>(residuals_.size()); }

 private:
  struct Residual {
    const ceres::CostFunction* cost = nullptr;
    std::unique_ptr<ceres::CostFunction> owned;
    const ceres::LossFunction* loss = nullptr;
    const MarginalizationPrior* prior = nullptr;  // priors only: == cost
    const TangentJacobians* tangent = nullptr;    // visual factors: == cost
    std::vector<double*> blocks;
    int64_t feature_id = -1;    // visual residuals only
    double* rho = nullptr;      // inverse-depth visual residuals: rho
    double* point = nullptr;    // world-point visual residuals: p_w
    int64_t target_frame = -1;  // visual residuals: the sighting's frame
    int target_camera = 0;
    int64_t anchor_frame = -1;
    int64_t imu_start_frame = -1;   // IMU residuals only
    int64_t link_start_frame = -1;  // AddFrameLink residuals only
    int first_index = 0;            // its blocks' indices in indices_
  };
  struct BlockInfo {
    int size = 0;
    const ceres::Manifold* manifold = nullptr;
    bool constant = false;
    bool landmark = false;  // an inverse depth: eliminated by the solver
    double bound = 0.0;     // > 0: every coordinate within +-bound
    int index = -1;         // in block_order_
  };

  void AddBlock(double* values, int size, bool pose, bool constant);
  ceres::Solver::Summary SolveWithCeres(const SolverOptions& options);
  // Adds every block (constant, bounded as here) and residual to problem.
  void AddToCeresProblem(ceres::Problem* problem) const;
  // Per block of block_order_: whether any residual has it.
  std::vector<bool> TouchedBlocks() const;
  void AddResidual(Residual residual);
  void AddLandmark(Landmark* landmark);
  // keep_points: the factors of every world point with sightings; returns
  // how many (window_problem_points.cc).
  int AddWorldPoints();
  // The factor of world point l's sighting s (WorldPointReprojectionFactor,
  // or TimedWorldPointReprojectionFactor when the time offset is estimated),
  // its tangent Jacobians in *tangent and its blocks (pose, T_b_c, p_w and
  // t_d when timed) in *blocks.
  std::unique_ptr<ceres::CostFunction> WorldPointFactor(
      Landmark& l, const Sighting& s, const TangentJacobians** tangent,
      std::vector<double*>* blocks) const;
  // keep_points, for OldestFrameMarginalization: converts the landmarks
  // anchored in the oldest frame whose track goes on into world points and
  // returns their ids.
  std::set<int64_t> ConvertLeavingTracks(const OutlierReport& excluded) const;
  // keep_points: adds the converted landmarks' factors in the oldest frame
  // and their point blocks to m (their window blocks to touched), and marks
  // the world points whose track ends there for marginalisation.
  void AddPointMarginalization(const OutlierReport& excluded,
                               const std::set<int64_t>& converted,
                               MarginalizationProblem* m,
                               std::set<const double*>* touched) const;
  // keep_points with max_points > 0: which of the world points left after
  // this marginalisation (`staying`, by feature id) to marginalise so that
  // max_points stay: the excess, those whose last sighting is oldest first,
  // then those with fewer sightings, then by feature id. Those with an
  // outlier are never chosen (the estimator removes or releases them).
  std::vector<int64_t> CapWorldPoints(const std::vector<int64_t>& staying,
                                      const OutlierReport& excluded) const;
  // Image velocity d xy / dt [1/s] of the point p_c [m] in `camera` of
  // frame, predicted from the frame's current state (the timed factors).
  Eigen::Vector2d MotionVelocity(const WindowFrame& frame,
                                 const Eigen::Vector3d& p_c,
                                 int camera = 0) const;

  Window* window_;
  FeatureManager* features_;
  WindowProblemSettings settings_;
  PoseManifold pose_manifold_;
  std::unique_ptr<ceres::LossFunction> loss_;
  std::vector<Residual> residuals_;
  std::unordered_map<const double*, BlockInfo> blocks_;  // lookup only
  std::vector<double*> block_order_;                     // as added
  std::vector<int> indices_;  // every residual's blocks (block_order_ index)
  int num_visual_ = 0;
  int landmarks_used_ = 0;
  // The world-point factors of the landmarks converted by the last
  // OldestFrameMarginalization (referred to by its result).
  mutable std::vector<std::unique_ptr<ceres::CostFunction>> converted_factors_;
  mutable std::vector<int64_t> capped_points_;
};

}  // namespace vio

#endif  // VIO_ESTIMATOR_WINDOW_PROBLEM_H_
