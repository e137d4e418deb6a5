#include "estimator/marginalization_system.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "factors/pose_manifold.h"
#include "factors/tangent_jacobians.h"
#include "geometry/so3.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstRowMajorMap = Eigen::Map<const RowMajorMatrix>;

int TangentSizeOf(const MarginalizationParameterBlock& p) {
  return p.TangentSize();
}

// A(oa.., ob..) += Ja^T Jb for row-major Jacobians of `rows` rows, with the
// visual factors' shape (2 rows, 6-wide poses) at fixed size.
void AddJtJ(const double* Ja, int ta, const double* Jb, int tb, int rows,
            int oa, int ob, Eigen::MatrixXd* A) {
  using RowMajor26 = Eigen::Matrix<double, 2, 6, Eigen::RowMajor>;
  if (rows == 2 && ta == 6 && tb == 6) {
    A->block<6, 6>(oa, ob).noalias() +=
        Eigen::Map<const RowMajor26>(Ja).transpose() *
        Eigen::Map<const RowMajor26>(Jb);
    return;
  }
  A->block(oa, ob, ta, tb).noalias() +=
      ConstRowMajorMap(Ja, rows, ta).transpose() *
      ConstRowMajorMap(Jb, rows, tb);
}

// A(op.., oq..) -= s w_p w_q^T, the poses' 6 x 6 case at fixed size.
void SubtractOuter(const double* w_p, int tp, const double* w_q, int tq,
                   double s, int op, int oq, Eigen::MatrixXd* A) {
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  if (tp == 6 && tq == 6) {
    A->block<6, 6>(op, oq).noalias() -=
        (s * Eigen::Map<const Vector6d>(w_p)) *
        Eigen::Map<const Vector6d>(w_q).transpose();
    return;
  }
  A->block(op, oq, tp, tq).noalias() -=
      (s * Eigen::Map<const Eigen::VectorXd>(w_p, tp)) *
      Eigen::Map<const Eigen::VectorXd>(w_q, tq).transpose();
}

}  // namespace

MarginalizationSystem::MarginalizationSystem(
    const MarginalizationProblem& problem)
    : problem_(problem) {
  AssignSlots();
  LayOutScalars();
  const int size = dense_marginalized_size_ + kept_size_;
  H_.setZero(size, size);
  b_.setZero(size);
}

void MarginalizationSystem::AssignSlots() {
  std::unordered_set<const double*> touched;
  const std::unordered_set<const double*> marginalized(
      problem_.marginalized.begin(), problem_.marginalized.end());
  for (const auto& r : problem_.residual_blocks) {
    touched.insert(r.parameter_blocks.begin(), r.parameter_blocks.end());
  }
  // Scalar candidates; one that shares a residual block with another is not
  // independent and stays in the dense system.
  auto candidate = [&](const MarginalizationParameterBlock& p) {
    return !p.constant && p.manifold == nullptr && p.size == 1 &&
           marginalized.count(p.values) > 0;
  };
  std::unordered_set<const double*> candidates, coupled;
  for (const auto& p : problem_.parameter_blocks) {
    if (candidate(p)) candidates.insert(p.values);
  }
  for (const auto& r : problem_.residual_blocks) {
    int n = 0;
    for (const double* v : r.parameter_blocks) n += candidates.count(v);
    if (n < 2) continue;
    for (const double* v : r.parameter_blocks) {
      if (candidates.count(v)) coupled.insert(v);
    }
  }
  int offset = 0;
  for (const auto& p : problem_.parameter_blocks) {
    if (p.constant || !marginalized.count(p.values)) continue;
    if (candidates.count(p.values) && !coupled.count(p.values)) {
      slots_[p.values] = {&p, Role::kScalar, static_cast<int>(scalars_.size())};
      scalars_.emplace_back();
      continue;
    }
    slots_[p.values] = {&p, Role::kDense, offset};
    offset += TangentSizeOf(p);
  }
  dense_marginalized_size_ = offset;
  for (const auto& p : problem_.parameter_blocks) {
    if (p.constant || marginalized.count(p.values) ||
        !touched.count(p.values)) {
      continue;
    }
    slots_[p.values] = {&p, Role::kDense, offset};
    offset += TangentSizeOf(p);
    kept_.push_back(&p);
  }
  kept_size_ = offset - dense_marginalized_size_;
}

