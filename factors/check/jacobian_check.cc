#include "factors/check/jacobian_check.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "factors/tangent_jacobians.h"

namespace vio {
namespace {

using RowMajorMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

int TangentSize(const FactorInstance& f, size_t b) {
  return f.manifolds[b] ? f.manifolds[b]->TangentSize()
                        : static_cast<int>(f.blocks[b].size());
}

// Evaluates the residual with block b replaced by value.
bool ResidualWith(const FactorInstance& f, size_t b,
                  const std::vector<double>& value, Eigen::VectorXd* r) {
  std::vector<const double*> params;
  for (size_t i = 0; i < f.blocks.size(); ++i) {
    params.push_back(i == b ? value.data() : f.blocks[i].data());
  }
  r->resize(f.cost->num_residuals());
  if (!f.cost->Evaluate(params.data(), r->data(), nullptr)) return false;
  return r->allFinite();
}

// x (+) delta through the block's manifold (or plain addition).
std::vector<double> PlusAlong(const FactorInstance& f, size_t b,
                              const Eigen::VectorXd& delta) {
  const std::vector<double>& x = f.blocks[b];
  std::vector<double> out(x.size());
  if (f.manifolds[b]) {
    f.manifolds[b]->Plus(x.data(), delta.data(), out.data());
  } else {
    for (size_t i = 0; i < x.size(); ++i) out[i] = x[i] + delta[i];
  }
  return out;
}

bool AnalyticTangentJacobians(const FactorInstance& f,
                              std::vector<Eigen::MatrixXd>* tangent) {
  const int m = f.cost->num_residuals();
  std::vector<RowMajorMatrix> ambient(f.blocks.size());
  std::vector<double*> jac_ptrs;
  std::vector<const double*> params;
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    ambient[b].resize(m, f.blocks[b].size());
    jac_ptrs.push_back(ambient[b].data());
    params.push_back(f.blocks[b].data());
  }
  Eigen::VectorXd r(m);
  if (!f.cost->Evaluate(params.data(), r.data(), jac_ptrs.data())) {
    return false;
  }
  tangent->clear();
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    if (f.manifolds[b]) {
      const int n = f.manifolds[b]->TangentSize();
      RowMajorMatrix plus(f.blocks[b].size(), n);
      f.manifolds[b]->PlusJacobian(f.blocks[b].data(), plus.data());
      tangent->push_back(ambient[b] * plus);
    } else {
      tangent->push_back(ambient[b]);
    }
  }
  return true;
}

// A factor that also gives its Jacobians in the tangent space
// (factors/tangent_jacobians.h): those, as written by EvaluateTangent.
// Returns false when it is not such a factor or its evaluation fails.
bool DirectTangentJacobians(const FactorInstance& f,
                            std::vector<Eigen::MatrixXd>* tangent) {
  const auto* direct = dynamic_cast<const TangentJacobians*>(f.cost.get());
  if (direct == nullptr) return false;
  const int m = f.cost->num_residuals();
  std::vector<RowMajorMatrix> jacobians(f.blocks.size());
  std::vector<double*> jac_ptrs;
  std::vector<const double*> params;
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    jacobians[b].resize(m, TangentSize(f, b));
    jac_ptrs.push_back(jacobians[b].data());
    params.push_back(f.blocks[b].data());
  }
  Eigen::VectorXd r(m);
  if (!direct->EvaluateTangent(params.data(), r.data(), jac_ptrs.data())) {
    return false;
  }
  tangent->assign(jacobians.begin(), jacobians.end());
  return true;
}

BlockJacobianError Error(const std::string& name, const Eigen::MatrixXd& a,
                         const Eigen::MatrixXd& numeric,
                         const JacobianCheckOptions& options) {
  BlockJacobianError e;
  e.block = name;
  if (!a.allFinite()) {
    // A non-finite analytic Jacobian fails whatever the numeric one says.
    e.max_abs_error = e.max_rel_error = std::numeric_limits<double>::infinity();
  } else {
    e.max_abs_error = (a - numeric).cwiseAbs().maxCoeff();
    const double scale =
        std::max(numeric.cwiseAbs().maxCoeff(), options.min_scale);
    e.max_rel_error = e.max_abs_error / scale;
  }
  return e;
}

}  // namespace

bool CompareJacobians(const FactorInstance& f,
                      const JacobianCheckOptions& options,
                      std::vector<BlockJacobianError>* errors) {
  errors->clear();
  std::vector<Eigen::MatrixXd> analytic;
  if (!AnalyticTangentJacobians(f, &analytic)) return false;
  // Factors with EvaluateTangent get a second row per block: their direct
  // tangent Jacobians against the same numeric ones.
  std::vector<Eigen::MatrixXd> direct;
  const bool has_direct = DirectTangentJacobians(f, &direct);
  if (dynamic_cast<const TangentJacobians*>(f.cost.get()) && !has_direct) {
    return false;
  }

  std::vector<BlockJacobianError> out;
  const int m = f.cost->num_residuals();
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    const int n = TangentSize(f, b);
    Eigen::MatrixXd numeric(m, n);
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
      delta[k] = options.step;
      Eigen::VectorXd r_plus, r_minus;
      if (!ResidualWith(f, b, PlusAlong(f, b, delta), &r_plus) ||
          !ResidualWith(f, b, PlusAlong(f, b, -delta), &r_minus)) {
        return false;
      }
      numeric.col(k) = (r_plus - r_minus) / (2.0 * options.step);
    }
    const std::string name = b < f.block_names.size()
                                 ? f.block_names[b]
                                 : "block " + std::to_string(b);
    out.push_back(Error(name, analytic[b], numeric, options));
    if (has_direct) {
      out.push_back(Error(name + " (tangent)", direct[b], numeric, options));
    }
  }
  *errors = std::move(out);
  return true;
}

}  // namespace vio
