#ifndef VIO_CONFIG_FRONTEND_CONFIG_H_
#define VIO_CONFIG_FRONTEND_CONFIG_H_

// YAML -> FrontendOptions. The `frontend:` block of a configuration file:
//
//   frontend:
//     stereo: true
//     tracker:        { max_features, min_distance_px, corner_quality,
//                       border_px, klt_window_px, klt_pyramid_levels,
//                       klt_max_iterations, klt_epsilon_px,
//                       max_forward_backward_px, fundamental_check,
//                       fundamental_threshold_px, fundamental_confidence,
//                       virtual_focal_px, clahe, clahe_clip_limit,
//                       clahe_tiles }
//     stereo_matcher: { klt_window_px, klt_pyramid_levels, klt_max_iterations,
//                       klt_epsilon_px, equalize, max_reverse_px,
//                       reverse_pyramid_levels,
//                       max_epipolar_px, start_from_previous }
//
// Every key is required (a missing one is an error, never a silent default);
// units are those of frontend/frontend_options.h. The cameras' calibration is
// not here: it comes from the sequence's sensor.yaml files.

#include <string>

#include "config/yaml_reader.h"
#include "frontend/frontend_options.h"

namespace vio {

// Reads the mapping `frontend` (the block's own node) and validates it.
// Throws ConfigError naming the file and key on a missing key, a wrong type
// or an out-of-range value.
FrontendOptions ReadFrontendOptions(const YamlNode& frontend);

// Loads `path` and reads its top-level `frontend:` block.
FrontendOptions LoadFrontendOptions(const std::string& path);

}  // namespace vio

#endif  // VIO_CONFIG_FRONTEND_CONFIG_H_
