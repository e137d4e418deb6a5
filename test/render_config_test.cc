// The render: block of the simulator presets (config/render_config.h).

#include "config/render_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test/testing/expect_error.h"

namespace vio {
namespace {

std::string Preset(const std::string& name) {
  return std::string(VIO_SOURCE_DIR) + "/config/" + name;
}

std::string Text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// sim_default.yaml's text with `from` replaced by `to`, read as a preset.
RenderOptions DefaultWith(const std::string& from, const std::string& to) {
  std::string s = Text(Preset("sim_default.yaml"));
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return ReadRenderOptions(YamlNode::LoadString(s, "mem.yaml").Child("render"));
}

void ExpectSame(const RenderOptions& a, const RenderOptions& b) {
  EXPECT_EQ(a.texture_folder, b.texture_folder);
  EXPECT_EQ(a.texels_per_m, b.texels_per_m);
  EXPECT_EQ(a.tile_size_m, b.tile_size_m);
  EXPECT_EQ(a.tile_gain_spread, b.tile_gain_spread);
  EXPECT_EQ(a.mip_bias, b.mip_bias);
  EXPECT_EQ(a.view_scale, b.view_scale);
  EXPECT_EQ(a.exposure_time_s, b.exposure_time_s);
  EXPECT_EQ(a.blur_step_px, b.blur_step_px);
  EXPECT_EQ(a.max_blur_samples, b.max_blur_samples);
  EXPECT_EQ(a.gain_change_per_frame, b.gain_change_per_frame);
  EXPECT_EQ(a.min_gain, b.min_gain);
  EXPECT_EQ(a.max_gain, b.max_gain);
  EXPECT_EQ(a.cam1_gain_ratio, b.cam1_gain_ratio);
  EXPECT_EQ(a.vignetting_corner_gain, b.vignetting_corner_gain);
  EXPECT_EQ(a.read_noise_grey, b.read_noise_grey);
  EXPECT_EQ(a.shot_noise_grey, b.shot_noise_grey);
  ASSERT_EQ(a.boxes.size(), b.boxes.size());
  for (size_t i = 0; i < a.boxes.size(); ++i) {
    EXPECT_EQ(a.boxes[i].center_xy_m, b.boxes[i].center_xy_m);
    EXPECT_EQ(a.boxes[i].size_m, b.boxes[i].size_m);
  }
}

TEST(RenderConfig, EveryPresetsBlockEqualsTheBuiltInDefaults) {
  for (const char* name : {"sim_default.yaml", "sim_stereo.yaml",
                           "sim_aggressive.yaml", "sim_outliers.yaml"}) {
    SCOPED_TRACE(name);
    ExpectSame(LoadRenderOptions(Preset(name)), RenderOptions());
  }
}

TEST(RenderConfig, TheEffectiveConfigurationReadsBackTheSame) {
  RenderOptions o;
  o.texture_folder = "/some/crops";
  o.exposure_time_s = 0.0025;
  o.boxes.pop_back();
  const YamlNode root =
      YamlNode::LoadString(RenderOptionsToYaml(o), "printed.yaml");
  ExpectSame(ReadRenderOptions(root.Child("render")), o);
  o.boxes.clear();
  ExpectSame(ReadRenderOptions(
                 YamlNode::LoadString(RenderOptionsToYaml(o), "printed.yaml")
                     .Child("render")),
             o);
}

TEST(RenderConfig, ReadsEveryKey) {
  EXPECT_EQ(DefaultWith("exposure_time_s: 0.004", "exposure_time_s: 0.01")
                .exposure_time_s,
            0.01);
  EXPECT_EQ(DefaultWith("view_scale: 1 ", "view_scale: 0.75 ").view_scale,
            0.75);
  const RenderOptions o =
      DefaultWith("    - [0, 0, 1.2, 1, 0.9]\n", "    - [0.5, -1, 1, 2, 3]\n");
  EXPECT_EQ(o.boxes[0].center_xy_m, Eigen::Vector2d(0.5, -1.0));
  EXPECT_EQ(o.boxes[0].size_m, Eigen::Vector3d(1.0, 2.0, 3.0));
}

TEST(RenderConfig, BadValuesNameTheFileAndKey) {
  ExpectErrorContaining<ConfigError>(
      [] { DefaultWith("  read_noise_grey: 1.5", "  noise_grey: 1.5"); },
      "mem.yaml: render.read_noise_grey");
  ExpectErrorContaining<ConfigError>(
      [] { DefaultWith("min_gain: 0.7", "min_gain: 1.2"); },
      "mem.yaml: render.min_gain and max_gain must be > 0");
  ExpectErrorContaining<ConfigError>(
      [] { DefaultWith("max_blur_samples: 16", "max_blur_samples: 0"); },
      "render.max_blur_samples must be in [1, 256]");
  ExpectErrorContaining<ConfigError>(
      [] { DefaultWith("[5, 2.5, 1, 1.4, 1.2]", "[5, 2.5, 1, 1.4]"); },
      "render.boxes[1] must be a row of 5 numbers");
  ExpectErrorContaining<ConfigError>(
      [] { DefaultWith("[5, 2.5, 1, 1.4, 1.2]", "[0.2, 0, 1, 1, 1]"); },
      "render.boxes[1] overlaps boxes[0]");
  ExpectErrorContaining<ConfigError>(
      [] { LoadRenderOptions(Preset("default.yaml")); },
      "default.yaml: render is missing");
}

}  // namespace
}  // namespace vio
