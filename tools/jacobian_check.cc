// jacobian_check: proves every factor's analytic Jacobians against central
// differences taken through the manifolds' Plus, at many random realistic
// linearisation points. Exit status 0 only when every row passes.

#include "factors/check/jacobian_check.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <iomanip>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "factors/check/factor_cases.h"
#include "tools/command_line.h"
#include "tools/curve_fitting/curve_check_case.h"

namespace {

struct Args {
  unsigned seed = 42;
  int trials = 200;
  std::string factor;  // empty: all
  double step = 1e-6;
  bool list = false;
};

constexpr char kUsage[] =
    "usage: jacobian_check [--seed N] [--trials N] [--factor NAME] [--step H]\n"
    "                      [--list] [--help]\n"
    "\n"
    "Compares each factor's analytic Jacobians, mapped to the tangent space\n"
    "(J_ambient * PlusJacobian), with central differences obtained by\n"
    "perturbing every parameter block through its manifold's Plus. One row "
    "per\n"
    "factor and parameter block: the worst absolute and relative error over "
    "all\n"
    "trials (relative to the block's largest entry) and PASS or FAIL against\n"
    "the factor's tolerance. Exit status 0 only when every row passes.\n"
    "\n"
    "  --seed N     seed of the random linearisation points (default 42)\n"
    "  --trials N   random points per factor (default 200)\n"
    "  --factor N   check only the factor named N (see --list)\n"
    "  --step H     central-difference step in the tangent space (default "
    "1e-6)\n"
    "  --list       list the factors and exit\n"
    "  --help       this text\n";

Args ParseArgs(int argc, char** argv) {
  Args args;
  vio::CommandLine line(argc, argv);
  while (line.Next()) {
    const std::string a = line.Current();
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (a == "--seed") {
      args.seed = line.Number<unsigned>();
    } else if (a == "--trials") {
      args.trials = line.Number<int>();
      if (args.trials < 1) throw std::invalid_argument("--trials must be >= 1");
    } else if (a == "--factor") {
      args.factor = line.Value();
    } else if (a == "--step") {
      args.step = line.Number<double>();
      if (!(args.step > 0.0)) throw std::invalid_argument("--step must be > 0");
    } else if (a == "--list") {
      args.list = true;
    } else {
      throw std::invalid_argument("unknown argument '" + a + "' (see --help)");
    }
  }
  return args;
}

struct Row {
  std::string factor, block;
  double max_abs = 0.0, max_rel = 0.0, tolerance = 0.0;
  int failed_evaluations = 0;
  bool Pass() const { return failed_evaluations == 0 && max_rel <= tolerance; }
};

// Runs all trials of one case and returns one row per parameter block.
std::vector<Row> CheckCase(const vio::FactorCase& c, const Args& args) {
  std::mt19937 rng(args.seed);
  vio::JacobianCheckOptions options;
  options.step = args.step;
  std::vector<Row> rows;
  int failed = 0;
  for (int t = 0; t < args.trials; ++t) {
    const vio::FactorInstance instance = c.sample(rng);
    std::vector<vio::BlockJacobianError> errors;
    if (!vio::CompareJacobians(instance, options, &errors)) {
      ++failed;
      continue;
    }
    if (rows.empty()) {
      for (const auto& e : errors) {
        rows.push_back({c.name, e.block, 0.0, 0.0, c.tolerance, 0});
      }
    }
    for (size_t b = 0; b < errors.size(); ++b) {
      rows[b].max_abs = std::max(rows[b].max_abs, errors[b].max_abs_error);
      rows[b].max_rel = std::max(rows[b].max_rel, errors[b].max_rel_error);
    }
  }
  if (rows.empty()) rows.push_back({c.name, "(all)", 0, 0, c.tolerance, 0});
  for (Row& r : rows) r.failed_evaluations = failed;
  return rows;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Args args = ParseArgs(argc, argv);
    // The project's factors, then the curve fitting exercise's cost function
    // (a tool's, so it cannot sit in factors/check/).
    std::vector<vio::FactorCase> cases = vio::AllFactorCases();
    cases.push_back(vio::MakeCurveSampleCase());
    if (args.list) {
      for (const auto& c : cases) {
        std::cout << std::left << std::setw(24) << c.name << c.description
                  << "\n";
      }
      return 0;
    }
    std::vector<Row> rows;
    for (const auto& c : cases) {
      if (!args.factor.empty() && c.name != args.factor) continue;
      for (Row& r : CheckCase(c, args)) rows.push_back(r);
    }
    if (rows.empty()) {
      throw std::invalid_argument("no factor named '" + args.factor +
                                  "' (see --list)");
    }
    std::cout << "jacobian_check: seed " << args.seed << ", " << args.trials
              << " random states per factor, step " << args.step << "\n\n";
    std::cout << std::left << std::setw(22) << "factor" << std::setw(16)
              << "block" << std::right << std::setw(14) << "max abs err"
              << std::setw(14) << "max rel err" << std::setw(11) << "tolerance"
              << "  result\n";
    bool all_pass = true;
    for (const Row& r : rows) {
      all_pass = all_pass && r.Pass();
      std::cout << std::left << std::setw(22) << r.factor << std::setw(16)
                << r.block << std::right << std::scientific
                << std::setprecision(2) << std::setw(14) << r.max_abs
                << std::setw(14) << r.max_rel << std::setw(11) << r.tolerance
                << "  " << (r.Pass() ? "PASS" : "FAIL");
      if (r.failed_evaluations > 0) {
        std::cout << " (" << r.failed_evaluations << " evaluations failed)";
      }
      std::cout << "\n" << std::defaultfloat;
    }
    std::cout << "\n"
              << (all_pass ? "all Jacobians match" : "MISMATCH") << "\n";
    return all_pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
