// WindowLinearization's normal equations A = J^T J, g = J^T r (reduced block
// A_rr, each landmark's w_l and h_l), the landmarks' elimination by their
// scalar Schur complements and the damped solve, as the header derives them.

#include <algorithm>

#include "estimator/window_linearization.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstRowMajorMap = Eigen::Map<const RowMajorMatrix>;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using RowMajor26 = Eigen::Matrix<double, 2, 6, Eigen::RowMajor>;

// Ceres' LEVENBERG_MARQUARDT bounds on the damping diagonal.
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;

double ClampDiagonal(double d) {
  return std::min(std::max(d, kMinDiagonal), kMaxDiagonal);
}

// A(oa.., ob..) += Ja^T Jb for row-major Jacobians of `rows` rows. The
// visual residuals' shape (2 rows, 6-wide poses) takes the fixed-size path:
// most of the pairs are of that kind.
void AddJtJ(const double* Ja, int ta, const double* Jb, int tb, int rows,
            int oa, int ob, Eigen::MatrixXd* A) {
  if (rows == 2 && ta == 6 && tb == 6) {
    A->block<6, 6>(oa, ob).noalias() +=
        Eigen::Map<const RowMajor26>(Ja).transpose() *
        Eigen::Map<const RowMajor26>(Jb);
    return;
  }
  A->block(oa, ob, ta, tb).noalias() +=
      ConstRowMajorMap(Ja, rows, ta)
          .transpose()
          .lazyProduct(ConstRowMajorMap(Jb, rows, tb));
}

// out(t) += Ja^T v for a row-major Jacobian of `rows` rows.
void AddJtv(const double* Ja, int ta, const double* v, int rows, double* out) {
  if (rows == 2 && ta == 6) {
    Eigen::Map<Vector6d>(out).noalias() +=
        Eigen::Map<const RowMajor26>(Ja).transpose() *
        Eigen::Map<const Eigen::Vector2d>(v);
    return;
  }
  Eigen::Map<Eigen::VectorXd>(out, ta).noalias() +=
      ConstRowMajorMap(Ja, rows, ta).transpose() *
      Eigen::Map<const Eigen::VectorXd>(v, rows);
}

}  // namespace

void WindowLinearization::BuildNormalEquations() {
  A_rr_.setZero();
  g_.setZero();
  diagonal_.setZero();
  std::fill(w_.begin(), w_.end(), 0.0);
  for (const Prior& p : priors_) {
    const MarginalizationPrior& f = *p.factor;
    for (size_t a = 0; a < p.blocks.size(); ++a) {
      const Block& ba = blocks_[p.blocks[a]];
      if (ba.role != Role::kReduced) continue;
      const int pa = f.TangentOffset(static_cast<int>(a));
      g_.segment(ba.offset, ba.tangent) += p.gradient.segment(pa, ba.tangent);
      for (size_t b = 0; b < p.blocks.size(); ++b) {
        const Block& bb = blocks_[p.blocks[b]];
        if (bb.role != Role::kReduced || ba.offset > bb.offset) continue;
        A_rr_.block(ba.offset, bb.offset, ba.tangent, bb.tangent) +=
            p.information.block(pa, f.TangentOffset(static_cast<int>(b)),
                                ba.tangent, bb.tangent);
      }
    }
  }
  for (const Residual& res : residuals_) {
    if (res.prior >= 0) continue;
    const double* r = r_.data() + res.residual_offset;
    const double* J_l =
        res.landmark >= 0
            ? jacobians_.data() + terms_[res.landmark_term].jacobian_offset
            : nullptr;
    for (int a = res.first_term; a < res.first_term + res.num_terms; ++a) {
      const Term& ta = terms_[a];
      if (ta.jacobian_offset < 0) continue;
      const Block& ba = blocks_[ta.block];
      const double* J_a = jacobians_.data() + ta.jacobian_offset;
      AddJtv(J_a, ba.tangent, r, res.rows, g_.data() + ba.offset);
      if (ba.role == Role::kEliminated) {
        diagonal_[ba.offset] +=
            Eigen::Map<const Eigen::VectorXd>(J_a, res.rows).squaredNorm();
        continue;
      }
      if (J_l != nullptr) {
        AddJtv(J_a, ba.tangent, J_l, res.rows, w_.data() + ta.w_offset);
      }
      for (int b = a; b < res.first_term + res.num_terms; ++b) {
        const Term& tb = terms_[b];
        const Block& bb = blocks_[tb.block];
        if (tb.jacobian_offset < 0 || bb.role != Role::kReduced) continue;
        const double* J_b = jacobians_.data() + tb.jacobian_offset;
        // Upper triangle: the block with the smaller offset is the row.
        if (ba.offset <= bb.offset) {
          AddJtJ(J_a, ba.tangent, J_b, bb.tangent, res.rows, ba.offset,
                 bb.offset, &A_rr_);
        } else {
          AddJtJ(J_b, bb.tangent, J_a, ba.tangent, res.rows, bb.offset,
                 ba.offset, &A_rr_);
        }
      }
    }
  }
  diagonal_.head(num_reduced_) = A_rr_.diagonal();
}

