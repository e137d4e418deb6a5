#ifndef VIO_EVAL_METRICS_H_
#define VIO_EVAL_METRICS_H_

// Trajectory error metrics with evo's definitions (evo/core/metrics.py,
// filters.py). The inputs are associated trajectories (element i with element
// i, see association.h), the estimate already aligned (alignment.h).
//
// ATE (evo_ape): per pose i, with P the aligned estimate and Q the ground
// truth,
//   translation  e_i = |p(Q_i) - p(P_i)|                         [m]
//   rotation     e_i = angle(R(P_i)^T R(Q_i))                    [deg]
// (evo_ape's `translation_part` and `angle_deg` pose relations).
//
// RPE (evo_rpe): for index pairs (i, j) chosen on the estimate,
//   E_ij = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j)
//   translation  |t(E_ij)|  [m],   rotation  angle(R(E_ij))  [deg].
// (E_ij^-1 = (P_i^-1 P_j)^-1 (Q_i^-1 Q_j) has the same translation norm and
// angle, so either order gives the same figures.)
// Pairs, evo's consecutive (not all-pairs) mode:
//   frames  i = 0, d, 2d, ...; pairs (0, d), (d, 2d), ...
//   meters  walk the estimate summing |p_k - p_{k-1}|; each index where the
//           sum reaches delta is marked and the sum restarts from 0 there;
//           pairs are consecutive marks. (So the first pair starts at the first
//           mark, not at index 0: evo's filter_pairs_by_path.)

#include <cstddef>
#include <utility>
#include <vector>

#include "dataset/trajectory.h"

namespace vio {

// evo's statistics of a set of errors: rmse = sqrt(mean(e^2)), mean, median
// (mean of the two middle values for an even count), std (population, 1/n),
// min, max. With count == 0 every figure is NaN.
struct ErrorStats {
  size_t count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;
  double min = 0.0;
  double max = 0.0;
};
ErrorStats ComputeStats(const std::vector<double>& errors);

struct AbsoluteTrajectoryError {
  std::vector<double> translation_m;  // [m] per associated pose
  std::vector<double> rotation_deg;   // [deg] per associated pose
  ErrorStats translation;             // [m]
  ErrorStats rotation;                // [deg]
};

// ATE of an aligned estimate against its associated ground truth. Throws
// std::invalid_argument when the sizes differ.
AbsoluteTrajectoryError ComputeAte(const Trajectory& aligned_estimate,
                                   const Trajectory& ground_truth);

// What an RPE delta counts: travelled distance along the estimate [m], or
// poses of the associated trajectories [frames].
enum class RpeUnit { kMeters, kFrames };

using IndexPairs = std::vector<std::pair<size_t, size_t>>;

// The index pairs described above. delta must be > 0 (and a whole number for
// frames); std::invalid_argument otherwise. May be empty (trajectory shorter
// than two deltas).
IndexPairs RpePairs(const Trajectory& estimate, double delta, RpeUnit unit);

struct RelativePoseError {
  double delta = 0.0;  // [m] or [frames], as unit says
  RpeUnit unit = RpeUnit::kMeters;
  IndexPairs pairs;
  std::vector<double> translation_m;  // [m] per pair
  std::vector<double> rotation_deg;   // [deg] per pair
  ErrorStats translation;             // [m]; count 0 when there is no pair
  ErrorStats rotation;                // [deg]
};

// RPE for one delta. Throws std::invalid_argument when the sizes differ or the
// delta is invalid; no pair is not an error (count 0).
RelativePoseError ComputeRpe(const Trajectory& aligned_estimate,
                             const Trajectory& ground_truth, double delta,
                             RpeUnit unit);

}  // namespace vio

#endif  // VIO_EVAL_METRICS_H_
