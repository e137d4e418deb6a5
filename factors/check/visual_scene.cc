#include "factors/check/visual_scene.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace vio {
namespace {

constexpr double kFocalPx = 458.654;  // EuRoC cam0 fu [px]
constexpr double kSigmaPx = 1.5;      // feature noise [px]
constexpr double kDeg = M_PI / 180.0;

double Uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Eigen::Vector3d UniformVector(std::mt19937& rng, double lo, double hi) {
  return Eigen::Vector3d(Uniform(rng, lo, hi), Uniform(rng, lo, hi),
                         Uniform(rng, lo, hi));
}

Eigen::Vector3d RandomDirection(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

// Uniform over SO(3): a normalised 4-D Gaussian.
Eigen::Quaterniond RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// A rotation by an angle uniform in [0, max_angle] [rad] about a random axis.
Eigen::Quaterniond SmallRotation(std::mt19937& rng, double max_angle) {
  return Eigen::Quaterniond(
      Eigen::AngleAxisd(Uniform(rng, 0.0, max_angle), RandomDirection(rng)));
}

Eigen::Isometry3d Make(const Eigen::Quaterniond& q, const Eigen::Vector3d& t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = t;
  return T;
}

// EuRoC's rig: both cameras look along body z, image x along -body y;
// cam0 at (-0.022, -0.065, 0.010) m, cam1 11 cm to its side. Perturbed by up
// to 2 degrees and 1 cm so that no Jacobian is checked only at a special
// rotation.
Eigen::Isometry3d EurocLikeExtrinsic(std::mt19937& rng,
                                     const Eigen::Vector3d& t_nominal) {
  const Eigen::Quaterniond q_nominal(
      Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitZ()));
  return Make(q_nominal * SmallRotation(rng, 2.0 * kDeg),
              t_nominal + UniformVector(rng, -0.01, 0.01));
}

VisualGeometry Resolve(std::mt19937& rng, VisualGeometry geometry) {
  if (geometry != VisualGeometry::kMixed) return geometry;
  switch (std::uniform_int_distribution<int>(0, 5)(rng)) {
    case 0:
      return VisualGeometry::kFarPoint;
    case 1:
      return VisualGeometry::kNegativeDepth;
    case 2:
      return VisualGeometry::kNearTargetCamera;
    default:
      return VisualGeometry::kRealistic;
  }
}

double SampleInverseDepth(std::mt19937& rng, VisualGeometry geometry,
                          VisualTarget target) {
  switch (geometry) {
    case VisualGeometry::kFarPoint:
      return std::pow(10.0, Uniform(rng, -6.0, -3.0));
    case VisualGeometry::kNegativeDepth:
      return -std::pow(10.0, Uniform(rng, -6.0, std::log10(0.05)));
    case VisualGeometry::kNearTargetCamera:
      // In one keyframe the target camera sits beside the anchor: a point
      // 5-20 cm from the anchor is 5-20 cm from it too.
      if (target == VisualTarget::kStereoSameFrame) {
        return 1.0 / Uniform(rng, 0.05, 0.2);
      }
      return 1.0 / Uniform(rng, 1.0, 20.0);
    default:
      return 1.0 / Uniform(rng, 1.0, 20.0);
  }
}

// Pose of the target camera in the world (T_w_c_target).
Eigen::Isometry3d SampleTargetCamera(std::mt19937& rng, VisualGeometry geometry,
                                     const Eigen::Isometry3d& T_w_ca,
                                     const Eigen::Vector3d& p_w_landmark) {
  const Eigen::Quaterniond q_w_c =
      Eigen::Quaterniond(T_w_ca.linear()) * SmallRotation(rng, 20.0 * kDeg);
  if (geometry == VisualGeometry::kNearTargetCamera) {
    // Put the camera 5-20 cm behind the landmark, looking at it.
    const double depth = Uniform(rng, 0.05, 0.2);
    const Eigen::Vector3d p_c(Uniform(rng, -0.5, 0.5) * depth,
                              Uniform(rng, -0.5, 0.5) * depth, depth);
    return Make(q_w_c, p_w_landmark - q_w_c * p_c);
  }
  const Eigen::Vector3d offset = Uniform(rng, 0.2, 3.0) * RandomDirection(rng);
  return Make(q_w_c, T_w_ca.translation() + offset);
}

bool Acceptable(VisualGeometry geometry, const Eigen::Vector3d& h, double rho) {
  if (geometry == VisualGeometry::kRealistic) {
    // In front (depth > 0.5 m) and inside a wide field of view.
    return h.z() / rho > 0.5 &&
           (h.head<2>() / h.z()).cwiseAbs().maxCoeff() < 1.0;
  }
  if (geometry == VisualGeometry::kNearTargetCamera) {
    return h.z() > 10.0 * kMinProjectiveDepth;
  }
  return h.z() > 0.5 * h.norm();
}

void AddTiming(std::mt19937& rng, VisualScene* s) {
  std::normal_distribution<double> velocity(0.0, 0.3);  // [1/s]
  s->t_d = Uniform(rng, -0.005, 0.005);
  for (TimedObservation* obs : {&s->obs_i, &s->obs_j}) {
    obs->velocity = Eigen::Vector2d(velocity(rng), velocity(rng));
    obs->t_d_at_stamp = s->t_d + Uniform(rng, -0.003, 0.003);
    // What the camera measured, a little off the pose's time.
    obs->xy += (s->t_d - obs->t_d_at_stamp) * obs->velocity;
  }
}

}  // namespace