void MarginalizationSystem::LayOutScalars() {
  for (const auto& r : problem_.residual_blocks) {
    Scalar* s = nullptr;
    for (const double* v : r.parameter_blocks) {
      const auto it = slots_.find(v);
      if (it != slots_.end() && it->second.role == Role::kScalar) {
        s = &scalars_[it->second.offset];
      }
    }
    if (s == nullptr) continue;
    for (const double* v : r.parameter_blocks) {
      const auto it = slots_.find(v);
      if (it == slots_.end() || it->second.role != Role::kDense) continue;
      const int o = it->second.offset;
      if (std::find(s->touched.begin(), s->touched.end(), o) ==
          s->touched.end()) {
        s->touched.push_back(o);
        s->tangent.push_back(TangentSizeOf(*it->second.block));
      }
    }
  }
  int w_total = 0;
  for (Scalar& s : scalars_) {
    s.w_offset = w_total;
    for (int t : s.tangent) s.w_size += t;
    w_total += s.w_size;
  }
  w_.assign(w_total, 0.0);
}

bool MarginalizationSystem::Evaluate(int k) {
  const MarginalizationResidualBlock& r = problem_.residual_blocks[k];
  const int m = r.cost->num_residuals();
  const size_t n = r.parameter_blocks.size();
  residual_.resize(m);
  ambient_ptrs_.assign(n, nullptr);
  tangent_offsets_.assign(n, -1);
  param_slots_.assign(n, nullptr);
  int tangent_total = 0;
  int ambient_total = 0;
  for (size_t j = 0; j < n; ++j) {
    const auto it = slots_.find(r.parameter_blocks[j]);
    if (it == slots_.end()) continue;  // constant
    param_slots_[j] = &it->second;
    tangent_offsets_[j] = tangent_total;
    tangent_total += m * TangentSizeOf(*it->second.block);
    ambient_total += m * it->second.block->size;
  }
  tangent_.resize(tangent_total);
  const double* const* params = r.parameter_blocks.data();
  if (const auto* t = dynamic_cast<const TangentJacobians*>(r.cost)) {
    for (size_t j = 0; j < n; ++j) {
      if (tangent_offsets_[j] >= 0) {
        ambient_ptrs_[j] = tangent_.data() + tangent_offsets_[j];
      }
    }
    if (!t->EvaluateTangent(params, residual_.data(), ambient_ptrs_.data())) {
      return false;
    }
  } else {
    ambient_.resize(ambient_total);
    int a = 0;
    for (size_t j = 0; j < n; ++j) {
      if (tangent_offsets_[j] < 0) continue;
      ambient_ptrs_[j] = ambient_.data() + a;
      a += m * param_slots_[j]->block->size;
    }
    if (!r.cost->Evaluate(params, residual_.data(), ambient_ptrs_.data())) {
      return false;
    }
    for (size_t j = 0; j < n; ++j) {
      if (tangent_offsets_[j] < 0) continue;
      const MarginalizationParameterBlock& p = *param_slots_[j]->block;
      Eigen::Map<RowMajorMatrix> J(tangent_.data() + tangent_offsets_[j], m,
                                   p.TangentSize());
      const ConstRowMajorMap amb(ambient_ptrs_[j], m, p.size);
      if (p.manifold == nullptr) {
        J = amb;
        continue;
      }
      plus_.resize(p.size * p.TangentSize());
      p.manifold->PlusJacobian(p.values, plus_.data());
      J.noalias() =
          amb * ConstRowMajorMap(plus_.data(), p.size, p.TangentSize());
    }
  }
  if (!residual_.allFinite() ||
      !Eigen::Map<const Eigen::VectorXd>(tangent_.data(), tangent_total)
           .allFinite()) {
    return false;
  }
  // Robust loss, first order (marginalization.h): r~ = sqrt(rho') r,
  // J~ = sqrt(rho') J.
  if (r.loss != nullptr) {
    double rho[3];
    r.loss->Evaluate(residual_.squaredNorm(), rho);
    if (!std::isfinite(rho[1]) || rho[1] < 0.0) return false;
    const double scale = std::sqrt(rho[1]);
    residual_ *= scale;
    Eigen::Map<Eigen::VectorXd>(tangent_.data(), tangent_total) *= scale;
  }
  return true;
}

