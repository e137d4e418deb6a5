#include "estimator/window_linearization.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "factors/pose_manifold.h"
#include "geometry/so3.h"

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

// Throws the set-up error of `what` number `index` (built only on failure).
void Require(bool ok, const char* what, size_t index, const char* message) {
  if (!ok) {
    throw std::invalid_argument(std::string("SolveWindow: ") + what + " " +
                                std::to_string(index) + " " + message);
  }
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

void WindowLinearization::SetUp(const WindowSolverProblem& problem) {
  blocks_in_ = &problem.blocks;
  residuals_in_ = &problem.residuals;
  block_indices_ = &problem.block_indices;
  num_reduced_ = 0;
  num_tangent_ = 0;
  max_ambient_jacobian_ = 0;
  SetUpBlocks();
  SetUpResiduals();
  SetUpLandmarkParts();
  A_rr_.resize(num_reduced_, num_reduced_);
  S_.resize(num_reduced_, num_reduced_);
  g_.resize(num_tangent_);
  diagonal_.resize(num_tangent_);
  rhs_.resize(num_reduced_);
  inv_h_.resize(landmarks_.size());
}

void WindowLinearization::SetUpBlocks() {
  blocks_.assign(blocks_in_->size(), Block());
  int num_landmarks = 0;
  int ambient = 0;
  int plus = 0;
  for (size_t i = 0; i < blocks_in_->size(); ++i) {
    const WindowSolverBlock& in = (*blocks_in_)[i];
    Require(in.values != nullptr && in.size >= 1, "block", i, "is empty");
    Require(in.manifold == nullptr || in.manifold->AmbientSize() == in.size,
            "block", i, "has a manifold of another ambient size");
    Block& b = blocks_[i];
    b.tangent = in.manifold ? in.manifold->TangentSize() : in.size;
    b.state_offset = ambient;
    ambient += in.size;
    if (in.constant) continue;
    if (in.eliminated) {
      Require(in.manifold == nullptr && in.size == 1, "block", i,
              "is eliminated but not a Euclidean block of size 1");
      b.role = Role::kEliminated;
      b.offset = num_landmarks++;  // moved below
      continue;
    }
    b.role = Role::kReduced;
    b.offset = num_reduced_;
    num_reduced_ += b.tangent;
    if (in.manifold != nullptr) {
      b.plus_offset = plus;
      plus += in.size * b.tangent;
    }
  }
  // Landmarks after the reduced coordinates. (Resized, not rebuilt: each
  // landmark keeps its buffer from the last step.)
  landmarks_.resize(num_landmarks);
  for (size_t i = 0; i < blocks_.size(); ++i) {
    Block& b = blocks_[i];
    if (b.role != Role::kEliminated) continue;
    Landmark& l = landmarks_[b.offset];
    l.block = static_cast<int>(i);
    l.touched.clear();
    l.w_offset = 0;
    l.w_size = 0;
    b.offset += num_reduced_;
  }
  num_tangent_ = num_reduced_ + static_cast<int>(landmarks_.size());
  plus_.resize(plus);
  candidate_.resize(ambient);
}

void WindowLinearization::SetUpResiduals() {
  int rows_total = 0;
  int jacobian_total = 0;
  int max_rows = 0;
  int max_terms = 0;
  residuals_.clear();
  terms_.clear();
  parameters_.clear();
  candidates_.clear();
  priors_.clear();
  for (size_t k = 0; k < residuals_in_->size(); ++k) {
    const WindowSolverResidual& in = (*residuals_in_)[k];
    Require(in.cost != nullptr, "residual", k, "has no cost function");
    const std::vector<int32_t>& sizes = in.cost->parameter_block_sizes();
    Require(static_cast<int>(sizes.size()) == in.num_blocks &&
                in.first_block >= 0 &&
                in.first_block + in.num_blocks <=
                    static_cast<int>(block_indices_->size()),
            "residual", k, "has the wrong number of parameter blocks");
    Residual res;
    res.rows = in.cost->num_residuals();
    res.residual_offset = rows_total;
    res.first_term = static_cast<int>(terms_.size());
    res.num_terms = in.num_blocks;
    rows_total += res.rows;
    max_rows = std::max(max_rows, res.rows);
    max_terms = std::max(max_terms, res.num_terms);
    int ambient_jacobian = 0;
    for (int j = 0; j < in.num_blocks; ++j) {
      const int i = (*block_indices_)[in.first_block + j];
      Require(i >= 0 && i < static_cast<int>(blocks_.size()), "residual", k,
              "names a block that does not exist");
      Require((*blocks_in_)[i].size == sizes[j], "residual", k,
              "has a parameter of another size than its block");
      const Block& b = blocks_[i];
      Term t;
      t.block = i;
      parameters_.push_back((*blocks_in_)[i].values);
      if (b.role == Role::kConstant) {
        candidates_.push_back((*blocks_in_)[i].values);
      } else {
        candidates_.push_back(candidate_.data() + b.state_offset);
        if (in.prior == nullptr) {
          t.jacobian_offset = jacobian_total;
          jacobian_total += res.rows * b.tangent;
          ambient_jacobian += res.rows * (*blocks_in_)[i].size;
        }
      }
      if (b.role == Role::kEliminated) {
        Require(res.landmark < 0 && in.prior == nullptr, "residual", k,
                "touches two eliminated blocks, or is a prior on one");
        res.landmark = b.offset - num_reduced_;
        res.landmark_term = static_cast<int>(terms_.size());
      }
      terms_.push_back(t);
    }
    if (in.prior != nullptr) SetUpPrior(static_cast<int>(k), &res);
    max_ambient_jacobian_ = std::max(max_ambient_jacobian_, ambient_jacobian);
    residuals_.push_back(res);
  }
  r_.resize(rows_total);
  jacobians_.resize(jacobian_total);
  ambient_.resize(max_ambient_jacobian_);
  ambient_ptrs_.resize(max_terms);
  scratch_r_.resize(max_rows);
}

void WindowLinearization::SetUpPrior(int k, Residual* res) {
  const WindowSolverResidual& in = (*residuals_in_)[k];
  Require(static_cast<const ceres::CostFunction*>(in.prior) == in.cost &&
              in.loss == nullptr,
          "residual", k, "names a prior other than its cost, or has a loss");
  Prior p;
  p.factor = in.prior;
  const std::vector<PriorBlock>& kinds = in.prior->blocks();
  for (int j = 0; j < in.num_blocks; ++j) {
    const int i = (*block_indices_)[in.first_block + j];
    Require(kinds[j].TangentSize() == blocks_[i].tangent &&
                (kinds[j].kind == PriorBlockKind::kEuclidean) ==
                    ((*blocks_in_)[i].manifold == nullptr),
            "residual", k, "is a prior whose block kinds disagree");
    p.blocks.push_back(i);
  }
  res->prior = static_cast<int>(priors_.size());
  priors_.push_back(std::move(p));
}

void WindowLinearization::SetUpLandmarkParts() {
  // Each landmark's w holds one part per reduced block its residuals touch,
  // in the order first met; a term's w_offset is first that part's index,
  // then its offset in w_.
  for (const Residual& res : residuals_) {
    if (res.landmark < 0) continue;
    Landmark& l = landmarks_[res.landmark];
    for (int j = res.first_term; j < res.first_term + res.num_terms; ++j) {
      Term& t = terms_[j];
      if (blocks_[t.block].role != Role::kReduced) continue;
      auto it = std::find(l.touched.begin(), l.touched.end(), t.block);
      if (it == l.touched.end()) it = l.touched.insert(it, t.block);
      t.w_offset = static_cast<int>(it - l.touched.begin());
    }
  }
  int w_total = 0;
  for (Landmark& l : landmarks_) {
    l.w_offset = w_total;
    for (int block : l.touched) l.w_size += blocks_[block].tangent;
    w_total += l.w_size;
  }
  for (const Residual& res : residuals_) {
    if (res.landmark < 0) continue;
    const Landmark& l = landmarks_[res.landmark];
    for (int j = res.first_term; j < res.first_term + res.num_terms; ++j) {
      Term& t = terms_[j];
      if (t.w_offset < 0) continue;
      int offset = l.w_offset;
      for (int p = 0; p < t.w_offset; ++p) {
        offset += blocks_[l.touched[p]].tangent;
      }
      t.w_offset = offset;
    }
  }
  w_.resize(w_total);
}

bool WindowLinearization::EvaluateResidual(int k) {
  const Residual& res = residuals_[k];
  double* r = r_.data() + res.residual_offset;
  if (res.prior >= 0) {
    return (*residuals_in_)[k].cost->Evaluate(
               parameters_.data() + res.first_term, r, nullptr) &&
           LinearizePrior(k);
  }
  const TangentJacobians* tangent_cost = (*residuals_in_)[k].tangent;
  if (tangent_cost != nullptr) {
    for (int j = 0; j < res.num_terms; ++j) {
      const Term& t = terms_[res.first_term + j];
      ambient_ptrs_[j] = t.jacobian_offset < 0
                             ? nullptr
                             : jacobians_.data() + t.jacobian_offset;
    }
    if (!tangent_cost->EvaluateTangent(parameters_.data() + res.first_term, r,
                                       ambient_ptrs_.data())) {
      return false;
    }
    if (!Eigen::Map<const Eigen::VectorXd>(r, res.rows).allFinite()) {
      return false;
    }
    for (int j = 0; j < res.num_terms; ++j) {
      const Term& t = terms_[res.first_term + j];
      if (t.jacobian_offset >= 0 &&
          !ConstRowMajorMap(ambient_ptrs_[j], res.rows,
                            blocks_[t.block].tangent)
               .allFinite()) {
        return false;
      }
    }
    return true;
  }
  int ambient = 0;
  for (int j = 0; j < res.num_terms; ++j) {
    const Term& t = terms_[res.first_term + j];
    if (t.jacobian_offset < 0) {
      ambient_ptrs_[j] = nullptr;
      continue;
    }
    ambient_ptrs_[j] = ambient_.data() + ambient;
    ambient += res.rows * (*blocks_in_)[t.block].size;
  }
  if (!(*residuals_in_)[k].cost->Evaluate(parameters_.data() + res.first_term,
                                          r, ambient_ptrs_.data())) {
    return false;
  }
  if (!Eigen::Map<const Eigen::VectorXd>(r, res.rows).allFinite()) return false;
  for (int j = 0; j < res.num_terms; ++j) {
    const Term& t = terms_[res.first_term + j];
    if (t.jacobian_offset < 0) continue;
    const Block& b = blocks_[t.block];
    const int size = (*blocks_in_)[t.block].size;
    double* J = jacobians_.data() + t.jacobian_offset;
    Eigen::Map<RowMajorMatrix> tangent(J, res.rows, b.tangent);
    const ConstRowMajorMap amb(ambient_ptrs_[j], res.rows, size);
    if (b.plus_offset >= 0) {
      // Ceres' rule: the tangent Jacobian is J_ambient * PlusJacobian(x).
      const double* P = plus_.data() + b.plus_offset;
      if (res.rows == 2 && size == kPoseAmbientSize &&
          b.tangent == kPoseTangentSize) {
        Eigen::Map<RowMajor26>(J).noalias() =
            Eigen::Map<const Eigen::Matrix<double, 2, 7, Eigen::RowMajor>>(
                ambient_ptrs_[j]) *
            Eigen::Map<const PosePlusJacobian>(P);
      } else {
        tangent.noalias() =
            amb.lazyProduct(ConstRowMajorMap(P, size, b.tangent));
      }
    } else {
      tangent = amb;
    }
    if (!tangent.allFinite()) return false;
  }
  return true;
}

bool WindowLinearization::LinearizePrior(int k) {
  const Residual& res = residuals_[k];
  Prior& p = priors_[res.prior];
  const MarginalizationPrior& f = *p.factor;
  if (!Eigen::Map<const Eigen::VectorXd>(r_.data() + res.residual_offset,
                                         res.rows)
           .allFinite() ||
      !f.Delta(parameters_.data() + res.first_term, &p.delta)) {
    return false;
  }
  // M: identity but for Jr^-1(phi) on each pose's rotation (the prior's
  // BlockJacobian); M^T G M and M^T (J^T r0 + G dx) touch only those columns.
  p.information = f.information();
  p.gradient = f.gradient0();
  p.gradient.noalias() += f.information() * p.delta;
  for (size_t b = 0; b < p.blocks.size(); ++b) {
    if (f.blocks()[b].kind != PriorBlockKind::kPose) continue;
    const int c = f.TangentOffset(static_cast<int>(b)) + kPoseRotation;
    const Eigen::Matrix3d M = RightJacobianInverse(p.delta.segment<3>(c));
    p.information.middleCols<3>(c) = p.information.middleCols<3>(c) * M;
    p.information.middleRows<3>(c) =
        M.transpose() * p.information.middleRows<3>(c);
    p.gradient.segment<3>(c) = M.transpose() * p.gradient.segment<3>(c);
  }
  return p.information.allFinite() && p.gradient.allFinite();
}

void WindowLinearization::Correct(int k, double* cost) {
  const Residual& res = residuals_[k];
  const ceres::LossFunction* loss = (*residuals_in_)[k].loss;
  Eigen::Map<Eigen::VectorXd> r(r_.data() + res.residual_offset, res.rows);
  const double sq = r.squaredNorm();
  if (loss == nullptr) {
    *cost += 0.5 * sq;
    return;
  }
  double rho[3];
  loss->Evaluate(sq, rho);
  *cost += 0.5 * rho[0];
  // Ceres' Corrector (internal/ceres/corrector.cc): the robust problem's
  // Gauss-Newton model is that of r~ = s r, J~ = sqrt(rho') (I - a r r^T /
  // |r|^2) J with a the root of a^2/2 - a = rho'' |r|^2 / rho' (Triggs et
  // al., "Bundle adjustment - a modern synthesis", sec. 4.3); where rho'' <= 0
  // (Huber and Cauchy away from the origin) a = 0, plain sqrt(rho') scaling.
  double scale_r = 0.0;
  double scale_j = 0.0;
  double alpha_sq_norm = 0.0;
  if (rho[1] > 0.0) {
    scale_j = std::sqrt(rho[1]);
    scale_r = scale_j;
    if (sq > 0.0 && rho[2] > 0.0) {
      const double alpha = 1.0 - std::sqrt(1.0 + 2.0 * sq * rho[2] / rho[1]);
      scale_r = scale_j / (1.0 - alpha);
      alpha_sq_norm = alpha / sq;
    }
  }
  for (int j = res.first_term; j < res.first_term + res.num_terms; ++j) {
    const Term& t = terms_[j];
    if (t.jacobian_offset < 0) continue;
    Eigen::Map<RowMajorMatrix> J(jacobians_.data() + t.jacobian_offset,
                                 res.rows, blocks_[t.block].tangent);
    if (alpha_sq_norm != 0.0) {
      const Eigen::RowVectorXd rtJ = r.transpose() * J;
      J -= alpha_sq_norm * r * rtJ;
    }
    J *= scale_j;
  }
  r *= scale_r;
}

bool WindowLinearization::Linearize() {
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.plus_offset < 0) continue;
    if (!(*blocks_in_)[i].manifold->PlusJacobian(
            (*blocks_in_)[i].values, plus_.data() + b.plus_offset)) {
      return false;
    }
  }
  double cost = 0.0;
  for (size_t k = 0; k < residuals_.size(); ++k) {
    if (!EvaluateResidual(static_cast<int>(k))) return false;
    Correct(static_cast<int>(k), &cost);
  }
  if (!std::isfinite(cost)) return false;
  cost_ = cost;
  BuildNormalEquations();
  return true;
}

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

