#ifndef VIO_TOOLS_CURVE_FITTING_CURVE_CHECK_CASE_H_
#define VIO_TOOLS_CURVE_FITTING_CURVE_CHECK_CASE_H_

// The curve fitting exercise's cost function as a jacobian_check case, so the
// tool proves every analytic Jacobian of the project. It lives here, not in
// factors/check/, because factors/ must not depend on tools/.

#include "factors/check/jacobian_check.h"

namespace vio {

// "curve_sample": CurveSampleCost at random samples x in [0, 1) and
// parameters (a, b, c) within +-3 of the exercise's truth (1, 2, 1).
FactorCase MakeCurveSampleCase();

}  // namespace vio

#endif  // VIO_TOOLS_CURVE_FITTING_CURVE_CHECK_CASE_H_
