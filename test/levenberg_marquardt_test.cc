// Tests of the hand-written LM (tools/curve_fitting/levenberg_marquardt.h):
// the damping updates and the trial sequence follow the user's notes
// step by step on problems small enough to compute by hand.

#include "tools/curve_fitting/levenberg_marquardt.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace vio {
namespace {

// The formulas of the notes, with numbers worked by hand.
TEST(LevenbergMarquardt, NielsenUpdateFollowsTheNotes) {
  const DampingState start{6.0, 2.0};
  // rho = 1/2: 1 - (2 rho - 1)^3 = 1, mu unchanged; nu reset to 2.
  DampingState s = UpdateDamping(LmDamping::kNielsen, {6.0, 8.0}, 0.5);
  EXPECT_DOUBLE_EQ(s.mu, 6.0);
  EXPECT_DOUBLE_EQ(s.nu, 2.0);
  // rho = 1/4: 1 - (-1/2)^3 = 9/8.
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kNielsen, start, 0.25).mu, 6.75);
  // rho = 1: 1 - 1 = 0, clamped to 1/3.
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kNielsen, start, 1.0).mu, 2.0);
  // rho = 0.9: 1 - 0.8^3 = 0.488.
  EXPECT_NEAR(UpdateDamping(LmDamping::kNielsen, start, 0.9).mu, 2.928, 1e-12);
  // Rejections: mu *= nu, nu *= 2: 6 -> 12 -> 48 -> 384.
  s = start;
  for (double expected_mu : {12.0, 48.0, 384.0}) {
    s = UpdateDamping(LmDamping::kNielsen, s, -0.1);
    EXPECT_DOUBLE_EQ(s.mu, expected_mu);
  }
  EXPECT_DOUBLE_EQ(s.nu, 16.0);
}

TEST(LevenbergMarquardt, MarquardtUpdateFollowsTheNotes) {
  const DampingState start{6.0, 2.0};
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kMarquardt, start, -3.0).mu, 12.0);
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kMarquardt, start, 0.2).mu, 12.0);
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kMarquardt, start, 0.25).mu, 6.0);
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kMarquardt, start, 0.75).mu, 6.0);
  EXPECT_DOUBLE_EQ(UpdateDamping(LmDamping::kMarquardt, start, 0.8).mu, 2.0);
}

// One residual r(p) = exp(p) - 2, so that every quantity is a scalar.
ResidualFunction OneParameterProblem() {
  return [](const Eigen::VectorXd& p, Eigen::VectorXd* r, Eigen::MatrixXd* j) {
    r->resize(1);
    j->resize(1, 1);
    (*r)[0] = std::exp(p[0]) - 2.0;
    (*j)(0, 0) = std::exp(p[0]);
    return true;
  };
}

TEST(LevenbergMarquardt, FirstStepMatchesAHandComputation) {
  // From p = 0: r = -1, J = 1, A = 1, g = -J r = 1; tau = 1 gives mu0 = 1.
  // dp = g / (A + mu) = 1/2; r(1/2) = e^0.5 - 2 = -0.351279;
  // rho = (1 - 0.123397) / (dp (mu dp + g)) = 0.876603 / 0.75 = 1.168804.
  // Nielsen: 1 - (2 rho - 1)^3 = -1.393 -> factor 1/3 -> mu = 1/3.
  // Marquardt: rho > 0.75 -> mu = 1/3.
  for (LmDamping damping : {LmDamping::kNielsen, LmDamping::kMarquardt}) {
    LmOptions options;
    options.damping = damping;
    options.tau = 1.0;
    options.max_iterations = 1;
    const LmSummary lm = SolveLevenbergMarquardt(
        OneParameterProblem(), Eigen::VectorXd::Zero(1), options);
    ASSERT_EQ(lm.log.size(), 1u);
    EXPECT_DOUBLE_EQ(lm.initial_mu, 1.0);
    EXPECT_DOUBLE_EQ(lm.p[0], 0.5);
    EXPECT_NEAR(lm.log[0].chi2, 0.123397, 1e-6);
    EXPECT_NEAR(lm.log[0].gain_ratio, 1.168804, 1e-6);
    EXPECT_TRUE(lm.log[0].accepted);
    EXPECT_NEAR(lm.log[0].mu_next, 1.0 / 3.0, 1e-15);
  }
}

// The notes' loop written out with scalars for r(p) = exp(p) - 2 (A = J^2,
// g = -J r), independent of the solver's Eigen code.
struct HandTrial {
  double mu, chi2, gain_ratio, mu_next;
  bool accepted;
};

