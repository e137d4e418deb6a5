#include "config/visual_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "test/testing/expect_error.h"

namespace vio {
namespace {

VisualFactorOptions Read(const std::string& text) {
  return ReadVisualOptions(YamlNode::LoadString(text, "mem.yaml"));
}

TEST(VisualConfig, DefaultFileHoldsTheUsersDefaults) {
  const VisualFactorOptions options =
      LoadVisualOptions(std::string(VIO_SOURCE_DIR) + "/config/default.yaml");
  const VisualFactorOptions defaults;
  EXPECT_DOUBLE_EQ(options.sigma_px, defaults.sigma_px);
  EXPECT_EQ(options.robust_kernel.type, RobustKernelType::kHuber);
  EXPECT_DOUBLE_EQ(options.robust_kernel.scale, kDefaultHuberScale);
}

TEST(VisualConfig, ReadsCauchyAndNone) {
  const VisualFactorOptions cauchy = Read(
      "visual: {sigma_px: 2.0, robust_kernel: {type: cauchy, scale: 2.3849}}");
  EXPECT_DOUBLE_EQ(cauchy.sigma_px, 2.0);
  EXPECT_EQ(cauchy.robust_kernel.type, RobustKernelType::kCauchy);
  EXPECT_DOUBLE_EQ(cauchy.robust_kernel.scale, 2.3849);
  // type none needs no scale.
  const VisualFactorOptions none =
      Read("visual: {sigma_px: 1.0, robust_kernel: {type: none}}");
  EXPECT_EQ(none.robust_kernel.type, RobustKernelType::kNone);
}

TEST(VisualConfig, MissingKeysAreErrorsNamingThem) {
  ExpectErrorContaining<ConfigError>([] { Read("imu: {rate_hz: 200}"); },
                                     "mem.yaml: visual is missing");
  ExpectErrorContaining<ConfigError>(
      [] { Read("visual: {robust_kernel: {type: none}}"); },
      "mem.yaml: visual.sigma_px is missing");
  ExpectErrorContaining<ConfigError>(
      [] { Read("visual: {sigma_px: 1.5, robust_kernel: {type: huber}}"); },
      "mem.yaml: visual.robust_kernel.scale is missing");
}

TEST(VisualConfig, BadValuesAreErrorsNamingKeyAndValue) {
  ExpectErrorContaining<ConfigError>(
      [] { Read("visual: {sigma_px: 1.5, robust_kernel: {type: tukey}}"); },
      "mem.yaml: visual.robust_kernel.type must be one of none, huber, "
      "cauchy (got 'tukey')");
  ExpectErrorContaining<ConfigError>(
      [] { Read("visual: {sigma_px: -1, robust_kernel: {type: none}}"); },
      "mem.yaml: visual.sigma_px must be a finite number > 0 (got -1)");
  ExpectErrorContaining<ConfigError>(
      [] {
        Read("visual: {sigma_px: 1.5, robust_kernel: {type: huber, scale: 0}}");
      },
      "mem.yaml: visual.robust_kernel.scale must be a finite number > 0 "
      "(got 0)");
  ExpectErrorContaining<ConfigError>(
      [] { Read("visual: {sigma_px: wide, robust_kernel: {type: none}}"); },
      "mem.yaml: visual.sigma_px must be a number (got 'wide')");
}

}  // namespace
}  // namespace vio
