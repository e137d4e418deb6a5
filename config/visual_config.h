#ifndef VIO_CONFIG_VISUAL_CONFIG_H_
#define VIO_CONFIG_VISUAL_CONFIG_H_

// The `visual:` block of a configuration file, mapped onto
// VisualFactorOptions (factors/visual_factor_options.h):
//
//   visual:
//     sigma_px: 1.5          # feature position noise [px], > 0
//     robust_kernel:
//       type: huber          # none | huber | cauchy
//       scale: 1.345         # [sigma], > 0; required unless type is none
//
// Every key is required (a missing one is an error, never a default); the
// scale of type none is not read. Errors are ConfigError naming the file and
// the key: "config/default.yaml: visual.robust_kernel.type must be one of
// none, huber, cauchy (got 'tukey')".

#include <string>

#include "config/yaml_reader.h"
#include "factors/visual_factor_options.h"

namespace vio {

// Reads and validates the `visual` mapping under `root`.
VisualFactorOptions ReadVisualOptions(const YamlNode& root);

// The same from a file.
VisualFactorOptions LoadVisualOptions(const std::string& path);

}  // namespace vio

#endif  // VIO_CONFIG_VISUAL_CONFIG_H_
