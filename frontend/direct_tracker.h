#ifndef VIO_FRONTEND_DIRECT_TRACKER_H_
#define VIO_FRONTEND_DIRECT_TRACKER_H_

// Direct (photometric) tracking of a frame against a keyframe: the notes'
// Algorithm 3, TrackFrame, coarse to fine over the image pyramid.
//
// At each level from coarsest_level down to finest_level the problem of
// frontend/photometric_alignment.h is minimised over delta = T_t_h (and the
// target images' brightness) by one of two solvers:
//
// kNotesLm, the notes' Levenberg-Marquardt by hand. With H, g the normal
// equations at the current state (eq. 4) it repeats, for i = 1 .. k_max:
//   solve (H + lambda diag(H)) step = -g   (Eigen's Cholesky, LLT)
//   take the candidate state (+) step, evaluate its error (weights W_m
//   re-computed there, as the notes' "error = calcweight");
//   error < last error: accept; lambda <- 0 if lambda <= 0.2 else lambda / 2;
//                       the level ends if the step was shorter than
//                       epsilon_1 (min_step);
//   otherwise:          the level ends if the step was shorter than
//                       epsilon_1; lambda <- 0.2 if lambda == 0 else
//                       2 lambda; solve again from the same state (the
//                       level ends once lambda exceeds max_lambda).
// The damping multiplies H's diagonal by (1 + lambda) (Marquardt's scaling,
// which the notes' lambda values 0.2 and "doubled" imply for a problem whose
// unknowns mix metres, radians and grey levels; LSD-SLAM's SE3Tracker does
// the same).
//
// kCeres, the alternative: the same residuals as PhotometricFactors
// (factors/photometric_factor.h) in a ceres::Problem solved by Ceres'
// Levenberg-Marquardt, with W_m and the Huber kernel fixed at the level's
// starting state.
//
// Both report the notes' iteration log (iteration, error, lambda) per level
// as data; tools print it.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "frontend/direct_keyframe.h"
#include "frontend/direct_options.h"
#include "frontend/photometric_alignment.h"

namespace vio {

// One row of the iteration log. Iteration 0 of a level is its starting
// state; every later row is one solve: the candidate's error, the lambda it
// was solved with and whether it was accepted. As in the notes, iteration i
// is the i-th linearisation: its rejected solves share its number (the inner
// "while true" loop). For kCeres, a row is one of Ceres' iterations, its
// lambda 1 / trust-region radius.
struct TrackIteration {
  int level = 0;
  int iteration = 0;
  double error = 0.0;   // mean robust cost of the candidate [-]
  double lambda = 0.0;  // damping the step was solved with [-]
  bool accepted = false;
  double step_norm = 0.0;  // |pose part of the step| [m and rad]
  int residuals = 0;       // active residuals at the candidate
};

struct TrackResult {
  bool ok = false;      // false: too few residuals at the finest level
  std::string failure;  // why, when not ok
  AlignmentState state;
  std::vector<TrackIteration> log;
  double error = 0.0;    // final mean robust cost at the finest level [-]
  int residuals = 0;     // active residuals there
  double overlap = 0.0;  // fraction of its points inside the left target
};

class DirectTracker {
 public:
  // Throws std::invalid_argument when the options do not validate.
  explicit DirectTracker(const DirectTrackerOptions& options);

  // Aligns the frame (left pyramid, and optionally its right pyramid with
  // T_r_l, the right camera from the left) to the keyframe, starting from
  // `initial`. Both pyramids need the keyframe's levels up to
  // coarsest_level; levels where the keyframe has no points are skipped.
  TrackResult Track(const DirectKeyframe& keyframe, const ImagePyramid& left,
                    const ImagePyramid* right, const Eigen::Isometry3d& T_r_l,
                    const AlignmentState& initial) const;

  const DirectTrackerOptions& options() const { return options_; }

 private:
  // One level with each solver; both update *state and append to *log.
  // They return false when the level had too few residuals.
  bool SolveNotesLm(const PhotometricAlignment& problem, int level,
                    AlignmentState* state,
                    std::vector<TrackIteration>* log) const;
  bool SolveCeres(const PhotometricAlignment& problem, int level,
                  AlignmentState* state,
                  std::vector<TrackIteration>* log) const;

  DirectTrackerOptions options_;
};

}  // namespace vio

#endif  // VIO_FRONTEND_DIRECT_TRACKER_H_
