#ifndef VIO_CONFIG_ESTIMATOR_CONFIG_H_
#define VIO_CONFIG_ESTIMATOR_CONFIG_H_

// The `estimator:` block of a configuration file, mapped onto EstimatorOptions
// (estimator/estimator_options.h, where every field's unit and meaning is
// documented). Every key is required; config/default.yaml lists them all with
// their units. gravity_magnitude is not read here: the tools take it from
// imu.gravity_magnitude. solver.backend is window or ceres; the other solver
// enums use Ceres' names, case-insensitive (linear_solver: dense_schur,
// sparse_schur, dense_qr, ...; trust_region: dogleg or levenberg_marquardt).
//
// Errors are ConfigError naming the file and the key:
//   "config/default.yaml: estimator.window_size must be >= 2 (got 1)".

#include <string>

#include "config/yaml_reader.h"
#include "estimator/estimator_options.h"

namespace vio {

// Reads and validates root's `estimator` mapping.
EstimatorOptions ReadEstimatorOptions(const YamlNode& root);

// Multi-line "key: value" listing of the effective options, for tools to
// print at startup.
std::string DescribeEstimatorOptions(const EstimatorOptions& options);

}  // namespace vio

#endif  // VIO_CONFIG_ESTIMATOR_CONFIG_H_
