#ifndef VIO_EVAL_ASSOCIATION_H_
#define VIO_EVAL_ASSOCIATION_H_

// Pairs the poses of an estimated trajectory with ground-truth poses by
// timestamp, with the rule of evo's sync.associate_trajectories (its current
// single-pass form over matching_time_indices):
//
//   - The trajectory with fewer poses is walked in order ("short"); when both
//     have the same number, the estimate is walked. For the usual case (a
//     20 Hz estimate against 200 Hz ground truth) this is "each estimate to
//     the nearest ground-truth stamp".
//   - Each short pose takes the pose of the other ("long") trajectory whose
//     stamp is nearest to its own, and is kept only when |difference| <=
//     max_diff (inclusive); otherwise it is dropped.
//   - Ties (two long stamps exactly equally near) go to the earlier stamp, as
//     numpy's argmin returns the first minimum.
//   - A long pose may be taken by several short poses (no uniqueness), again
//     as evo does. The short poses are never repeated.
//   - Repeated stamps (a pose whose stamp equals the one before it, as TUM
//     ground truth holds): in the long trajectory, of the poses sharing the
//     nearest stamp the first in file order is taken (argmin's first minimum)
//     and the later ones are never paired; in the short trajectory every pose
//     is walked, so each of the repeats is paired, all with the same long
//     pose.
//
// Stamps are compared as integer nanoseconds, so unlike evo (double seconds)
// there is no rounding at the max_diff boundary.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "dataset/trajectory.h"

namespace vio {

struct AssociationOptions {
  double max_diff = 0.01;  // [s] largest accepted |t_est - t_gt|, evo's default

  // Throws std::invalid_argument unless max_diff is finite and >= 0.
  void Validate() const;
};

// Two equally long trajectories, element i of one paired with element i of
// the other, in the walked trajectory's order.
struct Association {
  Trajectory estimate;
  Trajectory ground_truth;
  size_t num_estimate_in = 0;      // poses in the input estimate
  size_t num_ground_truth_in = 0;  // poses in the input ground truth
  bool walked_estimate = true;     // true: the estimate was the short side

  size_t size() const { return estimate.size(); }
};

// Associates by the rule above. Both inputs must have stamps that never
// decrease (the trajectory readers guarantee it); throws std::invalid_argument
// when they do or when the options are invalid. An empty result is not an
// error here: callers decide how many pairs they need.
Association Associate(const Trajectory& estimate,
                      const Trajectory& ground_truth,
                      const AssociationOptions& options = {});

// The ground truth an association of `estimate` needs, gathered from states
// handed over one at a time (a ground-truth file read with
// ForEachEurocGroundTruth, never held whole): for each estimate
// pose the state Associate would pair it with, by the rule above (nearest
// stamp, on a tie the earlier), one per pose. Associate(estimate, Take())
// then pairs exactly as with the whole ground truth, provided the whole has
// at least as many poses as the estimate (otherwise Associate walks the
// ground truth: states() tells the caller to read it whole), and memory
// follows the estimate, not the ground truth's rate.
class NearestGroundTruth {
 public:
  // estimate: stamps never decreasing (std::invalid_argument otherwise);
  // only its stamps are used, and it must outlive this object.
  explicit NearestGroundTruth(const Trajectory& estimate);

  // The next state; stamps strictly increasing (std::invalid_argument
  // otherwise).
  void Add(const StampedState& state);

  // How many states were added.
  int64_t states() const { return states_; }

  // One state per estimate pose, in its order (none when no state was
  // added). The object is spent afterwards.
  std::vector<StampedState> Take();

 private:
  const Trajectory& estimate_;
  size_t next_ = 0;  // the first estimate pose without its state yet
  StampedState before_;
  int64_t states_ = 0;
  std::vector<StampedState> nearest_;
};

// Pairs pose i with pose i, for trajectories without stamps (KITTI pose
// files, as evo's kitti mode does). Throws std::invalid_argument when the two
// do not hold the same number of poses.
Association AssociateByIndex(const Trajectory& estimate,
                             const Trajectory& ground_truth);

}  // namespace vio

#endif  // VIO_EVAL_ASSOCIATION_H_
