#ifndef VIO_FACTORS_CHECK_FACTOR_CASES_H_
#define VIO_FACTORS_CHECK_FACTOR_CASES_H_

// Every factor of the project, with a sampler of random realistic states.
// A factor is not done until it has a case here (used by tools/jacobian_check)
// and a numeric-differentiation test that draws from the same case.

#include <vector>

#include "factors/check/jacobian_check.h"

namespace vio {

// All cases, in a fixed order (the order of the jacobian_check table).
std::vector<FactorCase> AllFactorCases();

// The IMU factor (factors/imu_factor.h); check/imu_factor_case.cc.
FactorCase MakeImuFactorCase();

// The marginalisation prior (factors/marginalization_prior.h).
FactorCase MarginalizationPriorCase();

}  // namespace vio

#endif  // VIO_FACTORS_CHECK_FACTOR_CASES_H_
