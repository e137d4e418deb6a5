// Tests of the robust kernels and their Triggs-corrected IRLS weights
// (tools/curve_fitting/robust_irls.h).

#include "tools/curve_fitting/robust_irls.h"

#include <ceres/loss_function.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace vio {
namespace {

constexpr double kC = 1.5;

// Half the kernel of r^2: the cost of one residual as a function of r.
double HalfRho(const RobustKernel& kernel, double r) {
  return 0.5 * EvaluateKernel(kernel, r * r).rho;
}

TEST(RobustKernel, MatchesCeresLossesAndTheirDerivatives) {
  const ceres::HuberLoss huber(kC);
  const ceres::CauchyLoss cauchy(kC);
  for (double s : {0.0, 0.3, 2.0, kC * kC, 4.0, 30.0, 900.0}) {
    for (const auto& [type, loss] :
         {std::pair<KernelType, const ceres::LossFunction*>{KernelType::kHuber,
                                                            &huber},
          {KernelType::kCauchy, &cauchy}}) {
      double expected[3];
      loss->Evaluate(s, expected);
      const KernelValue v = EvaluateKernel({type, kC}, s);
      SCOPED_TRACE(std::string(KernelTypeName(type)) +
                   " s=" + std::to_string(s));
      EXPECT_NEAR(v.rho, expected[0], 1e-12 * (1.0 + expected[0]));
      EXPECT_NEAR(v.d_rho, expected[1], 1e-12);
      if (s > 0.0 && s != kC * kC) {
        EXPECT_NEAR(v.d2_rho, expected[2], 1e-12);
      }
    }
  }
}

TEST(IrlsWeights, GradientWeightIsTheSlopeOfTheCost) {
  // d/dr (1/2 rho(r^2)) = rho' r.
  for (KernelType type :
       {KernelType::kNone, KernelType::kHuber, KernelType::kCauchy}) {
    const RobustKernel kernel{type, kC};
    for (double r : {-7.0, -1.0, 0.4, 1.2, 2.0, 9.0}) {
      const double h = 1e-6;
      const double slope =
          (HalfRho(kernel, r + h) - HalfRho(kernel, r - h)) / (2.0 * h);
      EXPECT_NEAR(ComputeIrlsWeights(kernel, r).gradient * r, slope, 1e-7)
          << KernelTypeName(type) << " r=" << r;
    }
  }
}

TEST(IrlsWeights, TriggsHessianWeightIsTheCurvatureWhereItIsPositive) {
  // d^2/dr^2 (1/2 rho(r^2)) = rho' + 2 rho'' r^2, the notes' Triggs weight.
  for (KernelType type : {KernelType::kHuber, KernelType::kCauchy}) {
    const RobustKernel kernel{type, kC};
    for (double r : {0.3, 0.9, 1.3, -1.1}) {  // all inside |r| < c
      const double h = 1e-4;
      const double curvature =
          (HalfRho(kernel, r + h) - 2.0 * HalfRho(kernel, r) +
           HalfRho(kernel, r - h)) /
          (h * h);
      EXPECT_NEAR(ComputeIrlsWeights(kernel, r).hessian, curvature, 1e-6)
          << KernelTypeName(type) << " r=" << r;
    }
  }
  // Cauchy inside: (1 - s/c^2) / (1 + s/c^2)^2, at s = c^2 / 4: 0.48.
  EXPECT_NEAR(ComputeIrlsWeights({KernelType::kCauchy, kC}, 0.5 * kC).hessian,
              0.75 / (1.25 * 1.25), 1e-15);
}

TEST(IrlsWeights, FallBackToTheFirstOrderWeightBeyondTheInflection) {
  // Huber's linear part has zero curvature, Cauchy's s > c^2 negative: both
  // use rho' as the Hessian weight, so the normal matrix stays positive.
  const double r = 4.0 * kC;
  const IrlsWeights huber = ComputeIrlsWeights({KernelType::kHuber, kC}, r);
  EXPECT_DOUBLE_EQ(huber.hessian, 0.25);  // c / |r|
  EXPECT_DOUBLE_EQ(huber.gradient, 0.25);
  const IrlsWeights cauchy = ComputeIrlsWeights({KernelType::kCauchy, kC}, r);
  EXPECT_DOUBLE_EQ(cauchy.gradient, 1.0 / 17.0);  // 1 / (1 + 16)
  EXPECT_DOUBLE_EQ(cauchy.hessian, 1.0 / 17.0);
  const IrlsWeights none = ComputeIrlsWeights({KernelType::kNone, kC}, r);
  EXPECT_DOUBLE_EQ(none.gradient, 1.0);
  EXPECT_DOUBLE_EQ(none.hessian, 1.0);
}

TEST(RobustKernel, ParsesNamesAndRejectsABadScale) {
  KernelType type = KernelType::kNone;
  EXPECT_TRUE(ParseKernelType("cauchy", &type));
  EXPECT_EQ(type, KernelType::kCauchy);
  EXPECT_FALSE(ParseKernelType("Tukey", &type));
  std::string message;
  EXPECT_FALSE((RobustKernel{KernelType::kCauchy, 0.0}).Validate(&message));
  EXPECT_NE(message.find("got 0"), std::string::npos);
  EXPECT_TRUE((RobustKernel{KernelType::kNone, 0.0}).Validate(&message));
}

}  // namespace
}  // namespace vio
