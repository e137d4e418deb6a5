#include "factors/check/factor_cases.h"

namespace vio {

std::vector<FactorCase> AllFactorCases() {
  std::vector<FactorCase> cases;
  cases.push_back(MakeImuFactorCase());
  cases.push_back(MakeReprojectionCase());
  cases.push_back(MakeTimedReprojectionCase());
  cases.push_back(MakeStereoReprojectionCase());
  cases.push_back(MakeStereoTwoFrameReprojectionCase());
  cases.push_back(MakeTimedStereoTwoFrameReprojectionCase());
  cases.push_back(MakeWorldPointReprojectionCase());
  cases.push_back(MakeTimedWorldPointReprojectionCase());
  cases.push_back(MakeMarginalizationPriorCase());
  cases.push_back(MakePhotometricCase());
  cases.push_back(MakeZeroMotionFactorCase());
  return cases;
}

}  // namespace vio