bool WindowLinearization::SolveDamped(double lambda, Eigen::VectorXd* dx) {
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
  dx->resize(num_tangent_);
  if (num_reduced_ > 0) {
    llt_.compute(S_);
    if (llt_.info() != Eigen::Success) return false;
    dx->head(num_reduced_) = llt_.solve(rhs);
  }
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
    (*dx)[o] = inv_h[k] == 0.0 ? 0.0 : -(g_[o] + w_dx) * inv_h[k];
  }
  return dx->allFinite();
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

double WindowLinearization::ProjectedGradientMaxNorm() const {
  double max_norm = 0.0;
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.role == Role::kConstant) continue;
    const WindowSolverBlock& in = (*blocks_in_)[i];
    for (int c = 0; c < b.tangent; ++c) {
      const double g = g_[b.offset + c];
      double step = std::abs(g);
      if (in.manifold == nullptr) {
        const double x = in.values[c];
        step = std::abs(x - std::min(std::max(x - g, in.lower), in.upper));
      }
      max_norm = std::max(max_norm, step);
    }
  }
  return max_norm;
}

double WindowLinearization::StateNorm() const {
  double sum = 0.0;
  for (size_t i = 0; i < blocks_.size(); ++i) {
    if (blocks_[i].role == Role::kConstant) continue;
    sum += Eigen::Map<const Eigen::VectorXd>((*blocks_in_)[i].values,
                                             (*blocks_in_)[i].size)
               .squaredNorm();
  }
  return std::sqrt(sum);
}