void MarginalizationSystem::Add(int k) {
  const MarginalizationResidualBlock& r = problem_.residual_blocks[k];
  const int m = static_cast<int>(residual_.size());
  const size_t n = r.parameter_blocks.size();
  Scalar* s = nullptr;
  const double* J_s = nullptr;
  for (size_t j = 0; j < n; ++j) {
    if (param_slots_[j] != nullptr && param_slots_[j]->role == Role::kScalar) {
      s = &scalars_[param_slots_[j]->offset];
      J_s = tangent_.data() + tangent_offsets_[j];
    }
  }
  const Eigen::Map<const Eigen::VectorXd> js(J_s, J_s ? m : 0);
  if (s != nullptr) {
    s->h += js.squaredNorm();
    s->b -= js.dot(residual_);
  }
  for (size_t a = 0; a < n; ++a) {
    if (tangent_offsets_[a] < 0) continue;
    const Slot& sa = *param_slots_[a];
    if (sa.role != Role::kDense) continue;
    const int ta = TangentSizeOf(*sa.block);
    const ConstRowMajorMap Ja(tangent_.data() + tangent_offsets_[a], m, ta);
    b_.segment(sa.offset, ta).noalias() -= Ja.transpose() * residual_;
    if (s != nullptr) {
      int part = s->w_offset;
      for (size_t q = 0; q < s->touched.size() && s->touched[q] != sa.offset;
           ++q) {
        part += s->tangent[q];
      }
      Eigen::Map<Eigen::VectorXd>(w_.data() + part, ta).noalias() +=
          Ja.transpose() * js;
    }
    for (size_t c = a; c < n; ++c) {
      if (tangent_offsets_[c] < 0) continue;
      const Slot& sc = *param_slots_[c];
      if (sc.role != Role::kDense) continue;
      const int tc = TangentSizeOf(*sc.block);
      const double* J_c = tangent_.data() + tangent_offsets_[c];
      // Upper triangle: the block with the smaller offset is the row.
      if (sa.offset <= sc.offset) {
        AddJtJ(Ja.data(), ta, J_c, tc, m, sa.offset, sc.offset, &H_);
      } else {
        AddJtJ(J_c, tc, Ja.data(), ta, m, sc.offset, sa.offset, &H_);
      }
    }
  }
}