void WindowLinearization::AddSchurOfLandmark(const Landmark& l, double inv_h,
                                             Eigen::MatrixXd* S) const {
  // S -= w w^T / h over the blocks the landmark touches (upper triangle).
  const double* w = w_.data() + l.w_offset;
  int part_p = 0;
  for (int p : l.touched) {
    const Block& bp = blocks_[p];
    int part_q = 0;
    for (int q : l.touched) {
      const Block& bq = blocks_[q];
      if (bp.offset <= bq.offset) {
        if (bp.tangent == 6 && bq.tangent == 6) {
          S->block<6, 6>(bp.offset, bq.offset).noalias() -=
              (inv_h * Eigen::Map<const Vector6d>(w + part_p)) *
              Eigen::Map<const Vector6d>(w + part_q).transpose();
        } else {
          S->block(bp.offset, bq.offset, bp.tangent, bq.tangent).noalias() -=
              (inv_h *
               Eigen::Map<const Eigen::VectorXd>(w + part_p, bp.tangent)) *
              Eigen::Map<const Eigen::VectorXd>(w + part_q, bq.tangent)
                  .transpose();
        }
      }
      part_q += bq.tangent;
    }
    part_p += bp.tangent;
  }
}

void WindowLinearization::FormReducedSystem(double lambda) {
  S_ = A_rr_;
  Eigen::VectorXd& rhs = rhs_;
  rhs = -g_.head(num_reduced_);
  for (int i = 0; i < num_reduced_; ++i) {
    S_(i, i) += lambda * ClampDiagonal(diagonal_[i]);
  }
  std::vector<double>& inv_h = inv_h_;
  std::fill(inv_h.begin(), inv_h.end(), 0.0);
  for (size_t k = 0; k < landmarks_.size(); ++k) {
    const int o = num_reduced_ + static_cast<int>(k);
    const double h = diagonal_[o];
    if (h == 0.0) continue;  // no information: stays where it is
    inv_h[k] = 1.0 / (h + lambda * ClampDiagonal(h));
    const Landmark& l = landmarks_[k];
    AddSchurOfLandmark(l, inv_h[k], &S_);
    int part = 0;
    for (int p : l.touched) {
      const Block& bp = blocks_[p];
      rhs.segment(bp.offset, bp.tangent) +=
          (inv_h[k] * g_[o]) * Eigen::Map<const Eigen::VectorXd>(
                                   w_.data() + l.w_offset + part, bp.tangent);
      part += bp.tangent;
    }
  }
}

bool WindowLinearization::Factor() {
  ++solve_counts_.factorizations;
  llt_.compute(S_);
  factor_kept_ = llt_.info() == Eigen::Success;
  return factor_kept_;
}

bool WindowLinearization::BackSubstitute(Eigen::VectorXd* dx) const {
  for (size_t k = 0; k < landmarks_.size(); ++k) {
    const int o = num_reduced_ + static_cast<int>(k);
    double w_dx = 0.0;
    const Landmark& l = landmarks_[k];
    int part = 0;
    for (int p : l.touched) {
      const Block& bp = blocks_[p];
      w_dx += Eigen::Map<const Eigen::VectorXd>(w_.data() + l.w_offset + part,
                                                bp.tangent)
                  .dot(dx->segment(bp.offset, bp.tangent));
      part += bp.tangent;
    }
    (*dx)[o] = inv_h_[k] == 0.0 ? 0.0 : -(g_[o] + w_dx) * inv_h_[k];
  }
  return dx->allFinite();
}

bool WindowLinearization::SolveDamped(double lambda, Eigen::VectorXd* dx) {
  FormReducedSystem(lambda);
  dx->resize(num_tangent_);
  if (num_reduced_ > 0) {
    if (!Factor()) return false;
    dx->head(num_reduced_) = llt_.solve(rhs_);
  }
  return BackSubstitute(dx);
}

bool WindowLinearization::SolveDampedWithKeptFactor(double lambda,
                                                    Eigen::VectorXd* dx) {
  if (!factor_kept_ || num_reduced_ == 0) return SolveDamped(lambda, dx);
  FormReducedSystem(lambda);
  dx->resize(num_tangent_);
  // Preconditioned by the kept factor L of S_old: the iteration works on
  // L^-1 S L^-T, which is I + L^-1 (S - S_old) L^-T, so it converges in a few
  // steps while S stays near S_old (one linearisation to the next).
  pcg_.preconditioner().llt = &llt_;
  pcg_.setMaxIterations(kMaxPcgIterations);
  pcg_.setTolerance(kPcgTolerance);
  pcg_.compute(S_);
  dx->head(num_reduced_) = pcg_.solve(rhs_);
  solve_counts_.pcg_iterations += static_cast<int>(pcg_.iterations());
  if (pcg_.info() == Eigen::Success && dx->head(num_reduced_).allFinite()) {
    ++solve_counts_.pcg_solves;
    return BackSubstitute(dx);
  }
  ++solve_counts_.pcg_fallbacks;
  if (!Factor()) return false;
  dx->head(num_reduced_) = llt_.solve(rhs_);
  return BackSubstitute(dx);
}

double WindowLinearization::QuadraticForm(const Eigen::VectorXd& v) const {
  // v^T A v = v_r^T A_rr v_r + sum_l (2 v_l w_l^T v_r + h_l v_l^2).
  const auto v_r = v.head(num_reduced_);
  double sum = v_r.dot(A_rr_.selfadjointView<Eigen::Upper>() * v_r);
  for (size_t k = 0; k < landmarks_.size(); ++k) {
    const int o = num_reduced_ + static_cast<int>(k);
    const Landmark& l = landmarks_[k];
    double w_v = 0.0;
    int part = 0;
    for (int p : l.touched) {
      const Block& bp = blocks_[p];
      w_v += Eigen::Map<const Eigen::VectorXd>(w_.data() + l.w_offset + part,
                                               bp.tangent)
                 .dot(v.segment(bp.offset, bp.tangent));
      part += bp.tangent;
    }
    sum += 2.0 * v[o] * w_v + diagonal_[o] * v[o] * v[o];
  }
  return sum;
}

}  // namespace vio
