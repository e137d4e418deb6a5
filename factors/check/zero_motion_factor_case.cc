// The "zero_motion" case of the Jacobian check: two poses of a vehicle that
// (nearly) stood still, as the solver meets them: the second pose close to
// the first (millimetres, milliradians) or, in one state out of four, far
// from it (up to a metre and a large rotation, the branch away from
// identity), the velocity small.

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/pose_manifold.h"
#include "factors/zero_motion_factor.h"
#include "geometry/so3.h"

namespace vio {
namespace {

Eigen::Vector3d Gaussian3(std::mt19937& rng, double sigma) {
  std::normal_distribution<double> n(0.0, sigma);
  return Eigen::Vector3d(n(rng), n(rng), n(rng));
}

std::vector<double> PoseBlock(const Eigen::Vector3d& p,
                              const Eigen::Quaterniond& q) {
  return {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
}

FactorInstance SampleZeroMotion(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const bool far = u(rng) < 0.25;
  const Eigen::Vector3d p_i = Gaussian3(rng, 3.0);
  const Eigen::Quaterniond q_i = ExpQuaternion(Gaussian3(rng, 1.0));
  // Log-uniform offsets from 1e-8 (the series branch of Jr^-1) upwards.
  const double scale = far ? 0.5 : std::exp(std::log(1e-8) + u(rng) * 14.0);
  const Eigen::Vector3d p_j = p_i + Gaussian3(rng, std::min(scale, 1.0));
  const Eigen::Quaterniond q_j =
      (q_i * ExpQuaternion(Gaussian3(rng, far ? 1.0 : std::min(scale, 0.1))))
          .normalized();
  std::vector<double> sb(9);
  const Eigen::Vector3d v = Gaussian3(rng, far ? 1.0 : 0.01);
  const Eigen::Vector3d b_a = Gaussian3(rng, 0.1), b_g = Gaussian3(rng, 0.01);
  for (int k = 0; k < 3; ++k) {
    sb[k] = v[k];
    sb[3 + k] = b_a[k];
    sb[6 + k] = b_g[k];
  }
  FactorInstance f;
  f.cost = std::make_unique<ZeroMotionFactor>(0.002, 0.002, 0.005);
  f.blocks = {PoseBlock(p_i, q_i), PoseBlock(p_j, q_j), sb};
  f.manifolds = {std::make_shared<PoseManifold>(),
                 std::make_shared<PoseManifold>(), nullptr};
  f.block_names = {"pose_i", "pose_j", "speed_bias_j"};
  return f;
}

}  // namespace

FactorCase MakeZeroMotionFactorCase() {
  FactorCase c;
  c.name = "zero_motion";
  c.description =
      "still vehicle: p_j - p_i, Log(q_i^-1 q_j), v_j, near and far from "
      "identity";
  c.tolerance = 1e-6;
  c.sample = SampleZeroMotion;
  return c;
}

}  // namespace vio
