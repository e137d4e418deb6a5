// The "photometric" case: the photometric factor on a synthetic smooth image
// (a sum of sinusoids, 200 x 150 px) at random host pixels, inverse depths,
// poses, rigs and brightness parameters. The test on real EuRoC image
// patches is test/photometric_factor_test.cc.

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <vector>

#include "factors/check/factor_cases.h"
#include "factors/photometric_factor.h"
#include "factors/pose_manifold.h"

namespace vio {
namespace {

constexpr int kWidth = 200, kHeight = 150;  // [px]
constexpr double kDeg = M_PI / 180.0;

double Uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// A texture with gradients of up to ~30 grey/px at several scales, so the
// bicubic interpolation is exercised between and across pixels.
std::shared_ptr<const ImageGrid> SyntheticImage() {
  static const std::shared_ptr<const ImageGrid> kImage = [] {
    std::mt19937 rng(7);
    struct Wave {
      double amplitude, wu, wv, phase;
    };
    std::vector<Wave> waves;
    for (int k = 0; k < 12; ++k) {
      const double period = Uniform(rng, 4.0, 40.0);  // [px]
      const double angle = Uniform(rng, 0.0, M_PI);
      waves.push_back({Uniform(rng, 5.0, 20.0),
                       2.0 * M_PI / period * std::cos(angle),
                       2.0 * M_PI / period * std::sin(angle),
                       Uniform(rng, 0.0, 2.0 * M_PI)});
    }
    std::vector<float> values(kWidth * kHeight);
    for (int v = 0; v < kHeight; ++v) {
      for (int u = 0; u < kWidth; ++u) {
        double I = 128.0;
        for (const Wave& w : waves) {
          I += w.amplitude * std::sin(w.wu * u + w.wv * v + w.phase);
        }
        values[v * kWidth + u] = static_cast<float>(I);
      }
    }
    return std::make_shared<const ImageGrid>(kWidth, kHeight,
                                             std::move(values));
  }();
  return kImage;
}

Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

Eigen::Isometry3d SmallMotion(std::mt19937& rng, double max_angle,
                              double max_translation) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(Uniform(rng, 0.0, max_angle),
                        Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized())
          .toRotationMatrix();
  T.translation() = Eigen::Vector3d(Uniform(rng, -1, 1), Uniform(rng, -1, 1),
                                    Uniform(rng, -1, 1)) *
                    max_translation;
  return T;
}

Rigid ToRigid(const Eigen::Isometry3d& T) {
  return {T.linear(), T.translation()};
}

std::vector<double> Values(const Block7& x) {
  return std::vector<double>(x.data(), x.data() + x.size());
}

FactorInstance SamplePhotometric(std::mt19937& rng) {
  static const auto kPose = std::make_shared<const PoseManifold>();
  const Pinhole camera{180.0, 175.0, 99.5, 74.5};
  const std::shared_ptr<const ImageGrid> image = SyntheticImage();
  while (true) {
    // A rig: the host camera's extrinsic, and the target camera either the
    // same camera (mono) or one 11 cm to its side (stereo).
    const Eigen::Isometry3d T_b_a =
        Eigen::Isometry3d(RandomRotation(rng)) *
        Eigen::Translation3d(Uniform(rng, -0.1, 0.1), Uniform(rng, -0.1, 0.1),
                             Uniform(rng, -0.1, 0.1));
    Eigen::Isometry3d T_a_c = Eigen::Isometry3d::Identity();
    if (std::uniform_int_distribution<int>(0, 1)(rng) == 1) {
      T_a_c = SmallMotion(rng, 1.0 * kDeg, 0.0);
      T_a_c.translation() = Eigen::Vector3d(0.11, 0.0, 0.0);
    }
    const Eigen::Isometry3d T_b_c = T_b_a * T_a_c;
    // Host pose anywhere; the target camera a few centimetres and degrees
    // from the host camera, so the pixel stays in view.
    const Eigen::Isometry3d T_w_bi =
        Eigen::Translation3d(Uniform(rng, -5, 5), Uniform(rng, -5, 5),
                             Uniform(rng, 0, 3)) *
        Eigen::Isometry3d(RandomRotation(rng));
    const Eigen::Isometry3d T_w_cj =
        T_w_bi * T_b_a * SmallMotion(rng, 4.0 * kDeg, 0.08);
    const Eigen::Isometry3d T_w_bj = T_w_cj * T_b_c.inverse();

    PhotometricHost host;
    host.camera = camera;
    host.uv = Eigen::Vector2d(Uniform(rng, 10, kWidth - 11),
                              Uniform(rng, 10, kHeight - 11));
    host.intensity = Uniform(rng, 40.0, 220.0);
    // Half realistic depths (0.5-10 m), half nearly at infinity.
    const double rho = std::uniform_int_distribution<int>(0, 1)(rng) == 0
                           ? Uniform(rng, 0.1, 2.0)
                           : std::pow(10.0, Uniform(rng, -6.0, -2.0));
    auto factor = std::make_unique<PhotometricFactor>(
        host, image, camera, ToRigid(T_b_a), ToRigid(T_b_c),
        Uniform(rng, 0.05, 0.5));
    FactorInstance f;
    f.blocks = {Values(BlockFromIsometry(T_w_bi)),
                Values(BlockFromIsometry(T_w_bj)),
                {rho},
                {Uniform(rng, -0.3, 0.3), Uniform(rng, -10.0, 10.0)},
                {Uniform(rng, -0.3, 0.3), Uniform(rng, -10.0, 10.0)}};
    f.manifolds = {kPose, kPose, nullptr, nullptr, nullptr};
    f.block_names = {"pose_i", "pose_j", "rho", "ab_i", "ab_j"};
    // Keep only states whose target pixel lies well inside the image, so
    // the numeric steps do not cross the inactive boundary.
    const InverseDepthChain chain(camera.Bearing(host.uv), rho, ToRigid(T_b_a),
                                  ToRigid(T_w_bi), ToRigid(T_w_bj),
                                  ToRigid(T_b_c));
    if (chain.h_c().z() < 0.1) continue;  // in front of the target
    const Eigen::Vector2d w = camera.Project(chain.h_c());
    if (!image->Inside(w.x(), w.y(), 6.0)) continue;
    f.cost = std::move(factor);
    return f;
  }
}

}  // namespace

FactorCase MakePhotometricCase() {
  FactorCase c;
  c.name = "photometric";
  c.description =
      "photometric residual, bicubic synthetic image, affine brightness "
      "[pose_i, pose_j, rho, ab_i, ab_j]";
  c.sample = SamplePhotometric;
  return c;
}

}  // namespace vio