Block7 BlockFromIsometry(const Eigen::Isometry3d& T) {
  Block7 x;
  x.head<3>() = T.translation();
  x.tail<4>() = Eigen::Quaterniond(T.linear()).normalized().coeffs();
  return x;
}

Eigen::Isometry3d IsometryFromBlock(const Block7& x) {
  return Make(Eigen::Quaterniond(Eigen::Vector4d(x.tail<4>())), x.head<3>());
}

Eigen::Isometry3d TargetCameraPose(const VisualScene& s, VisualTarget target) {
  switch (target) {
    case VisualTarget::kMonoOtherFrame:
      return IsometryFromBlock(s.pose_j) * IsometryFromBlock(s.extrinsic0);
    case VisualTarget::kStereoSameFrame:
      return IsometryFromBlock(s.pose_i) * IsometryFromBlock(s.extrinsic1);
    case VisualTarget::kStereoOtherFrame:
      break;
  }
  return IsometryFromBlock(s.pose_j) * IsometryFromBlock(s.extrinsic1);
}

void SetTargetCameraPose(const Eigen::Isometry3d& T_w_c, VisualTarget target,
                         VisualScene* s) {
  switch (target) {
    case VisualTarget::kMonoOtherFrame:
      s->pose_j =
          BlockFromIsometry(T_w_c * IsometryFromBlock(s->extrinsic0).inverse());
      return;
    case VisualTarget::kStereoSameFrame:
      s->extrinsic1 =
          BlockFromIsometry(IsometryFromBlock(s->pose_i).inverse() * T_w_c);
      return;
    case VisualTarget::kStereoOtherFrame:
      s->pose_j =
          BlockFromIsometry(T_w_c * IsometryFromBlock(s->extrinsic1).inverse());
      return;
  }
}

Eigen::Vector3d TargetPoint(const VisualScene& s, VisualTarget target) {
  const Eigen::Isometry3d T_w_ci =
      IsometryFromBlock(s.pose_i) * IsometryFromBlock(s.extrinsic0);
  const Eigen::Isometry3d T_cj_ci =
      TargetCameraPose(s, target).inverse() * T_w_ci;
  // The landmark as a homogeneous 4-vector (f, rho) in the anchor camera, f
  // the anchor bearing at the pose's time.
  const Eigen::Vector2d xy_i =
      s.obs_i.xy - (s.t_d - s.obs_i.t_d_at_stamp) * s.obs_i.velocity;
  const Eigen::Vector4d X(xy_i.x(), xy_i.y(), 1.0, s.rho);
  return (T_cj_ci.matrix() * X).head<3>();
}

VisualScene SampleVisualScene(std::mt19937& rng, VisualGeometry geometry,
                              VisualTarget target, bool timed,
                              double noise_px) {
  geometry = Resolve(rng, geometry);
  for (int attempt = 0; attempt < 1000; ++attempt) {
    VisualScene s;
    s.sqrt_info = kFocalPx / kSigmaPx;
    const Eigen::Isometry3d T_w_bi =
        Make(RandomRotation(rng), UniformVector(rng, -3.0, 3.0));
    const Eigen::Isometry3d T_b_c0 =
        EurocLikeExtrinsic(rng, Eigen::Vector3d(-0.022, -0.065, 0.010));
    const Eigen::Isometry3d T_b_c1 =
        EurocLikeExtrinsic(rng, Eigen::Vector3d(-0.020, 0.045, 0.008));
    s.pose_i = BlockFromIsometry(T_w_bi);
    s.extrinsic0 = BlockFromIsometry(T_b_c0);
    s.extrinsic1 = BlockFromIsometry(T_b_c1);
    s.rho = SampleInverseDepth(rng, geometry, target);
    s.obs_i.xy =
        Eigen::Vector2d(Uniform(rng, -0.5, 0.5), Uniform(rng, -0.5, 0.5));
    const Eigen::Isometry3d T_w_ca = T_w_bi * T_b_c0;
    if (target == VisualTarget::kStereoSameFrame) {
      s.pose_j = s.pose_i;
    } else {
      // For rho <= 0 the landmark has no finite position; any far point on
      // the ray serves to place the target camera.
      const double depth = s.rho > 1e-3 ? 1.0 / s.rho : 1e3;
      const Eigen::Vector3d p_w_l = T_w_ca * (depth * s.obs_i.xy.homogeneous());
      SetTargetCameraPose(SampleTargetCamera(rng, geometry, T_w_ca, p_w_l),
                          target, &s);
    }
    const Eigen::Vector3d h = TargetPoint(s, target);
    if (!Acceptable(geometry, h, s.rho)) continue;
    std::normal_distribution<double> noise(0.0, noise_px / kFocalPx);
    s.obs_j.xy = h.head<2>() / h.z() + Eigen::Vector2d(noise(rng), noise(rng));
    if (timed) AddTiming(rng, &s);
    return s;
  }
  throw std::logic_error("SampleVisualScene: no acceptable scene drawn");
}

}  // namespace vio
