#include "dataset/imu_curve_terms.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/so3.h"

namespace vio {
namespace {

// Collects the 3x3 Jacobian blocks of one 3-row residual; a block met twice
// (the two ends of a gyroscope interval share control rotations) adds up.
class TermBuilder {
 public:
  explicit TermBuilder(const Eigen::Vector3d& r) { term_.r = r; }
  void Add(int block, const Eigen::Matrix3d& d_r_d_block) {
    for (size_t k = 0; k < term_.blocks.size(); ++k) {
      if (term_.blocks[k] == block) {
        columns_[k] += d_r_d_block;
        return;
      }
    }
    term_.blocks.push_back(block);
    columns_.push_back(d_r_d_block);
  }
  CurveTerm Finish() {
    term_.J.resize(3, 3 * static_cast<int>(columns_.size()));
    for (size_t k = 0; k < columns_.size(); ++k) {
      term_.J.middleCols<3>(3 * static_cast<int>(k)) = columns_[k];
    }
    return term_;
  }

 private:
  CurveTerm term_;
  std::vector<Eigen::Matrix3d> columns_;
};

// The linear bias spline enters with weights (1 - l), l on knots m, m + 1.
void AddBias(const ImuCurveState& state, double t, bool gyro, double scale,
             TermBuilder* b) {
  int m = 0;
  double l = 0.0;
  state.BiasKnot(t, &m, &l);
  const auto block = [&](int k) {
    return gyro ? state.GyroBiasBlock(k) : state.AccelBiasBlock(k);
  };
  b->Add(block(m), scale * (1.0 - l) * Eigen::Matrix3d::Identity());
  if (m + 1 < state.bias_knots()) {
    b->Add(block(m + 1), scale * l * Eigen::Matrix3d::Identity());
  }
}

}  // namespace

PoseSpline ImuCurveState::Spline() const {
  return PoseSpline(0.0, knot_spacing_s, positions, rotations);
}

void ImuCurveState::BiasKnot(double t, int* m, double* l) const {
  const double s = std::max(t / bias_knot_spacing_s, 0.0);
  *m = std::min(static_cast<int>(std::floor(s)), std::max(bias_knots() - 2, 0));
  *l = bias_knots() < 2 ? 0.0 : std::min(s - *m, 1.0);
}

Eigen::Vector3d ImuCurveState::GyroBias(double t) const {
  int m = 0;
  double l = 0.0;
  BiasKnot(t, &m, &l);
  return bias_knots() < 2 ? b_g[m] : (1.0 - l) * b_g[m] + l * b_g[m + 1];
}

Eigen::Vector3d ImuCurveState::AccelBias(double t) const {
  int m = 0;
  double l = 0.0;
  BiasKnot(t, &m, &l);
  return bias_knots() < 2 ? b_a[m] : (1.0 - l) * b_a[m] + l * b_a[m + 1];
}

void ImuCurveState::Plus(int block, const Eigen::Vector3d& d) {
  const int n = control_points();
  if (block < 2 * n) {
    const int i = block / 2;
    if (block % 2 == 0) {
      positions[i] += d;
    } else {
      rotations[i] = (rotations[i] * ExpQuaternion(d)).normalized();
    }
    return;
  }
  const int m = (block - 2 * n) / 2;
  ((block - 2 * n) % 2 == 0 ? b_g[m] : b_a[m]) += d;
}

CurveTerm GyroIntervalTerm(const ImuCurveState& state, const PoseSpline& spline,
                           double t_a, double t_b,
                           const Eigen::Vector3d& w_mean_rad_s) {
  std::array<Eigen::Matrix3d, PoseSpline::kOrder> d_Ra, d_Rb;
  int first_a = 0, first_b = 0;
  const Eigen::Quaterniond q_a = spline.Rotation(t_a, &d_Ra, &first_a);
  const Eigen::Quaterniond q_b = spline.Rotation(t_b, &d_Rb, &first_b);
  const double dt = t_b - t_a;
  const Eigen::Vector3d phi = Log(q_a.conjugate() * q_b);
  const Eigen::Vector3d b_g = state.GyroBias(0.5 * (t_a + t_b));
  TermBuilder b(phi - (w_mean_rad_s - b_g) * dt);
  // R_a Exp(da), R_b Exp(db): R_a^T R_b -> Exp(-da) M Exp(db)
  //   = M Exp(db - M^T da), M = Exp(phi), so
  // d phi = Jr^-1(phi) (db - M^T da), with da = sum_k d_Ra[k] e_{first_a+k}.
  const Eigen::Matrix3d jr_inv = RightJacobianInverse(phi);
  const Eigen::Matrix3d through_a = -jr_inv * Exp(phi).transpose();
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    b.Add(state.RotationBlock(first_a + k), through_a * d_Ra[k]);
    b.Add(state.RotationBlock(first_b + k), jr_inv * d_Rb[k]);
  }
  // -(w - b_g) dt: d/d b_g = +dt (times the knot weights).
  AddBias(state, 0.5 * (t_a + t_b), /*gyro=*/true, dt, &b);
  return b.Finish();
}

