#include "factors/robust_kernel.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "factors/visual_factor_options.h"

namespace vio {
namespace {

using ::testing::HasSubstr;

// rho'(s), the weight a kernel gives a squared residual s.
double Weight(const ceres::LossFunction& loss, double s) {
  double rho[3];
  loss.Evaluate(s, rho);
  return rho[1];
}

TEST(RobustKernelOptions, NoneIsPlainSquaredLoss) {
  RobustKernelOptions options;
  options.type = RobustKernelType::kNone;
  EXPECT_EQ(MakeLossFunction(options), nullptr);
}

TEST(RobustKernelOptions, HuberScaleIsInUnitsOfSigma) {
  // Residuals are whitened, so the kernel must start to down-weight exactly
  // at |r| = scale sigma: weight 1 inside, scale / |r| outside.
  RobustKernelOptions options;  // Huber 1.345 by default
  ASSERT_EQ(options.type, RobustKernelType::kHuber);
  const auto loss = MakeLossFunction(options);
  ASSERT_NE(loss, nullptr);
  const double c = kDefaultHuberScale;
  EXPECT_DOUBLE_EQ(Weight(*loss, 0.99 * c * c), 1.0);
  EXPECT_NEAR(Weight(*loss, 9.0), c / 3.0, 1e-12);
}

TEST(RobustKernelOptions, CauchyHalvesTheWeightAtItsScale) {
  RobustKernelOptions options;
  options.type = RobustKernelType::kCauchy;
  options.scale = DefaultRobustKernelScale(options.type);
  EXPECT_DOUBLE_EQ(options.scale, 2.3849);
  const auto loss = MakeLossFunction(options);
  ASSERT_NE(loss, nullptr);
  // rho'(s) = 1 / (1 + s / c^2).
  EXPECT_NEAR(Weight(*loss, options.scale * options.scale), 0.5, 1e-12);
}

TEST(RobustKernelOptions, ValidateRejectsNonPositiveOrNonFiniteScale) {
  for (double scale : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
    RobustKernelOptions options;
    options.type = RobustKernelType::kCauchy;
    options.scale = scale;
    std::string message;
    EXPECT_FALSE(options.Validate(&message)) << scale;
    EXPECT_THAT(message, HasSubstr("scale must be a finite number > 0"));
    EXPECT_THROW(MakeLossFunction(options), std::invalid_argument);
  }
  RobustKernelOptions none;
  none.type = RobustKernelType::kNone;
  none.scale = -1.0;  // not used
  std::string message;
  EXPECT_TRUE(none.Validate(&message));
}

TEST(RobustKernelOptions, NamesRoundTripAndUnknownNamesAreRejected) {
  for (RobustKernelType t : {RobustKernelType::kNone, RobustKernelType::kHuber,
                             RobustKernelType::kCauchy}) {
    RobustKernelType parsed = RobustKernelType::kNone;
    ASSERT_TRUE(ParseRobustKernelType(RobustKernelName(t), &parsed));
    EXPECT_EQ(parsed, t);
  }
  RobustKernelType parsed = RobustKernelType::kHuber;
  EXPECT_FALSE(ParseRobustKernelType("Huber", &parsed));
  EXPECT_FALSE(ParseRobustKernelType("tukey", &parsed));
  EXPECT_EQ(parsed, RobustKernelType::kHuber);
}

TEST(VisualFactorOptions, ValidateNamesTheOffendingField) {
  VisualFactorOptions options;
  std::string message;
  EXPECT_TRUE(options.Validate(&message));
  EXPECT_DOUBLE_EQ(options.SqrtInformation(458.654), 458.654 / 1.5);
  options.sigma_px = 0.0;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_THAT(message, HasSubstr("sigma_px must be a finite number > 0"));
  options.sigma_px = 1.0;
  options.robust_kernel.scale = -2.0;
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_THAT(message, HasSubstr("robust_kernel.scale must be"));
}

}  // namespace
}  // namespace vio
