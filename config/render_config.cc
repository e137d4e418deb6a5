#include "config/render_config.h"

#include <charconv>
#include <sstream>
#include <vector>

namespace vio {
namespace {

std::string Num(double v) {
  char buffer[32];
  const std::to_chars_result r =
      std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, r.ptr);
}

std::vector<SceneBox> ReadBoxes(const YamlNode& node) {
  std::vector<SceneBox> boxes;
  for (const std::vector<double>& row : node.GetRows("boxes", 5)) {
    SceneBox b;
    b.center_xy_m = {row[0], row[1]};
    b.size_m = {row[2], row[3], row[4]};
    boxes.push_back(b);
  }
  return boxes;
}

}  // namespace

RenderOptions ReadRenderOptions(const YamlNode& r) {
  RenderOptions o;
  o.texture_folder = r.Get<std::string>("texture_folder");
  o.texels_per_m = r.Get<double>("texels_per_m");
  o.tile_size_m = r.Get<double>("tile_size_m");
  o.tile_gain_spread = r.Get<double>("tile_gain_spread");
  o.mip_bias = r.Get<double>("mip_bias");
  o.view_scale = r.Get<double>("view_scale");
  o.exposure_time_s = r.Get<double>("exposure_time_s");
  o.blur_step_px = r.Get<double>("blur_step_px");
  o.max_blur_samples = r.Get<int>("max_blur_samples");
  o.gain_change_per_frame = r.Get<double>("gain_change_per_frame");
  o.min_gain = r.Get<double>("min_gain");
  o.max_gain = r.Get<double>("max_gain");
  o.cam1_gain_ratio = r.Get<double>("cam1_gain_ratio");
  o.vignetting_corner_gain = r.Get<double>("vignetting_corner_gain");
  o.read_noise_grey = r.Get<double>("read_noise_grey");
  o.shot_noise_grey = r.Get<double>("shot_noise_grey");
  o.boxes = ReadBoxes(r);
  ValidateAt(r, o);
  return o;
}

RenderOptions LoadRenderOptions(const std::string& path) {
  const YamlNode root = YamlNode::LoadFile(path);
  if (!root.Has("render")) {
    throw ConfigError(root.Where("render") +
                      " is missing (needed to render images)");
  }
  return ReadRenderOptions(root.Child("render"));
}

std::string RenderOptionsToYaml(const RenderOptions& o) {
  std::ostringstream y;
  y << "render:  # images (vio_sim --render); units in the key names\n"
    << "  texture_folder: \"" << o.texture_folder
    << "\"  # empty: render/textures\n"
    << "  texels_per_m: " << Num(o.texels_per_m) << "\n"
    << "  tile_size_m: " << Num(o.tile_size_m) << "\n"
    << "  tile_gain_spread: " << Num(o.tile_gain_spread) << "\n"
    << "  mip_bias: " << Num(o.mip_bias) << "\n"
    << "  view_scale: " << Num(o.view_scale) << "\n"
    << "  exposure_time_s: " << Num(o.exposure_time_s) << "\n"
    << "  blur_step_px: " << Num(o.blur_step_px) << "\n"
    << "  max_blur_samples: " << o.max_blur_samples << "\n"
    << "  gain_change_per_frame: " << Num(o.gain_change_per_frame) << "\n"
    << "  min_gain: " << Num(o.min_gain) << "\n"
    << "  max_gain: " << Num(o.max_gain) << "\n"
    << "  cam1_gain_ratio: " << Num(o.cam1_gain_ratio) << "\n"
    << "  vignetting_corner_gain: " << Num(o.vignetting_corner_gain) << "\n"
    << "  read_noise_grey: " << Num(o.read_noise_grey) << "\n"
    << "  shot_noise_grey: " << Num(o.shot_noise_grey) << "\n";
  if (o.boxes.empty()) {
    y << "  boxes: []\n";
    return y.str();
  }
  y << "  boxes:  # [center_x_m, center_y_m, size_x_m, size_y_m, size_z_m]\n";
  for (const SceneBox& b : o.boxes) {
    y << "    - [" << Num(b.center_xy_m.x()) << ", " << Num(b.center_xy_m.y())
      << ", " << Num(b.size_m.x()) << ", " << Num(b.size_m.y()) << ", "
      << Num(b.size_m.z()) << "]\n";
  }
  return y.str();
}

}  // namespace vio
