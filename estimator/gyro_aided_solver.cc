#include "estimator/gyro_aided_solver.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "estimator/gyro_bias_from_rotations.h"

namespace vio {
namespace {

using Mat9 = Eigen::Matrix<double, 9, 9>;
using Vec9 = Eigen::Matrix<double, 9, 1>;
constexpr int kV = 0, kG = 3, kBa = 6;  // columns of x = (v_0, g, b_a)
// Depths used for the row weights are clamped to this range [m].
constexpr double kMinWeightDepth = 0.1, kMaxWeightDepth = 1e3;
constexpr double kDepthRange = 4.0;
// Below this relative eigenvalue the reduced system is singular.
constexpr double kMinRelativeEigenvalue = 1e-12;

// Frame k's camera: attitude R_c = R_k R_b_c and position p_c = A x + e with
// A = [T I, T^2/2 I, J_k] and e = alpha_k + R_k t_b_c (the header's p_ck),
// alpha_k at b_a = 0 and J_k = d alpha_k / d b_a (the preintegration's
// first-order correction, linear in b_a: its columns are exact
// differences).
struct CameraTerms {
  Eigen::Matrix3d R_v_c;
  Eigen::Matrix<double, 3, 9> A;
  Eigen::Vector3d e;
};

std::vector<CameraTerms> CamerasAt(const GyroAidedProblem& problem,
                                   const Eigen::Vector3d& b_g) {
  GyroAidedSolution at;
  at.b_g = b_g;
  std::vector<CameraTerms> cameras(problem.NumFrames());
  for (int k = 0; k < problem.NumFrames(); ++k) {
    const GyroAidedFrameState s = FrameState(problem, at, k);
    CameraTerms& c = cameras[k];
    c.R_v_c = s.R_v_b * problem.T_b_c.linear();
    c.A.setZero();
    c.A.block<3, 3>(0, kV) = s.t_s * Eigen::Matrix3d::Identity();
    c.A.block<3, 3>(0, kG) = 0.5 * s.t_s * s.t_s * Eigen::Matrix3d::Identity();
    // With v_0 = g = b_a = 0 the state's position is alpha_k.
    c.e = s.p_v_b + s.R_v_b * problem.T_b_c.translation();
    for (int i = 0; k > 0 && i < 3; ++i) {
      GyroAidedSolution unit = at;
      unit.b_a = Eigen::Vector3d::Unit(i);
      c.A.block<3, 1>(0, kBa + i) =
          FrameState(problem, unit, k).p_v_b - s.p_v_b;
    }
  }
  return cameras;
}

// A track's weighted rows B x + c lambda - d, two per non-anchor sighting.
struct TrackRows {
  Eigen::Matrix<double, Eigen::Dynamic, 9> B;
  Eigen::VectorXd c, d;
};

// The camera-k depth of track t's point under solution s.
double DepthIn(const CameraTerms& anchor, const CameraTerms& k,
               const Eigen::Vector2d& xy_anchor, double lambda, const Vec9& x) {
  const Eigen::Vector3d P =
      anchor.A * x + anchor.e +
      lambda * anchor.R_v_c *
          Eigen::Vector3d(xy_anchor.x(), xy_anchor.y(), 1.0);
  return (k.R_v_c.transpose() * (P - k.A * x - k.e)).z();
}

// Rows of the header's constraint M_k R_ck^T (P - p_ck) = 0 with
// P = p_cf + lambda R_cf u_f: B = w M R_ck^T (A_f - A_k),
// c = w M R_ck^T R_cf u_f, d = w M R_ck^T (e_k - e_f); w = focal / depth.
std::vector<TrackRows> BuildRows(const GyroAidedProblem& problem,
                                 const std::vector<CameraTerms>& cameras,
                                 const GyroAidedSolution* previous) {
  Vec9 x_prev = Vec9::Zero();
  std::vector<CameraTerms> cameras_prev;
  if (previous != nullptr) {
    x_prev << previous->v_0, previous->g, previous->b_a;
    cameras_prev = CamerasAt(problem, previous->b_g);
  }
  // The weights' depths are held within a factor kDepthRange of the median
  // depth: a track without parallax has a depth that is noise (even its
  // sign), and taken as it is it would weigh hundreds of times the others.
  double low = kMinWeightDepth, high = kMaxWeightDepth;
  if (previous != nullptr) {
    std::vector<double> positive;
    for (double d : previous->depth) {
      if (d > 0.0 && std::isfinite(d)) positive.push_back(d);
    }
    if (!positive.empty()) {
      std::nth_element(positive.begin(), positive.begin() + positive.size() / 2,
                       positive.end());
      const double median = positive[positive.size() / 2];
      low = std::max(low, median / kDepthRange);
      high = std::min(high, median * kDepthRange);
    }
  }
  std::vector<TrackRows> rows(problem.tracks.size());
  for (size_t t = 0; t < problem.tracks.size(); ++t) {
    const std::vector<GyroAidedSighting>& s = problem.tracks[t].sightings;
    const int m = static_cast<int>(s.size()) - 1;
    TrackRows& r = rows[t];
    r.B.setZero(2 * m, 9);
    r.c.setZero(2 * m);
    r.d.setZero(2 * m);
    const CameraTerms& f = cameras[s[0].frame];
    const Eigen::Vector3d u_f = Eigen::Vector3d(s[0].xy.x(), s[0].xy.y(), 1.0);
    for (int i = 0; i < m; ++i) {
      const CameraTerms& k = cameras[s[i + 1].frame];
      double depth = 1.0;
      if (previous != nullptr) {
        depth = DepthIn(cameras_prev[s[0].frame], cameras_prev[s[i + 1].frame],
                        s[0].xy, previous->depth[t], x_prev);
      }
      if (!std::isfinite(depth)) depth = high;
      depth = std::clamp(std::abs(depth), low, high);
      const double w = problem.focal_px / depth;
      Eigen::Matrix<double, 2, 3> M;
      M << -1.0, 0.0, s[i + 1].xy.x(), 0.0, -1.0, s[i + 1].xy.y();
      const Eigen::Matrix<double, 2, 3> MR = w * M * k.R_v_c.transpose();
      r.B.block<2, 9>(2 * i, 0) = MR * (f.A - k.A);
      r.c.segment<2>(2 * i) = MR * f.R_v_c * u_f;
      r.d.segment<2>(2 * i) = MR * (k.e - f.e);
    }
  }
  return rows;
}

// The Schur complement of every track's depth: H x = b.
// The Schur complement of every track's depth, H x = b, with the prior
// b_a ~ N(0, sigma^2) in the rows' units (pixels; sigma 0 holds it at 0).
void Reduce(const std::vector<TrackRows>& rows, double accel_bias_sigma,
            Mat9* H, Vec9* b) {
  H->setZero();
  b->setZero();
  const double prior = accel_bias_sigma > 0.0
                           ? 1.0 / (accel_bias_sigma * accel_bias_sigma)
                           : 1e12;
  H->block<3, 3>(kBa, kBa) = prior * Eigen::Matrix3d::Identity();
  for (const TrackRows& r : rows) {
    const double ctc = r.c.squaredNorm() + 1e-12;
    const Vec9 Btc = r.B.transpose() * r.c;
    *H += r.B.transpose() * r.B - Btc * Btc.transpose() / ctc;
    *b += r.B.transpose() * r.d - Btc * (r.c.dot(r.d) / ctc);
  }
}

double DepthOf(const TrackRows& r, const Vec9& x) {
  return r.c.dot(r.d - r.B * x) / (r.c.squaredNorm() + 1e-12);
}

// Fills depths, residual figures and the stacked residual (when wanted) of
// x; returns the sum of squares.
double Evaluate(const GyroAidedProblem& problem,
                const std::vector<CameraTerms>& cameras,
                const std::vector<TrackRows>& rows, const Vec9& x,
                GyroAidedSolution* out, Eigen::VectorXd* residual) {
  out->v_0 = x.segment<3>(kV);
  out->g = x.segment<3>(kG);
  out->b_a = x.segment<3>(kBa);
  out->depth.assign(rows.size(), 0.0);
  out->track_rms_px.assign(rows.size(), 0.0);
  double sum = 0.0, sum_px = 0.0;
  int count = 0;
  std::vector<double> stacked;
  for (size_t t = 0; t < rows.size(); ++t) {
    const TrackRows& r = rows[t];
    const double lambda = DepthOf(r, x);
    out->depth[t] = lambda;
    const Eigen::VectorXd e = r.B * x + r.c * lambda - r.d;
    sum += e.squaredNorm();
    if (residual != nullptr)
      stacked.insert(stacked.end(), e.data(), e.data() + e.size());
    // The reprojection error proper, in pixels.
    const std::vector<GyroAidedSighting>& s = problem.tracks[t].sightings;
    const CameraTerms& f = cameras[s[0].frame];
    const Eigen::Vector3d P =
        f.A * x + f.e +
        lambda * f.R_v_c * Eigen::Vector3d(s[0].xy.x(), s[0].xy.y(), 1.0);
    double track = 0.0;
    for (size_t i = 1; i < s.size(); ++i) {
      const CameraTerms& k = cameras[s[i].frame];
      const Eigen::Vector3d q = k.R_v_c.transpose() * (P - k.A * x - k.e);
      const double px =
          q.z() > 0.0 ? problem.focal_px * (q.hnormalized() - s[i].xy).norm()
                      : std::numeric_limits<double>::infinity();
      track += px * px;
    }
    sum_px += track;
    count += static_cast<int>(s.size()) - 1;
    out->track_rms_px[t] = std::sqrt(track / (s.size() - 1));
  }
  out->rms_px = count > 0 ? std::sqrt(sum_px / count) : 0.0;
  if (residual != nullptr) {
    *residual = Eigen::Map<Eigen::VectorXd>(stacked.data(), stacked.size());
  }
  return sum;
}

int RowCount(const std::vector<TrackRows>& rows) {
  int n = 0;
  for (const TrackRows& r : rows) n += static_cast<int>(r.c.size());
  return n;
}

// Covariance sigma^2 P (P^T H P)^-1 P^T, sigma^2 from the residual per
// degree of freedom; P spans the unknowns (identity: all six).
Mat9 Covariance(const Mat9& H, const Eigen::MatrixXd& P, double sum, int rows,
                int unknowns) {
  const double dof = std::max(1, rows - unknowns);
  const Eigen::MatrixXd reduced = P.transpose() * H * P;
  return (sum / dof) * P * reduced.inverse() * P.transpose();
}

bool Singular(const Mat9& H) {
  const Eigen::SelfAdjointEigenSolver<Mat9> eig(H);
  const double max = eig.eigenvalues().maxCoeff();
  return !(max > 0.0) ||
         !(eig.eigenvalues().minCoeff() > kMinRelativeEigenvalue * max);
}

// Gravity with |g| = magnitude on the reduced system H x = b: g = G g_hat
// + B w (B spans the plane orthogonal to g_hat), solved for (v_0, w, b_a)
// and iterated from x's g (VINS-Mono's RefineGravity); then v_0 and b_a once
// more with g on the sphere. *P receives the last tangent basis of x.
bool SolveOnSphere(const Mat9& H, const Vec9& b, double magnitude, Vec9* x,
                   Eigen::Matrix<double, 9, 8>* P) {
  Eigen::Vector3d g = x->segment<3>(kG);
  if (!(g.norm() > 0.0)) return false;
  for (int it = 0; it < 4; ++it) {
    const Eigen::Vector3d g_hat = g.normalized();
    const Eigen::Vector3d any = std::abs(g_hat.x()) < 0.9
                                    ? Eigen::Vector3d::UnitX()
                                    : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d b1 = g_hat.cross(any).normalized();
    const Eigen::Vector3d b2 = g_hat.cross(b1);
    P->setZero();
    P->block<3, 3>(kV, 0).setIdentity();
    P->block<3, 1>(kG, 3) = b1;
    P->block<3, 1>(kG, 4) = b2;
    P->block<3, 3>(kBa, 5).setIdentity();
    Vec9 x0 = Vec9::Zero();
    x0.segment<3>(kG) = magnitude * g_hat;
    const Eigen::Matrix<double, 8, 8> reduced = P->transpose() * H * *P;
    const Eigen::Matrix<double, 8, 1> y =
        reduced.ldlt().solve(P->transpose() * (b - H * x0));
    if (!y.allFinite()) return false;
    g = magnitude * (x0 + *P * y).segment<3>(kG).normalized();
  }
  Eigen::Matrix<double, 9, 6> Q = Eigen::Matrix<double, 9, 6>::Zero();
  Q.block<3, 3>(kV, 0).setIdentity();
  Q.block<3, 3>(kBa, 3).setIdentity();
  Vec9 x0 = Vec9::Zero();
  x0.segment<3>(kG) = g;
  const Eigen::Matrix<double, 6, 6> HQ = Q.transpose() * H * Q;
  *x = x0 + Q * HQ.ldlt().solve(Q.transpose() * (b - H * x0));
  return x->allFinite();
}

// The reprojection rows at (x, depths): r = f (q_xy / q_z - xy_k) with
// q = R_ck^T (P - p_ck), P = A_f x + e_f + lambda R_cf u_f, p_ck = A_k x +
// e_k, linearised as B dx + c dlambda - d with d = -r:
//   dr/dq = f [[1/q_z, 0, -q_x/q_z^2], [0, 1/q_z, -q_y/q_z^2]],
//   dq/dx = R_ck^T (A_f - A_k),  dq/dlambda = R_ck^T R_cf u_f.
// A point behind (or at) a camera contributes no row; `residual` gets r.
std::vector<TrackRows> ReprojectionRows(const GyroAidedProblem& problem,
                                        const std::vector<CameraTerms>& cameras,
                                        const Vec9& x,
                                        const std::vector<double>& depths,
                                        GyroAidedSolution* out,
                                        std::vector<double>* residual) {
  constexpr double kMinZ = 1e-3;  // [m]
  constexpr double kBehindPenaltyPx = 100.0;
  std::vector<TrackRows> rows(problem.tracks.size());
  double sum_px = 0.0;
  int count = 0;
  out->track_rms_px.assign(rows.size(), 0.0);
  for (size_t t = 0; t < problem.tracks.size(); ++t) {
    const std::vector<GyroAidedSighting>& s = problem.tracks[t].sightings;
    const int m = static_cast<int>(s.size()) - 1;
    TrackRows& r = rows[t];
    r.B.setZero(2 * m, 9);
    r.c.setZero(2 * m);
    r.d.setZero(2 * m);
    const CameraTerms& f = cameras[s[0].frame];
    const Eigen::Vector3d ray_f =
        f.R_v_c * Eigen::Vector3d(s[0].xy.x(), s[0].xy.y(), 1.0);
    const Eigen::Vector3d P = f.A * x + f.e + depths[t] * ray_f;
    double track = 0.0;
    for (int i = 0; i < m; ++i) {
      const CameraTerms& k = cameras[s[i + 1].frame];
      const Eigen::Vector3d q = k.R_v_c.transpose() * (P - k.A * x - k.e);
      if (!(q.z() > kMinZ)) {
        // Rows of a fixed length for the bias fit: a constant penalty.
        track = std::numeric_limits<double>::infinity();
        if (residual != nullptr) {
          residual->push_back(kBehindPenaltyPx);
          residual->push_back(kBehindPenaltyPx);
        }
        continue;
      }
      const Eigen::Vector2d e =
          problem.focal_px * (q.hnormalized() - s[i + 1].xy);
      track += e.squaredNorm();
      if (residual != nullptr) {
        residual->push_back(e.x());
        residual->push_back(e.y());
      }
      Eigen::Matrix<double, 2, 3> J;
      J << 1.0 / q.z(), 0.0, -q.x() / (q.z() * q.z()), 0.0, 1.0 / q.z(),
          -q.y() / (q.z() * q.z());
      const Eigen::Matrix<double, 2, 3> JR =
          problem.focal_px * J * k.R_v_c.transpose();
      r.B.block<2, 9>(2 * i, 0) = JR * (f.A - k.A);
      r.c.segment<2>(2 * i) = JR * ray_f;
      r.d.segment<2>(2 * i) = -e;
    }
    sum_px += track;
    count += m;
    out->track_rms_px[t] = std::sqrt(track / m);
  }
  out->rms_px = count > 0 ? std::sqrt(sum_px / count) : 0.0;
  return rows;
}

// Gauss-Newton on the reprojection errors from the linear solution (which
// minimises an algebraic error and, measured on noisy data, is biased);
// |g| held when problem.gravity_magnitude > 0. Fills out (x, depths,
// residual figures, covariance); `residual` the stacked errors [px].
bool RefineOnReprojection(const GyroAidedProblem& problem,
                          const std::vector<CameraTerms>& cameras, Vec9 x,
                          std::vector<double> depths, GyroAidedSolution* out,
                          Eigen::VectorXd* residual) {
  constexpr int kIterations = 4;
  Mat9 H;
  Vec9 b;
  Eigen::MatrixXd P = Mat9::Identity();
  std::vector<TrackRows> rows;
  const double prior =
      problem.accel_bias_sigma > 0.0
          ? 1.0 / (problem.accel_bias_sigma * problem.accel_bias_sigma)
          : 1e12;
  for (int it = 0; it <= kIterations; ++it) {
    rows = ReprojectionRows(problem, cameras, x, depths, out, nullptr);
    Reduce(rows, problem.accel_bias_sigma, &H, &b);
    if (it == kIterations) break;
    // The normal equations in the absolute unknowns: H x_new = b + H x,
    // with the prior's pull towards b_a = 0.
    Vec9 rhs = b + H * x;
    rhs.segment<3>(kBa) -= prior * x.segment<3>(kBa);
    Vec9 x_new = H.ldlt().solve(rhs);
    if (problem.gravity_magnitude > 0.0) {
      Eigen::Matrix<double, 9, 8> tangent;
      if (!SolveOnSphere(H, rhs, problem.gravity_magnitude, &x_new, &tangent)) {
        return false;
      }
      P = tangent;
    }
    if (!x_new.allFinite()) return false;
    const Vec9 dx = x_new - x;
    for (size_t t = 0; t < rows.size(); ++t) {
      const TrackRows& r = rows[t];
      depths[t] += r.c.dot(r.d - r.B * dx) / (r.c.squaredNorm() + 1e-12);
    }
    x = x_new;
  }
  // The residual is needed for the covariance's sigma^2 whether or not the
  // caller wants it (without it the covariance was zero).
  std::vector<double> stacked;
  ReprojectionRows(problem, cameras, x, depths, out, &stacked);
  out->v_0 = x.segment<3>(kV);
  out->g = x.segment<3>(kG);
  out->b_a = x.segment<3>(kBa);
  out->depth = depths;
  double sum = 0.0;
  for (double e : stacked) sum += e * e;
  if (residual != nullptr) {
    *residual = Eigen::Map<Eigen::VectorXd>(stacked.data(), stacked.size());
  }
  out->covariance = Covariance(H, P, sum, RowCount(rows),
                               static_cast<int>(P.cols() + rows.size()));
  return true;
}

// Solves at b_g with the rows' weights from `previous`; with `residual`,
// the stacked weighted residual too.
bool SolveRows(const GyroAidedProblem& problem, const Eigen::Vector3d& b_g,
               const GyroAidedSolution* previous, GyroAidedSolution* out,
               Eigen::VectorXd* residual) {
  if (problem.tracks.size() < 2) return false;
  const std::vector<CameraTerms> cameras = CamerasAt(problem, b_g);
  const std::vector<TrackRows> rows = BuildRows(problem, cameras, previous);
  Mat9 H;
  Vec9 b;
  Reduce(rows, problem.accel_bias_sigma, &H, &b);
  if (Singular(H)) return false;
  Vec9 x = H.ldlt().solve(b);
  if (!x.allFinite()) return false;
  out->free_g_norm = x.segment<3>(kG).norm();
  Eigen::MatrixXd P = Mat9::Identity();
  if (problem.gravity_magnitude > 0.0) {
    Eigen::Matrix<double, 9, 8> tangent;
    if (!SolveOnSphere(H, b, problem.gravity_magnitude, &x, &tangent)) {
      return false;
    }
    P = tangent;
  }
  out->b_g = b_g;
  const double sum = Evaluate(problem, cameras, rows, x, out, residual);
  out->covariance = Covariance(H, P, sum, RowCount(rows),
                               static_cast<int>(P.cols() + rows.size()));
  return RefineOnReprojection(problem, cameras, x, out->depth, out, residual);
}

// Gauss-Newton with Levenberg damping on b_g, the residual of the linear
// solution at each bias (variable projection), Jacobian by central
// differences (three components).
bool FitBias(const GyroAidedProblem& problem, const GyroAidedSolution* weights,
             Eigen::Vector3d* b_g) {
  constexpr int kIterations = 10;
  constexpr double kStep = 1e-5;  // [rad/s]
  GyroAidedSolution s;
  Eigen::VectorXd r;
  if (!SolveRows(problem, *b_g, weights, &s, &r)) return false;
  double cost = r.squaredNorm(), damping = 1e-6;
  for (int it = 0; it < kIterations; ++it) {
    Eigen::MatrixXd J(r.size(), 3);
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d plus = *b_g, minus = *b_g;
      plus[j] += kStep;
      minus[j] -= kStep;
      Eigen::VectorXd rp, rm;
      if (!SolveRows(problem, plus, weights, &s, &rp) ||
          !SolveRows(problem, minus, weights, &s, &rm)) {
        return false;
      }
      J.col(j) = (rp - rm) / (2.0 * kStep);
    }
    const Eigen::Matrix3d JtJ = J.transpose() * J;
    const Eigen::Vector3d Jtr = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Eigen::Matrix3d damped = JtJ;
      damped.diagonal() *= 1.0 + damping;
      const Eigen::Vector3d step = -damped.ldlt().solve(Jtr);
      Eigen::VectorXd r_new;
      if (step.allFinite() &&
          SolveRows(problem, *b_g + step, weights, &s, &r_new) &&
          r_new.squaredNorm() < cost) {
        *b_g += step;
        r = r_new;
        const double change = cost - r.squaredNorm();
        cost = r.squaredNorm();
        damping = std::max(1e-9, damping * 0.1);
        improved = true;
        if (step.norm() < 1e-7 || change < 1e-10 * cost) return true;
      } else {
        damping *= 10.0;
      }
    }
    if (!improved) return true;  // at a minimum to the step's precision
  }
  return true;
}

}  // namespace

