#include "config/frontend_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace vio {
namespace {

using ::testing::HasSubstr;

std::string ConfigFile(const std::string& name) {
  return std::string(VIO_SOURCE_DIR) + "/config/" + name;
}

template <typename F>
void ExpectConfigError(F f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no ConfigError; expected one containing: " << text;
  } catch (const ConfigError& e) {
    EXPECT_THAT(e.what(), HasSubstr(text));
  }
}

// The default.yaml frontend block as text, with `from` replaced by `to`.
std::string DefaultWith(const std::string& from, const std::string& to) {
  std::ifstream in(ConfigFile("default.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

FrontendOptions ReadText(const std::string& text) {
  return ReadFrontendOptions(
      YamlNode::LoadString(text, "mem.yaml").Child("frontend"));
}

TEST(FrontendConfig, ShippedFilesLoadAndSayMonoOrStereo) {
  const FrontendOptions defaults =
      LoadFrontendOptions(ConfigFile("default.yaml"));
  EXPECT_TRUE(defaults.stereo);
  EXPECT_EQ(defaults.tracker.max_features, 150);
  EXPECT_DOUBLE_EQ(defaults.tracker.min_distance_px, 30.0);
  EXPECT_EQ(defaults.stereo_matcher.klt.window_px, 15);
  EXPECT_EQ(defaults.tracker.klt.window_px, 21);
  EXPECT_FALSE(LoadFrontendOptions(ConfigFile("euroc_mono.yaml")).stereo);
  EXPECT_TRUE(LoadFrontendOptions(ConfigFile("euroc_stereo.yaml")).stereo);
}

TEST(FrontendConfig, ReadsEveryKey) {
  const FrontendOptions o =
      ReadText(DefaultWith("max_features: 150", "max_features: 99"));
  EXPECT_EQ(o.tracker.max_features, 99);
  EXPECT_EQ(ReadText(DefaultWith("clahe_tiles: 8", "clahe_tiles: 4"))
                .tracker.clahe_tiles,
            4);
  EXPECT_DOUBLE_EQ(
      ReadText(DefaultWith("max_epipolar_px: 1.0", "max_epipolar_px: 2.5"))
          .stereo_matcher.max_epipolar_px,
      2.5);
  EXPECT_FALSE(ReadText(DefaultWith("anchor_refinement: true",
                                    "anchor_refinement: false"))
                   .tracker.anchor_refinement);
  EXPECT_EQ(ReadText(DefaultWith("reverse_pyramid_levels: 0",
                                 "reverse_pyramid_levels: 2"))
                .stereo_matcher.reverse_pyramid_levels,
            2);
  EXPECT_FALSE(ReadText(DefaultWith("start_from_previous: true",
                                    "start_from_previous: false"))
                   .stereo_matcher.start_from_previous);
  EXPECT_DOUBLE_EQ(ReadText(DefaultWith("anchor_max_correction_px: 2.0",
                                        "anchor_max_correction_px: 3.5"))
                       .tracker.anchor_max_correction_px,
                   3.5);
  EXPECT_DOUBLE_EQ(ReadText(DefaultWith("anchor_min_correlation: 0.8",
                                        "anchor_min_correlation: 0.9"))
                       .tracker.anchor_min_correlation,
                   0.9);
  EXPECT_EQ(ReadText(DefaultWith("fundamental_baseline_frames: 5",
                                 "fundamental_baseline_frames: 0"))
                .tracker.fundamental_baseline_frames,
            0);
  EXPECT_EQ(
      ReadText(DefaultWith("refill_min_missing: 5", "refill_min_missing: 12"))
          .tracker.refill_min_missing,
      12);
}

TEST(FrontendConfig, ShippedFilesEqualTheBuiltInTracker) {
  for (const char* name :
       {"default.yaml", "euroc_mono.yaml", "euroc_stereo.yaml"}) {
    const FeatureTrackerOptions o =
        LoadFrontendOptions(ConfigFile(name)).tracker;
    const FeatureTrackerOptions d;
    EXPECT_EQ(o.anchor_refinement, d.anchor_refinement) << name;
    EXPECT_EQ(o.anchor_max_correction_px, d.anchor_max_correction_px) << name;
    EXPECT_EQ(o.anchor_min_correlation, d.anchor_min_correlation) << name;
    EXPECT_EQ(o.fundamental_baseline_frames, d.fundamental_baseline_frames)
        << name;
    EXPECT_EQ(o.refill_min_missing, d.refill_min_missing) << name;
    const StereoMatcherOptions m =
        LoadFrontendOptions(ConfigFile(name)).stereo_matcher;
    const StereoMatcherOptions dm;
    EXPECT_EQ(m.start_from_previous, dm.start_from_previous) << name;
    EXPECT_EQ(m.reverse_pyramid_levels, dm.reverse_pyramid_levels) << name;
    EXPECT_EQ(m.klt.max_iterations, dm.klt.max_iterations) << name;
    EXPECT_EQ(m.klt.window_px, dm.klt.window_px) << name;
  }
}

TEST(FrontendConfig, MissingKeyNamesFileAndKey) {
  ExpectConfigError(
      [] { ReadText(DefaultWith("    corner_quality: 0.002", "")); },
      "mem.yaml: frontend.tracker.corner_quality is missing");
  ExpectConfigError(
      [] { ReadText(DefaultWith("    max_reverse_px: 0.5", "")); },
      "mem.yaml: frontend.stereo_matcher.max_reverse_px is missing");
  ExpectConfigError([] { ReadText("other: 1\n"); },
                    "mem.yaml: frontend is missing");
}

TEST(FrontendConfig, WrongTypeAndOutOfRangeNameTheKey) {
  ExpectConfigError(
      [] { ReadText(DefaultWith("stereo: true", "stereo: maybe")); },
      "mem.yaml: frontend.stereo must be true or false (got 'maybe')");
  ExpectConfigError(
      [] { ReadText(DefaultWith("klt_window_px: 21", "klt_window_px: 20")); },
      "mem.yaml: frontend.tracker.klt_window_px must be odd and >= 3 (got "
      "20)");
  ExpectConfigError(
      [] {
        ReadText(DefaultWith("max_epipolar_px: 1.0", "max_epipolar_px: 0"));
      },
      "mem.yaml: frontend.stereo_matcher.max_epipolar_px must be > 0 (got 0)");
}

TEST(FrontendConfig, MissingFileIsAConfigError) {
  ExpectConfigError([] { LoadFrontendOptions("/nonexistent/f.yaml"); },
                    "/nonexistent/f.yaml: cannot open the file");
}

}  // namespace
}  // namespace vio
