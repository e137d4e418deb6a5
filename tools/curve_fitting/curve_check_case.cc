#include "tools/curve_fitting/curve_check_case.h"

#include <memory>

#include "tools/curve_fitting/curve_ceres.h"
#include "tools/curve_fitting/curve_problem.h"

namespace vio {

FactorCase MakeCurveSampleCase() {
  FactorCase c;
  c.name = "curve_sample";
  c.description =
      "curve fitting exercise, r = exp(a x^2 + b x + c) - y "
      "(tools/curve_fitting)";
  c.sample = [](std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_real_distribution<double> offset(-3.0, 3.0);
    const Eigen::Vector3d truth(1.0, 2.0, 1.0);
    const Eigen::Vector3d p =
        truth + Eigen::Vector3d(offset(rng), offset(rng), offset(rng));
    const double x = unit(rng);
    const double y = CurveModel(truth, x) + offset(rng);
    FactorInstance f;
    f.cost = std::make_unique<CurveSampleCost>(x, y);
    f.blocks = {{p.x(), p.y(), p.z()}};
    f.manifolds = {nullptr};
    f.block_names = {"abc"};
    return f;
  };
  return c;
}

}  // namespace vio
