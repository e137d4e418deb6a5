#ifndef VIO_CONFIG_RENDER_CONFIG_H_
#define VIO_CONFIG_RENDER_CONFIG_H_

// The render: block of a simulator preset (config/sim_*.yaml) <->
// RenderOptions (render/render_options.h). Every key is required:
//
//   render:
//     texture_folder: ""        # empty: render/textures
//     texels_per_m, tile_size_m, tile_gain_spread, mip_bias, view_scale,
//     exposure_time_s, blur_step_px, max_blur_samples,
//     gain_change_per_frame, min_gain, max_gain, cam1_gain_ratio,
//     vignetting_corner_gain, read_noise_grey, shot_noise_grey,
//     boxes: [[center_x_m, center_y_m, size_x_m, size_y_m, size_z_m], ...]
//
// A missing key, a wrong type or an out-of-range value (Validate()) is a
// ConfigError naming the file and the key.

#include <string>

#include "config/yaml_reader.h"
#include "render/render_options.h"

namespace vio {

// Reads the render: block itself (root.Child("render")).
RenderOptions ReadRenderOptions(const YamlNode& render);

// The render: block of a preset file. Throws ConfigError naming the file
// when it has none.
RenderOptions LoadRenderOptions(const std::string& path);

// The options as the render: block (numbers exact), so that reading the
// text gives them back; tools print it as the effective configuration.
std::string RenderOptionsToYaml(const RenderOptions& options);

}  // namespace vio

#endif  // VIO_CONFIG_RENDER_CONFIG_H_
