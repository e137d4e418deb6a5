// The "imu" case of the Jacobian check: an IMU factor over a random but
// plausible interval, at states near the motion it predicts, with the bias
// estimate moved away from the linearisation point so that the first-order
// correction (and its Jacobians) is exercised.

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/imu_factor.h"
#include "factors/pose_manifold.h"
#include "geometry/so3.h"
#include "preintegration/imu_preintegration.h"

namespace vio {
namespace {

Eigen::Vector3d Gaussian3(std::mt19937& rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  return Eigen::Vector3d(n(rng), n(rng), n(rng));
}

Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// 200 Hz samples (with jitter) of a body turning at a random rate of up to a
// few rad/s and accelerating by a few m/s^2 on top of gravity, both varying
// smoothly, covering [t0_ns, t1_ns] with one sample beyond each end.
std::vector<ImuSample> RandomSamples(std::mt19937& rng, int64_t t0_ns,
                                     int64_t t1_ns) {
  std::uniform_int_distribution<int64_t> jitter(-500000, 500000);
  const Eigen::Vector3d w0 = Gaussian3(rng, 1.0), w1 = Gaussian3(rng, 1.0);
  const Eigen::Vector3d a0 = Gaussian3(rng, 2.0), a1 = Gaussian3(rng, 2.0);
  const Eigen::Vector3d gravity_b =
      RandomRotation(rng).conjugate() * Eigen::Vector3d(0.0, 0.0, 9.81);
  std::vector<ImuSample> out;
  for (int64_t t = t0_ns - 3000000; out.empty() || out.back().t_ns < t1_ns;
       t += 5000000 + jitter(rng)) {
    const double s = 1e-9 * static_cast<double>(t - t0_ns);
    ImuSample sample;
    sample.t_ns = t;
    sample.gyr = w0 + std::sin(3.0 * s) * w1 + Gaussian3(rng, 0.01);
    sample.acc = gravity_b + a0 + std::cos(2.0 * s) * a1 + Gaussian3(rng, 0.05);
    out.push_back(sample);
  }
  return out;
}

FactorInstance SampleImuFactor(std::mt19937& rng) {
  const double kGravity = 9.81;
  std::uniform_real_distribution<double> duration(0.05, 0.5);
  const int64_t t0_ns = 1000000000;
  const int64_t t1_ns =
      t0_ns + static_cast<int64_t>(std::llround(1e9 * duration(rng)));
  const Eigen::Vector3d lin_b_a = Gaussian3(rng, 0.1);
  const Eigen::Vector3d lin_b_g = Gaussian3(rng, 0.01);
  const ImuPreintegration pre(t0_ns, t1_ns, RandomSamples(rng, t0_ns, t1_ns),
                              lin_b_a, lin_b_g, ImuNoise(),
                              PreintegrationOptions());

  // State i anywhere; biases off the linearisation point (within the
  // re-propagation thresholds, where the correction is meant to be used).
  const Eigen::Vector3d p_i = Gaussian3(rng, 5.0);
  const Eigen::Quaterniond q_i = RandomRotation(rng);
  const Eigen::Vector3d v_i = Gaussian3(rng, 1.0);
  const Eigen::Vector3d b_a_i = lin_b_a + Gaussian3(rng, 0.03);
  const Eigen::Vector3d b_g_i = lin_b_g + Gaussian3(rng, 0.003);
  // State j: what the corrected preintegration predicts, slightly disturbed.
  const double T = pre.sum_dt();
  const Eigen::Vector3d g_w(0.0, 0.0, -kGravity);
  const ImuDelta d = pre.Corrected(b_a_i, b_g_i);
  const Eigen::Vector3d p_j =
      p_i + v_i * T + 0.5 * g_w * T * T + q_i * d.p + Gaussian3(rng, 0.01);
  const Eigen::Quaterniond q_j =
      (q_i * d.q * ExpQuaternion(Gaussian3(rng, 0.01))).normalized();
  const Eigen::Vector3d v_j = v_i + g_w * T + q_i * d.v + Gaussian3(rng, 0.01);
  const Eigen::Vector3d b_a_j = b_a_i + Gaussian3(rng, 1e-3);
  const Eigen::Vector3d b_g_j = b_g_i + Gaussian3(rng, 1e-4);

  const auto pose = [](const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
    return std::vector<double>{p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
  };
  const auto speed_bias = [](const Eigen::Vector3d& v,
                             const Eigen::Vector3d& b_a,
                             const Eigen::Vector3d& b_g) {
    return std::vector<double>{v.x(),   v.y(),   v.z(),   b_a.x(), b_a.y(),
                               b_a.z(), b_g.x(), b_g.y(), b_g.z()};
  };
  FactorInstance f;
  f.cost = std::make_unique<ImuFactor>(pre.result(), kGravity);
  f.blocks = {pose(p_i, q_i), speed_bias(v_i, b_a_i, b_g_i), pose(p_j, q_j),
              speed_bias(v_j, b_a_j, b_g_j)};
  const auto manifold = std::make_shared<const PoseManifold>();
  f.manifolds = {manifold, nullptr, manifold, nullptr};
  f.block_names = {"pose_i", "speed_bias_i", "pose_j", "speed_bias_j"};
  return f;
}

}  // namespace

FactorCase MakeImuFactorCase() {
  FactorCase c;
  c.name = "imu";
  c.description =
      "IMU preintegration factor [pose_i, speed_bias_i, pose_j, speed_bias_j]";
  c.tolerance = 1e-5;
  c.sample = SampleImuFactor;
  return c;
}

}  // namespace vio
