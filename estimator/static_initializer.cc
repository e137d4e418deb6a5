#include "estimator/static_initializer.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace vio {

namespace {

// Per-axis population standard deviation of a set of vectors.
Eigen::Vector3d StdOf(const std::vector<Eigen::Vector3d>& values) {
  if (values.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : values) mean += v;
  mean /= static_cast<double>(values.size());
  Eigen::Vector3d var = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : values) var += (v - mean).cwiseAbs2();
  return (var / static_cast<double>(values.size())).cwiseSqrt();
}

}  // namespace

ImuStatistics ComputeImuStatistics(const std::vector<ImuSample>& samples,
                                   double block_s) {
  ImuStatistics s;
  s.count = static_cast<int>(samples.size());
  if (samples.empty()) return s;
  const int64_t t0 = samples.front().t_ns;
  s.duration_s = 1e-9 * static_cast<double>(samples.back().t_ns - t0);
  std::vector<Eigen::Vector3d> acc, gyr, acc_blocks, gyr_blocks;
  Eigen::Vector3d acc_sum = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyr_sum = Eigen::Vector3d::Zero();
  int in_block = 0;
  int64_t block_index = 0;
  const int64_t block_ns = static_cast<int64_t>(block_s * 1e9);
  for (const ImuSample& m : samples) {
    acc.push_back(m.acc);
    gyr.push_back(m.gyr);
    s.acc_mean += m.acc;
    s.gyr_mean += m.gyr;
    // A sample past the current block closes it.
    const int64_t index = block_ns > 0 ? (m.t_ns - t0) / block_ns : 0;
    if (index != block_index && in_block > 0) {
      acc_blocks.push_back(acc_sum / in_block);
      gyr_blocks.push_back(gyr_sum / in_block);
      acc_sum.setZero();
      gyr_sum.setZero();
      in_block = 0;
    }
    block_index = index;
    acc_sum += m.acc;
    gyr_sum += m.gyr;
    ++in_block;
  }
  s.acc_mean /= s.count;
  s.gyr_mean /= s.count;
  s.acc_std = StdOf(acc);
  s.gyr_std = StdOf(gyr);
  s.acc_block_std = StdOf(acc_blocks);
  s.gyr_block_std = StdOf(gyr_blocks);
  s.blocks = static_cast<int>(acc_blocks.size());
  return s;
}

double Yaw(const Eigen::Matrix3d& R_w_b) {
  return std::atan2(R_w_b(1, 0), R_w_b(0, 0));
}

Eigen::Quaterniond GravityAlignedAttitude(const Eigen::Vector3d& f_b) {
  if (!f_b.allFinite() || f_b.norm() < 1e-9) {
    throw std::invalid_argument(
        "GravityAlignedAttitude: the specific force must be finite and not "
        "zero");
  }
  // The shortest rotation taking f_b onto +z, then the yaw about z removed:
  // Rz(-yaw) keeps +z fixed, so R_w_b * f_b still points up.
  const Eigen::Matrix3d R =
      Eigen::Quaterniond::FromTwoVectors(f_b, Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  const Eigen::Matrix3d R_w_b =
      Eigen::AngleAxisd(-Yaw(R), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
      R;
  return Eigen::Quaterniond(R_w_b).normalized();
}

void StaticInitializer::AddSample(const ImuSample& sample) {
  samples_.push_back(sample);
  const int64_t window_ns = static_cast<int64_t>(options_.window_s * 1e9);
  while (samples_.size() > 1 &&
         sample.t_ns - samples_.front().t_ns > window_ns) {
    samples_.pop_front();
  }
}

ImuStatistics StaticInitializer::Statistics() const {
  return ComputeImuStatistics({samples_.begin(), samples_.end()},
                              options_.block_s);
}

bool StaticInitializer::TryInitialize(StaticInitState* state) const {
  const ImuStatistics s = Statistics();
  // Allow one sample period of slack on the span.
  if (s.count < 2 || s.blocks < 2 || s.duration_s < 0.95 * options_.window_s ||
      s.acc_block_std.maxCoeff() > options_.max_acc_std ||
      s.gyr_block_std.maxCoeff() > options_.max_gyr_std ||
      s.acc_mean.norm() < 0.5 * gravity_magnitude_) {
    return false;
  }
  state->q_w_b = GravityAlignedAttitude(s.acc_mean);
  state->b_g = s.gyr_mean;
  const Eigen::Vector3d up_b = s.acc_mean.normalized();
  state->b_a =
      options_.estimate_accel_bias
          ? Eigen::Vector3d((s.acc_mean.norm() - gravity_magnitude_) * up_b)
          : Eigen::Vector3d::Zero();
  return true;
}

}  // namespace vio
