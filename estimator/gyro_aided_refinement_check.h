#ifndef VIO_ESTIMATOR_GYRO_AIDED_REFINEMENT_CHECK_H_
#define VIO_ESTIMATOR_GYRO_AIDED_REFINEMENT_CHECK_H_

// The checks on the joint adjustment of a gyroscope-aided start
// (gyro_aided_initializer.h), which holds the accelerometer bias at zero:
// its own scale covariance leaves b_a out and claims 0.7-2 %, against errors
// of up to 73 % measured on the hand-held and motion_mono presets, so it guards
// nothing. The joint adjustment frees b_a (state_prior's sigma) and its
// covariance (scale_uncertainty.h) is the honest figure; two refusals use it:
//   - the adjusted window's relative scale sigma above
//     mono.max_scale_uncertainty (the limit the SfM start's alignment
//     meets): scale not observable;
//   - the adjustment moving the start's scale by more than
//     mono.gyro_max_refine_change_sigmas of that sigma, in log terms
//     (|log(1 + change)| / sigma): the two solutions differ in b_a alone
//     (zero, or estimated), so a move of several sigmas says that the scale
//     rests on the accelerometer bias, which the window does not determine.
// docs/initialisation.md has the trials behind both.

#include "estimator/init_attempt.h"
#include "estimator/initialization_options.h"

namespace vio {

// change: the adjustment's relative change of the window's path length
// [-]; sigma: the adjusted window's relative scale sigma (< 0: unknown).
// kNone when both checks pass; otherwise the reason, with *value and *limit.
InitFailure CheckGyroAidedRefinement(double change, double sigma,
                                     const MonoInitOptions& mono,
                                     double* value, double* limit);

}  // namespace vio

#endif  // VIO_ESTIMATOR_GYRO_AIDED_REFINEMENT_CHECK_H_
