#include "config/visual_config.h"

namespace vio {
namespace {

RobustKernelOptions ReadRobustKernel(const YamlNode& node) {
  RobustKernelOptions options;
  const std::string type = node.Get<std::string>("type");
  if (!ParseRobustKernelType(type, &options.type)) {
    throw ConfigError(node.Where("type") +
                      " must be one of none, huber, cauchy (got '" + type +
                      "')");
  }
  options.scale =
      options.type == RobustKernelType::kNone ? 0.0 : node.Get<double>("scale");
  return options;
}

}  // namespace

VisualFactorOptions ReadVisualOptions(const YamlNode& root) {
  const YamlNode visual = root.Child("visual");
  VisualFactorOptions options;
  options.sigma_px = visual.Get<double>("sigma_px");
  options.robust_kernel = ReadRobustKernel(visual.Child("robust_kernel"));
  ValidateAt(visual, options);
  return options;
}

VisualFactorOptions LoadVisualOptions(const std::string& path) {
  return ReadVisualOptions(YamlNode::LoadFile(path));
}

}  // namespace vio
