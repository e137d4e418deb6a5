#include "estimator/visual_inertial_alignment.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cmath>

#include "geometry/so3.h"

namespace vio {
namespace {

// r_k = Log(dq_k^-1 R_k^T R_{k+1}) at the interval's linearisation bias.
Eigen::Vector3d RotationMisfit(const AlignmentFrame& i, const AlignmentFrame& j,
                               const ImuPreintegration& interval) {
  const Eigen::Quaterniond q_vis(i.R_v_b.transpose() * j.R_v_b);
  return Log(interval.delta().q.conjugate() * q_vis.normalized());
}

// Columns of the unknown vector x = (v_0, g, [s], [db_a]).
struct Layout {
  bool scale = false, accel_bias = false;
  int V() const { return 0; }
  int G() const { return 3; }
  int S() const { return 6; }
  int Ba() const { return scale ? 7 : 6; }
  int Size() const { return 6 + (scale ? 1 : 0) + (accel_bias ? 3 : 0); }
};

Layout LayoutOf(const AlignmentOptions& o) {
  Layout l;
  l.scale = o.estimate_scale;
  l.accel_bias = o.accel_bias_sigma > 0.0;
  return l;
}

// The preintegration from frame 0 to every frame k > 0 (index k - 1).
std::vector<ImuPreintegration> FromFirstFrame(
    const std::vector<ImuPreintegration>& intervals) {
  std::vector<ImuPreintegration> cumulative;
  for (const ImuPreintegration& i : intervals) {
    if (cumulative.empty()) {
      cumulative.push_back(i);
    } else {
      cumulative.push_back(ImuPreintegration::Merge(cumulative.back(), i));
    }
  }
  return cumulative;
}

// The stacked, weighted system A x = b of the header: three rows per frame
// k > 0 over options.position_sigma_m, then the prior rows of db_a over
// options.accel_bias_sigma. With the scale held, s = 1 moves to b.
void BuildSystem(const std::vector<AlignmentFrame>& frames,
                 const std::vector<ImuPreintegration>& from_first,
                 const Eigen::Vector3d& t_b_c, const Eigen::Vector3d& b_a,
                 const AlignmentOptions& options, Eigen::MatrixXd* A,
                 Eigen::VectorXd* b) {
  const Layout l = LayoutOf(options);
  const int n = static_cast<int>(frames.size());
  const int prior_rows = l.accel_bias ? 3 : 0;
  *A = Eigen::MatrixXd::Zero(3 * (n - 1) + prior_rows, l.Size());
  *b = Eigen::VectorXd::Zero(A->rows());
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const AlignmentFrame& f0 = frames[0];
  const double w = 1.0 / options.position_sigma_m;
  for (int k = 1; k < n; ++k) {
    const ImuPreintegration& imu = from_first[k - 1];
    const double T = imu.sum_dt();
    const ImuDelta d = imu.Corrected(b_a, imu.lin_b_g());
    const int r = 3 * (k - 1);
    A->block<3, 3>(r, l.V()) = -w * T * I;
    A->block<3, 3>(r, l.G()) = -w * 0.5 * T * T * I;
    b->segment<3>(r) =
        w * (f0.R_v_b * d.p + (frames[k].R_v_b - f0.R_v_b) * t_b_c);
    const Eigen::Vector3d dpbar = frames[k].p_v_c - f0.p_v_c;
    if (l.scale) {
      A->block<3, 1>(r, l.S()) = w * dpbar;
    } else {
      b->segment<3>(r) -= w * dpbar;
    }
    if (l.accel_bias) {
      A->block<3, 3>(r, l.Ba()) = -w * f0.R_v_b * imu.result().d_dp_d_ba;
    }
  }
  if (l.accel_bias) {
    A->block<3, 3>(3 * (n - 1), l.Ba()) = I / options.accel_bias_sigma;
  }
}

// Least squares with column scaling (the columns carry seconds, squared
// seconds and visual units); fills x, the RMS of the position rows (unweighted
// back to metres) and the standard deviation of column `col` from
// sigma^2 (A^T A)^-1, sigma^2 = |A x - b|^2 / (rows - unknowns) (col < 0: not
// wanted), and with `covariance` that whole matrix in x's units.
bool SolveScaled(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                 int position_rows, double position_sigma, int col,
                 Eigen::VectorXd* x, double* residual_rms, double* sigma_col,
                 Eigen::MatrixXd* covariance = nullptr) {
  const Eigen::VectorXd norms = A.colwise().norm();
  if ((norms.array() <= 0.0).any()) return false;
  const Eigen::MatrixXd As = A * norms.cwiseInverse().asDiagonal();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  if (qr.rank() < As.cols()) return false;
  *x = norms.cwiseInverse().asDiagonal() * qr.solve(b);
  const Eigen::VectorXd r = A * *x - b;
  *residual_rms =
      position_sigma * std::sqrt(r.head(position_rows).squaredNorm() /
                                 std::max(1, position_rows));
  if (col >= 0) {
    const Eigen::Index dof = A.rows() - A.cols();
    const double sigma2 = dof > 0 ? r.squaredNorm() / dof : 0.0;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(As.cols());
    e[col] = 1.0;
    const double cov = (As.transpose() * As).ldlt().solve(e)[col];
    *sigma_col = std::sqrt(std::max(0.0, sigma2 * cov)) / norms[col];
  }
  if (covariance != nullptr) {
    const Eigen::Index dof = A.rows() - A.cols();
    const double sigma2 = dof > 0 ? r.squaredNorm() / dof : 0.0;
    const Eigen::MatrixXd inverse =
        (As.transpose() * As)
            .ldlt()
            .solve(Eigen::MatrixXd::Identity(As.cols(), As.cols()));
    *covariance = sigma2 * norms.cwiseInverse().asDiagonal() * inverse *
                  norms.cwiseInverse().asDiagonal();
  }
  return x->allFinite();
}

// Velocities, scale and bias from the solution x (gravity g given).
void Unpack(const Eigen::VectorXd& x, const Eigen::Vector3d& g,
            const std::vector<AlignmentFrame>& frames,
            const std::vector<ImuPreintegration>& from_first,
            const Eigen::Vector3d& b_a, const Layout& l,
            VelocityGravityScale* result) {
  const Eigen::Vector3d v0 = x.segment<3>(l.V());
  const Eigen::Vector3d dba = l.accel_bias
                                  ? Eigen::Vector3d(x.segment<3>(l.Ba()))
                                  : Eigen::Vector3d::Zero();
  result->g_v = g;
  result->scale = l.scale ? x[l.S()] : 1.0;
  result->b_a = b_a + dba;
  result->v_v.assign(1, v0);
  for (const ImuPreintegration& imu : from_first) {
    const ImuDelta d = imu.Corrected(b_a, imu.lin_b_g());
    result->v_v.push_back(v0 + g * imu.sum_dt() +
                          frames[0].R_v_b *
                              (d.v + imu.result().d_dv_d_ba * dba));
  }
}

// Two unit vectors spanning the plane orthogonal to the unit vector g_hat.
Eigen::Matrix<double, 3, 2> TangentBasis(const Eigen::Vector3d& g_hat) {
  const Eigen::Vector3d helper = std::abs(g_hat.z()) < 0.9
                                     ? Eigen::Vector3d::UnitZ()
                                     : Eigen::Vector3d::UnitX();
  Eigen::Matrix<double, 3, 2> B;
  B.col(0) = g_hat.cross(helper).normalized();
  B.col(1) = g_hat.cross(B.col(0)).normalized();
  return B;
}

}  // namespace

double RotationMisfitRms(const std::vector<AlignmentFrame>& frames,
                         const std::vector<ImuPreintegration>& intervals) {
  double sum = 0.0;
  for (size_t k = 0; k + 1 < frames.size(); ++k) {
    sum += RotationMisfit(frames[k], frames[k + 1], intervals[k]).squaredNorm();
  }
  return frames.size() < 2 ? 0.0 : std::sqrt(sum / (frames.size() - 1));
}

Eigen::Vector3d AlignGyroscopeBias(const std::vector<AlignmentFrame>& frames,
                                   const Eigen::Vector3d& b_a,
                                   std::vector<ImuPreintegration>* intervals,
                                   int iterations) {
  Eigen::Vector3d b_g = intervals->empty() ? Eigen::Vector3d::Zero()
                                           : intervals->front().lin_b_g();
  for (int it = 0; it < iterations; ++it) {
    // Log(Exp(-J d) dq^-1 R_vis) ~ r - J d for a small misfit r (the left
    // Jacobian of Log at r is ~ I), so the normal equations are
    // (sum J^T J) d = sum J^T r.
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (size_t k = 0; k + 1 < frames.size(); ++k) {
      const ImuPreintegration& imu = (*intervals)[k];
      const Eigen::Matrix3d& J = imu.result().d_dq_d_bg;
      H += J.transpose() * J;
      g += J.transpose() * RotationMisfit(frames[k], frames[k + 1], imu);
    }
    const Eigen::Vector3d d = H.ldlt().solve(g);
    if (!d.allFinite()) break;
    b_g += d;
    for (ImuPreintegration& imu : *intervals) imu.Repropagate(b_a, b_g);
  }
  return b_g;
}

bool SolveVelocityGravityScale(const std::vector<AlignmentFrame>& frames,
                               const std::vector<ImuPreintegration>& intervals,
                               const Eigen::Vector3d& t_b_c,
                               const Eigen::Vector3d& b_a,
                               const AlignmentOptions& options,
                               VelocityGravityScale* result) {
  const int n = static_cast<int>(frames.size());
  if (n < 3 || static_cast<int>(intervals.size()) < n - 1) return false;
  const Layout l = LayoutOf(options);
  const std::vector<ImuPreintegration> from_first = FromFirstFrame(intervals);
  Eigen::MatrixXd A;
  Eigen::VectorXd b, x;
  BuildSystem(frames, from_first, t_b_c, b_a, options, &A, &b);
  double sigma = 0.0;
  Eigen::MatrixXd covariance;
  if (!SolveScaled(A, b, 3 * (n - 1), options.position_sigma_m,
                   l.scale ? l.S() : -1, &x, &result->residual_rms, &sigma,
                   &covariance)) {
    return false;
  }
  Unpack(x, x.segment<3>(l.G()), frames, from_first, b_a, l, result);
  result->scale_sigma = l.scale ? sigma : 0.0;
  // |g| = g_hat^T g to first order, so its variance is g_hat^T Cov_g g_hat.
  const Eigen::Vector3d g_hat = result->g_v.normalized();
  result->gravity_norm_sigma = std::sqrt(
      std::max(0.0, g_hat.dot(covariance.block<3, 3>(l.G(), l.G()) * g_hat)));
  return true;
}

bool RefineGravity(const std::vector<AlignmentFrame>& frames,
                   const std::vector<ImuPreintegration>& intervals,
                   const Eigen::Vector3d& t_b_c, const Eigen::Vector3d& b_a,
                   double gravity_magnitude, const AlignmentOptions& options,
                   VelocityGravityScale* result, int iterations) {
  const int n = static_cast<int>(frames.size());
  if (n < 3 || static_cast<int>(intervals.size()) < n - 1 ||
      !(result->g_v.norm() > 0.0)) {
    return false;
  }
  const Layout l = LayoutOf(options);
  const std::vector<ImuPreintegration> from_first = FromFirstFrame(intervals);
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  BuildSystem(frames, from_first, t_b_c, b_a, options, &A, &b);
  Eigen::Vector3d g_hat = result->g_v.normalized();
  for (int it = 0; it < iterations; ++it) {
    // A_g g = A_g (G g_hat) + (A_g B) w: the first term moves to b, the
    // gravity columns become the two of w (x without one column).
    const Eigen::Matrix<double, 3, 2> B = TangentBasis(g_hat);
    const Eigen::MatrixXd A_g = A.middleCols<3>(l.G());
    Eigen::MatrixXd Ar(A.rows(), A.cols() - 1);
    Ar.leftCols<3>() = A.leftCols<3>();
    Ar.middleCols<2>(3) = A_g * B;
    Ar.rightCols(A.cols() - 6) = A.rightCols(A.cols() - 6);
    const Eigen::VectorXd br = b - A_g * (gravity_magnitude * g_hat);
    Eigen::VectorXd xr;
    double sigma = 0.0;
    if (!SolveScaled(Ar, br, 3 * (n - 1), options.position_sigma_m,
                     l.scale ? l.S() - 1 : -1, &xr, &result->residual_rms,
                     &sigma)) {
      return false;
    }
    const Eigen::Vector3d g = gravity_magnitude * g_hat + B * xr.segment<2>(3);
    // Back to the full layout for Unpack: g in its three columns.
    Eigen::VectorXd x(A.cols());
    x.head<3>() = xr.head<3>();
    x.segment<3>(3) = g;
    x.tail(A.cols() - 6) = xr.tail(A.cols() - 6);
    g_hat = g.normalized();
    Unpack(x, gravity_magnitude * g_hat, frames, from_first, b_a, l, result);
    result->scale_sigma = l.scale ? sigma : 0.0;
  }
  return true;
}

Eigen::Matrix3d GravityAlignedRotation(const Eigen::Vector3d& g_v) {
  return Eigen::Quaterniond::FromTwoVectors(g_v, -Eigen::Vector3d::UnitZ())
      .toRotationMatrix();
}

}  // namespace vio
