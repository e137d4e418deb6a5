// The structure of a step's problem (SetUp: blocks, residuals, priors, each
// landmark's parts of W) and the state it acts on. Evaluating the residuals is
// in window_linearization_residuals.cc, the normal equations and the damped
// solve in window_linearization_schur.cc.

#include "estimator/window_linearization.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace vio {
namespace {

// Throws the set-up error of `what` number `index` (built only on failure).
void Require(bool ok, const char* what, size_t index, const char* message) {
  if (!ok) {
    throw std::invalid_argument(std::string("SolveWindow: ") + what + " " +
                                std::to_string(index) + " " + message);
  }
}

}  // namespace

void WindowLinearization::SetUp(const WindowSolverProblem& problem) {
  blocks_in_ = &problem.blocks;
  residuals_in_ = &problem.residuals;
  block_indices_ = &problem.block_indices;
  num_reduced_ = 0;
  num_tangent_ = 0;
  max_ambient_jacobian_ = 0;
  factor_kept_ = false;
  solve_counts_ = SolveCounts();
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

void WindowLinearization::Accept() {
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const Block& b = blocks_[i];
    if (b.role == Role::kConstant) continue;
    std::copy_n(candidate_.data() + b.state_offset, (*blocks_in_)[i].size,
                (*blocks_in_)[i].values);
  }
}

}  // namespace vio