std::vector<HandTrial> HandComputedTrials(LmDamping damping, double p,
                                          double tau, int count) {
  double r = std::exp(p) - 2.0, j = std::exp(p);
  double mu = tau * j * j, nu = 2.0;
  std::vector<HandTrial> trials;
  while (static_cast<int>(trials.size()) < count) {
    const double g = -j * r;
    const double dp = g / (j * j + mu);
    const double r_new = std::exp(p + dp) - 2.0;
    const double rho = (r * r - r_new * r_new) / (dp * (mu * dp + g));
    HandTrial t{mu, r_new * r_new, rho, 0.0, rho > 0.0};
    if (damping == LmDamping::kNielsen) {
      if (rho > 0.0) {
        mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));
        nu = 2.0;
      } else {
        mu *= nu;
        nu *= 2.0;
      }
    } else {
      mu = rho < 0.25 ? 2.0 * mu : (rho > 0.75 ? mu / 3.0 : mu);
    }
    t.mu_next = mu;
    if (t.accepted) {
      p += dp;
      r = r_new;
      j = std::exp(p);
    }
    trials.push_back(t);
  }
  return trials;
}

TEST(LevenbergMarquardt, TrialsFollowTheNotesStepByStepWithRejections) {
  // From p = -2 the Gauss-Newton step (about +13.8) overshoots wildly, so the
  // first trials are rejected until mu has grown, then steps are accepted.
  for (LmDamping damping : {LmDamping::kNielsen, LmDamping::kMarquardt}) {
    SCOPED_TRACE(LmDampingName(damping));
    LmOptions options;
    options.damping = damping;
    options.tau = 1e-3;
    options.max_iterations = 4;
    const LmSummary lm = SolveLevenbergMarquardt(
        OneParameterProblem(), Eigen::VectorXd::Constant(1, -2.0), options);
    ASSERT_GE(lm.log.size(), 6u);
    const std::vector<HandTrial> hand = HandComputedTrials(
        damping, -2.0, 1e-3, static_cast<int>(lm.log.size()));
    int rejected = 0;
    for (size_t i = 0; i < hand.size(); ++i) {
      SCOPED_TRACE("trial " + std::to_string(i));
      const LmTrial& t = lm.log[i];
      EXPECT_EQ(t.accepted, hand[i].accepted);
      EXPECT_NEAR(t.mu, hand[i].mu, 1e-9 * hand[i].mu);
      EXPECT_NEAR(t.mu_next, hand[i].mu_next, 1e-9 * hand[i].mu_next);
      EXPECT_NEAR(t.chi2, hand[i].chi2, 1e-9 * hand[i].chi2);
      EXPECT_NEAR(t.gain_ratio, hand[i].gain_ratio,
                  1e-9 * std::abs(hand[i].gain_ratio));
      rejected += t.accepted ? 0 : 1;
    }
    EXPECT_GE(rejected, 2);
    EXPECT_EQ(lm.iterations, 4);
  }
}

TEST(LevenbergMarquardt, StopsAtOnceWhenTheStartIsStationary) {
  // exp(p) - 2 = 0 at p = ln 2: g = 0 <= eps1 before any trial.
  const LmSummary lm = SolveLevenbergMarquardt(
      OneParameterProblem(), Eigen::VectorXd::Constant(1, std::log(2.0)),
      LmOptions{});
  EXPECT_EQ(lm.termination, LmTermination::kGradient);
  EXPECT_EQ(lm.iterations, 0);
  EXPECT_TRUE(lm.log.empty());
}

TEST(LevenbergMarquardt, RejectsInvalidOptionsAndAnUnevaluableStart) {
  LmOptions options;
  options.tau = 0.0;
  EXPECT_THROW(SolveLevenbergMarquardt(OneParameterProblem(),
                                       Eigen::VectorXd::Zero(1), options),
               std::invalid_argument);
  const ResidualFunction never = [](const Eigen::VectorXd&, Eigen::VectorXd*,
                                    Eigen::MatrixXd*) { return false; };
  try {
    SolveLevenbergMarquardt(never, Eigen::VectorXd::Zero(1), LmOptions{});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("at the start"), std::string::npos);
  }
  std::string message;
  options = LmOptions{};
  options.kernel = {KernelType::kHuber, -1.0};
  EXPECT_FALSE(options.Validate(&message));
  EXPECT_NE(message.find("kernel scale c"), std::string::npos);
}

}  // namespace
}  // namespace vio