bool MarginalizationSystem::AccumulatePrior(int k) {
  // The prior's Gauss-Newton terms from its J^T J (factors/
  // marginalization_prior.h): M^T (J^T J) M and M^T (J^T r0 + J^T J dx),
  // with M = Jr^-1(phi) on each pose's rotation, identity elsewhere.
  const MarginalizationResidualBlock& r = problem_.residual_blocks[k];
  const auto* prior = static_cast<const MarginalizationPrior*>(r.cost);
  Eigen::VectorXd dx;
  if (!prior->Delta(r.parameter_blocks.data(), &dx)) return false;
  Eigen::MatrixXd G = prior->information();
  Eigen::VectorXd g = prior->gradient0() + G * dx;
  for (size_t j = 0; j < prior->blocks().size(); ++j) {
    if (prior->blocks()[j].kind != PriorBlockKind::kPose) continue;
    const int c = prior->TangentOffset(static_cast<int>(j)) + kPoseRotation;
    const Eigen::Matrix3d M = RightJacobianInverse(dx.segment<3>(c));
    G.middleCols<3>(c) = G.middleCols<3>(c) * M;
    G.middleRows<3>(c) = M.transpose() * G.middleRows<3>(c);
    g.segment<3>(c) = M.transpose() * g.segment<3>(c);
  }
  if (!G.allFinite() || !g.allFinite()) return false;
  // Each block's slot looked up once (a prior holding world points has
  // about 80 blocks: 6400 pairs below).
  const size_t n = r.parameter_blocks.size();
  param_slots_.assign(n, nullptr);
  for (size_t a = 0; a < n; ++a) {
    const auto it = slots_.find(r.parameter_blocks[a]);
    if (it != slots_.end()) param_slots_[a] = &it->second;
  }
  for (size_t a = 0; a < n; ++a) {
    if (param_slots_[a] == nullptr) continue;
    const Slot& sa = *param_slots_[a];
    const int ta = TangentSizeOf(*sa.block);
    const int pa = prior->TangentOffset(static_cast<int>(a));
    b_.segment(sa.offset, ta) -= g.segment(pa, ta);
    for (size_t c = 0; c < n; ++c) {
      if (param_slots_[c] == nullptr || param_slots_[c]->offset < sa.offset) {
        continue;
      }
      const Slot& sc = *param_slots_[c];
      H_.block(sa.offset, sc.offset, ta, TangentSizeOf(*sc.block)) +=
          G.block(pa, prior->TangentOffset(static_cast<int>(c)), ta,
                  TangentSizeOf(*sc.block));
    }
  }
  return true;
}

void MarginalizationSystem::Accumulate(int* used, int* skipped) {
  for (size_t k = 0; k < problem_.residual_blocks.size(); ++k) {
    const MarginalizationResidualBlock& r = problem_.residual_blocks[k];
    // A prior on dense blocks only goes through its J^T J.
    bool prior_path =
        r.loss == nullptr && dynamic_cast<const MarginalizationPrior*>(r.cost);
    for (const double* v : r.parameter_blocks) {
      const auto it = slots_.find(v);
      if (it != slots_.end() && it->second.role == Role::kScalar) {
        prior_path = false;
      }
    }
    const int kk = static_cast<int>(k);
    bool ok = false;
    if (prior_path) {
      ok = AccumulatePrior(kk);
    } else if (Evaluate(kk)) {
      Add(kk);
      ok = true;
    }
    ++*(ok ? used : skipped);
  }
}

int MarginalizationSystem::EliminateScalars(double floor) {
  double scale = 0.0;
  for (int i = 0; i < dense_marginalized_size_; ++i) {
    scale = std::max(scale, H_(i, i));
  }
  for (const Scalar& s : scalars_) scale = std::max(scale, s.h);
  const double threshold = floor * scale;
  int dropped = 0;
  for (const Scalar& s : scalars_) {
    if (!(s.h > threshold && s.h > 0.0)) {
      ++dropped;
      continue;
    }
    const double inv_h = 1.0 / s.h;
    int part_p = s.w_offset;
    for (size_t p = 0; p < s.touched.size(); ++p) {
      const int op = s.touched[p], tp = s.tangent[p];
      const Eigen::Map<const Eigen::VectorXd> w_p(w_.data() + part_p, tp);
      b_.segment(op, tp) -= (inv_h * s.b) * w_p;
      int part_q = s.w_offset;
      for (size_t q = 0; q < s.touched.size(); ++q) {
        const int oq = s.touched[q], tq = s.tangent[q];
        if (op <= oq) {
          SubtractOuter(w_.data() + part_p, tp, w_.data() + part_q, tq, inv_h,
                        op, oq, &H_);
        }
        part_q += tq;
      }
      part_p += tp;
    }
  }
  H_.triangularView<Eigen::StrictlyLower>() = H_.transpose();
  return dropped;
}

}  // namespace vio