CurveTerm AccelerometerTerm(const ImuCurveState& state,
                            const PoseSpline& spline, double t,
                            const Eigen::Vector3d& acc_m_s2,
                            double gravity_m_s2) {
  double u = 0.0;
  const int i = spline.Segment(t, &u);
  const double dt = spline.dt_s();
  const Eigen::Vector4d ddb = PoseSpline::Basis(u, 2) / (dt * dt);
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    a += ddb[k] * spline.positions()[i + k];
  }
  std::array<Eigen::Matrix3d, PoseSpline::kOrder> d_R;
  int first = 0;
  const Eigen::Matrix3d R = spline.Rotation(t, &d_R, &first).toRotationMatrix();
  const Eigen::Vector3d y =
      R.transpose() * (a - Eigen::Vector3d(0, 0, -gravity_m_s2));
  TermBuilder b(y + state.AccelBias(t) - acc_m_s2);
  // a = sum_k ddb_k c_{i+k}: d y / d c_{i+k} = R^T ddb_k.
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    b.Add(state.PositionBlock(i + k), ddb[k] * R.transpose());
  }
  // (R Exp(d))^T x = Exp(-d) R^T x ~= y - d x y = y + [y]x d,
  // d = sum_k d_R[k] e_{first+k}.
  const Eigen::Matrix3d y_cross = Skew(y);
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    b.Add(state.RotationBlock(first + k), y_cross * d_R[k]);
  }
  AddBias(state, t, /*gyro=*/false, 1.0, &b);
  return b.Finish();
}

CurveTerm PositionTerm(const ImuCurveState& state, const PoseSpline& spline,
                       double t, const Eigen::Vector3d& p_w_b) {
  double u = 0.0;
  const int i = spline.Segment(t, &u);
  const Eigen::Vector4d basis = PoseSpline::Basis(u, 0);
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    p += basis[k] * spline.positions()[i + k];
  }
  TermBuilder b(p - p_w_b);
  // p = sum_k b_k c_{i+k}: linear.
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    b.Add(state.PositionBlock(i + k), basis[k] * Eigen::Matrix3d::Identity());
  }
  return b.Finish();
}

CurveTerm RotationTerm(const ImuCurveState& state, const PoseSpline& spline,
                       double t, const Eigen::Quaterniond& q_w_b) {
  std::array<Eigen::Matrix3d, PoseSpline::kOrder> d_R;
  int first = 0;
  const Eigen::Quaterniond q = spline.Rotation(t, &d_R, &first);
  const Eigen::Vector3d r = Log(q_w_b.conjugate() * q);
  TermBuilder b(r);
  // Log(R^T R(t) Exp(d)) ~= r + Jr^-1(r) d.
  const Eigen::Matrix3d jr_inv = RightJacobianInverse(r);
  for (int k = 0; k < PoseSpline::kOrder; ++k) {
    b.Add(state.RotationBlock(first + k), jr_inv * d_R[k]);
  }
  return b.Finish();
}

CurveTerm PositionSmoothnessTerm(const ImuCurveState& state, int i) {
  TermBuilder b(state.positions[i - 1] - 2.0 * state.positions[i] +
                state.positions[i + 1]);
  b.Add(state.PositionBlock(i - 1), Eigen::Matrix3d::Identity());
  b.Add(state.PositionBlock(i), -2.0 * Eigen::Matrix3d::Identity());
  b.Add(state.PositionBlock(i + 1), Eigen::Matrix3d::Identity());
  return b.Finish();
}

CurveTerm RotationSmoothnessTerm(const ImuCurveState& state, int i) {
  // d_j = Log(R_j^T R_{j+1}) moves by Jr^-1(d_j) e_{j+1} and, since
  // Exp(-e) M = M Exp(-M^T e), by -Jr^-1(d_j) Exp(d_j)^T e_j.
  const std::vector<Eigen::Quaterniond>& R = state.rotations;
  const Eigen::Vector3d d0 = Log(R[i - 1].conjugate() * R[i]);
  const Eigen::Vector3d d1 = Log(R[i].conjugate() * R[i + 1]);
  const Eigen::Matrix3d j0 = RightJacobianInverse(d0);
  const Eigen::Matrix3d j1 = RightJacobianInverse(d1);
  TermBuilder b(d1 - d0);
  b.Add(state.RotationBlock(i - 1), j0 * Exp(d0).transpose());
  b.Add(state.RotationBlock(i), -j1 * Exp(d1).transpose() - j0);
  b.Add(state.RotationBlock(i + 1), j1);
  return b.Finish();
}

CurveTerm BiasWalkTerm(const ImuCurveState& state, int m, bool gyro) {
  const std::vector<Eigen::Vector3d>& knots = gyro ? state.b_g : state.b_a;
  TermBuilder b(knots[m + 1] - knots[m]);
  const auto block = [&](int k) {
    return gyro ? state.GyroBiasBlock(k) : state.AccelBiasBlock(k);
  };
  b.Add(block(m), -Eigen::Matrix3d::Identity());
  b.Add(block(m + 1), Eigen::Matrix3d::Identity());
  return b.Finish();
}

}  // namespace vio