bool WindowLinearization::CandidateCost(const Eigen::VectorXd& dx,
                                        double* cost) {
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.role == Role::kConstant) continue;
    const WindowSolverBlock& in = (*blocks_in_)[i];
    double* out = candidate_.data() + b.state_offset;
    if (in.manifold != nullptr) {
      if (!in.manifold->Plus(in.values, dx.data() + b.offset, out)) {
        return false;
      }
      continue;
    }
    for (int c = 0; c < in.size; ++c) {
      // Projected onto the bounds, as Ceres' ParameterBlock::Plus does.
      out[c] = std::min(std::max(in.values[c] + dx[b.offset + c], in.lower),
                        in.upper);
    }
  }
  double sum = 0.0;
  for (size_t k = 0; k < residuals_.size(); ++k) {
    const Residual& res = residuals_[k];
    if (!(*residuals_in_)[k].cost->Evaluate(candidates_.data() + res.first_term,
                                            scratch_r_.data(), nullptr)) {
      return false;
    }
    const Eigen::Map<const Eigen::VectorXd> r(scratch_r_.data(), res.rows);
    if (!r.allFinite()) return false;
    const double sq = r.squaredNorm();
    if ((*residuals_in_)[k].loss == nullptr) {
      sum += 0.5 * sq;
    } else {
      double rho[3];
      (*residuals_in_)[k].loss->Evaluate(sq, rho);
      sum += 0.5 * rho[0];
    }
  }
  if (!std::isfinite(sum)) return false;
  *cost = sum;
  return true;
}

void WindowLinearization::Accept() {
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.role == Role::kConstant) continue;
    std::copy_n(candidate_.data() + b.state_offset, (*blocks_in_)[i].size,
                (*blocks_in_)[i].values);
  }
}

}  // namespace vio