GyroAidedFrameState FrameState(const GyroAidedProblem& problem,
                               const GyroAidedSolution& solution, int k) {
  GyroAidedFrameState s;
  s.v_v = solution.v_0;
  if (k == 0) return s;
  const ImuPreintegration& imu = problem.from_first[k - 1];
  const ImuDelta d = imu.Corrected(solution.b_a, solution.b_g);
  s.t_s = imu.sum_dt();
  s.R_v_b = d.q.normalized().toRotationMatrix();
  s.p_v_b = solution.v_0 * s.t_s + 0.5 * solution.g * s.t_s * s.t_s + d.p;
  s.v_v = solution.v_0 + solution.g * s.t_s + d.v;
  return s;
}

bool SolveAtBias(const GyroAidedProblem& problem, const Eigen::Vector3d& b_g,
                 const GyroAidedSolution* previous, GyroAidedSolution* out) {
  return SolveRows(problem, b_g, previous, out, nullptr);
}

bool FitGyroAided(GyroAidedProblem* problem, const Eigen::Vector3d& b_g_guess,
                  GyroAidedSolution* out) {
  // The bias from the rotations alone first (the fit on the reprojection
  // errors, started from zero, was measured to stop in a wrong minimum).
  Eigen::Vector3d b_g = b_g_guess;
  if (!FitGyroBiasFromRotations(*problem, &b_g)) return false;
  GyroAidedSolution solution;
  const GyroAidedSolution* weights = nullptr;
  // Two passes of the fit on the reprojection errors, the first with unit
  // depths in the linear start, the IMU re-propagated at the bias after
  // each.
  constexpr int kPasses = 2;
  for (int pass = 0; pass < kPasses; ++pass) {
    if (!FitBias(*problem, weights, &b_g)) return false;
    for (ImuPreintegration& imu : problem->from_first) {
      imu.Repropagate(imu.lin_b_a(), b_g);
    }
    GyroAidedSolution next;
    if (!SolveAtBias(*problem, b_g, weights, &next)) return false;
    solution = next;
    weights = &solution;
  }
  *out = solution;
  return true;
}

}  // namespace vio
