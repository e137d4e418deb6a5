#include "preintegration/midpoint_step.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "geometry/so3.h"
#include "test/testing/jacobian_test_utils.h"

namespace vio {
namespace {

using testing::ExpectJacobianNear;

const char* const kStateNames[] = {"p", "theta", "v", "b_a", "b_g"};
const char* const kNoiseNames[] = {"n_a0", "n_g0", "n_a1",
                                   "n_g1", "n_ba", "n_bg"};

struct StepCase {
  ImuDelta curr;
  ImuSample s0, s1;
  Eigen::Vector3d b_a, b_g;
};

// The error of `next` with respect to the nominal step result, in the error
// state's tangent space; the bias error rides along unchanged.
Vector15d ErrorOf(const ImuDelta& next, const ImuDelta& nominal,
                  const Eigen::Vector3d& db_a, const Eigen::Vector3d& db_g) {
  Vector15d e;
  e.segment<3>(kImuP) = next.p - nominal.p;
  e.segment<3>(kImuR) = Log(nominal.q.conjugate() * next.q);
  e.segment<3>(kImuV) = next.v - nominal.v;
  e.segment<3>(kImuBa) = db_a;
  e.segment<3>(kImuBg) = db_g;
  return e;
}

// The step as a function of the current error state x (15).
Vector15d StepOfState(const StepCase& c, const Vector15d& x) {
  const ImuDelta nominal = MidpointStep(c.curr, c.s0, c.s1, c.b_a, c.b_g);
  ImuDelta curr = c.curr;
  curr.p += x.segment<3>(kImuP);
  curr.q = curr.q * ExpQuaternion(x.segment<3>(kImuR));
  curr.v += x.segment<3>(kImuV);
  const Eigen::Vector3d b_a = c.b_a + x.segment<3>(kImuBa);
  const Eigen::Vector3d b_g = c.b_g + x.segment<3>(kImuBg);
  return ErrorOf(MidpointStep(curr, c.s0, c.s1, b_a, b_g), nominal,
                 x.segment<3>(kImuBa), x.segment<3>(kImuBg));
}

// The step as a function of the noise n (18) added to the measurements and
// to the biases' random walk.
Vector15d StepOfNoise(const StepCase& c,
                      const Eigen::Matrix<double, 18, 1>& n) {
  const ImuDelta nominal = MidpointStep(c.curr, c.s0, c.s1, c.b_a, c.b_g);
  ImuSample s0 = c.s0, s1 = c.s1;
  s0.acc += n.segment<3>(kNoiseAcc0);
  s0.gyr += n.segment<3>(kNoiseGyr0);
  s1.acc += n.segment<3>(kNoiseAcc1);
  s1.gyr += n.segment<3>(kNoiseGyr1);
  return ErrorOf(MidpointStep(c.curr, s0, s1, c.b_a, c.b_g), nominal,
                 n.segment<3>(kNoiseBa), n.segment<3>(kNoiseBg));
}

// Compares F and G of one step with central differences, 3 x 3 block by
// 3 x 3 block, so a failure names the block (e.g. "F[p, b_g]", the note's f15).
void ExpectStepJacobiansNear(const StepCase& c, const std::string& label,
                             double tolerance = 1e-6) {
  Matrix15d F;
  Matrix15x18d G;
  MidpointStep(c.curr, c.s0, c.s1, c.b_a, c.b_g, &F, &G);
  for (int r = 0; r < 5; ++r) {
    for (int col = 0; col < 5; ++col) {
      const auto f = [&](const Eigen::VectorXd& x3) -> Eigen::VectorXd {
        Vector15d x = Vector15d::Zero();
        x.segment<3>(3 * col) = x3;
        return StepOfState(c, x).segment<3>(3 * r);
      };
      ExpectJacobianNear(
          label + " F[" + kStateNames[r] + ", " + kStateNames[col] + "]",
          F.block<3, 3>(3 * r, 3 * col), f, Eigen::Vector3d::Zero(), tolerance,
          1e-4);
    }
    for (int col = 0; col < 6; ++col) {
      const auto f = [&](const Eigen::VectorXd& n3) -> Eigen::VectorXd {
        Eigen::Matrix<double, 18, 1> n = Eigen::Matrix<double, 18, 1>::Zero();
        n.segment<3>(3 * col) = n3;
        return StepOfNoise(c, n).segment<3>(3 * r);
      };
      ExpectJacobianNear(
          label + " G[" + kStateNames[r] + ", " + kNoiseNames[col] + "]",
          G.block<3, 3>(3 * r, 3 * col), f, Eigen::Vector3d::Zero(), tolerance,
          1e-4);
    }
  }
}

Eigen::Vector3d Gaussian3(std::mt19937& rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  return Eigen::Vector3d(n(rng), n(rng), n(rng));
}

// delta_p stays zero: it enters the step only additively, and a large value
// would drown the tiny position blocks (about dt^3) in rounding error.
StepCase RandomCase(std::mt19937& rng, double rate_sigma, int64_t dt_ns) {
  StepCase c;
  c.curr.q = ExpQuaternion(Gaussian3(rng, 1.0));
  c.curr.v = Gaussian3(rng, 1.0);
  c.b_a = Gaussian3(rng, 0.1);
  c.b_g = Gaussian3(rng, 0.01);
  c.s0.t_ns = 1000;
  c.s1.t_ns = 1000 + dt_ns;
  c.s0.acc = Eigen::Vector3d(0.0, 0.0, 9.81) + Gaussian3(rng, 2.0);
  c.s1.acc = c.s0.acc + Gaussian3(rng, 0.2);
  c.s0.gyr = Gaussian3(rng, rate_sigma);
  c.s1.gyr = c.s0.gyr + Gaussian3(rng, 0.1 * rate_sigma);
  return c;
}

TEST(MidpointStep, JacobiansMatchNumericDiffAtRandomSteps) {
  std::mt19937 rng(42);
  for (int i = 0; i < 10; ++i) {
    ExpectStepJacobiansNear(RandomCase(rng, 1.0, 5000000),
                            "random " + std::to_string(i));
  }
}

TEST(MidpointStep, JacobiansMatchNumericDiffWithoutRotation) {
  // w - b_g is exactly zero: Exp and Jr take their small-angle branches.
  std::mt19937 rng(1);
  StepCase c = RandomCase(rng, 1.0, 5000000);
  c.s0.gyr = c.s1.gyr = c.b_g;
  ExpectStepJacobiansNear(c, "zero rate");
}

TEST(MidpointStep, JacobiansMatchNumericDiffAtTinyRotation) {
  // 1e-8 rad per step.
  std::mt19937 rng(2);
  StepCase c = RandomCase(rng, 1.0, 5000000);
  c.s0.gyr = c.s1.gyr = c.b_g + Eigen::Vector3d(2e-6, 0.0, 0.0);
  ExpectStepJacobiansNear(c, "1e-8 rad");
}

TEST(MidpointStep, JacobiansMatchNumericDiffAtFastRotationAndLongStep) {
  // About 0.5 rad per step: far from the small-angle regime where Jr ~ I.
  std::mt19937 rng(3);
  ExpectStepJacobiansNear(RandomCase(rng, 10.0, 30000000), "fast");
}

TEST(MidpointStep, JacobiansMatchNumericDiffAtTinyStep) {
  // 1 us, as at an interval end interpolated just after a sample. The
  // position and velocity blocks scale as dt^2 and dt^3 (1e-12, 1e-18), so
  // delta_v is zero too, for the same reason as delta_p. The rotation
  // differences are 1e-10 rad against a rounding of 1e-16, hence 1e-5.
  std::mt19937 rng(4);
  StepCase c = RandomCase(rng, 1.0, 1000);
  c.curr.v.setZero();
  ExpectStepJacobiansNear(c, "1 us", 1e-5);
}

TEST(MidpointStep, RotatesByTheMeanRateAndIntegratesTheMeanAcceleration) {
  // Closed form for a constant rate about z and acceleration along it.
  ImuSample s0, s1;
  s0.t_ns = 0;
  s1.t_ns = 100000000;  // 0.1 s
  s0.gyr = Eigen::Vector3d(0.0, 0.0, 1.0);
  s1.gyr = Eigen::Vector3d(0.0, 0.0, 3.0);
  s0.acc = s1.acc = Eigen::Vector3d(0.0, 0.0, 2.0);
  const ImuDelta next = MidpointStep(
      ImuDelta(), s0, s1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(Log(next.q).z(), 0.2, 1e-15);
  EXPECT_TRUE(next.v.isApprox(Eigen::Vector3d(0.0, 0.0, 0.2), 1e-15));
  EXPECT_TRUE(next.p.isApprox(Eigen::Vector3d(0.0, 0.0, 0.01), 1e-15));
}

TEST(MidpointStep, RejectsSamplesOutOfOrder) {
  ImuSample s0, s1;
  s0.t_ns = s1.t_ns = 5;
  try {
    MidpointStep(ImuDelta(), s0, s1, Eigen::Vector3d::Zero(),
                 Eigen::Vector3d::Zero());
    ADD_FAILURE() << "no ImuError";
  } catch (const ImuError& e) {
    EXPECT_STREQ(e.what(),
                 "midpoint step from t = 5 ns to t = 5 ns: the second sample "
                 "must come later");
  }
}

TEST(StepNoiseVariances, GiveTheMidpointAverageTheContinuousTimeVariance) {
  ImuNoise noise;
  const double dt = 0.005;
  const Eigen::Matrix<double, 18, 1> q = StepNoiseVariances(noise, dt);
  // The step uses (n_g0 + n_g1) / 2: variance (q0 + q1) / 4 = sigma^2 / dt.
  const double sigma_g = noise.gyroscope_noise_density;
  EXPECT_NEAR(0.25 * (q[kNoiseGyr0] + q[kNoiseGyr1]), sigma_g * sigma_g / dt,
              1e-20);
  const double sigma_bg = noise.gyroscope_random_walk;
  EXPECT_NEAR(q[kNoiseBg + 2], sigma_bg * sigma_bg * dt, 1e-25);
}

}  // namespace
}  // namespace vio
