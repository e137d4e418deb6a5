#ifndef VIO_FACTORS_PHOTOMETRIC_FACTOR_H_
#define VIO_FACTORS_PHOTOMETRIC_FACTOR_H_

// The direct (photometric) residual of the user's notes (seeds/000, eq. 1)
// for one pixel p of a host image i with inverse depth rho, warped into a
// target image j, with DSO's affine brightness per image and the notes'
// inverse-depth-variance weight (eq. 3):
//
//   f  = e^(a_j - a_i) (I_i(p) - b_i) - (I_j(w) - b_j)           [grey]
//   r  = sqrt(W) * f                                              (1)
//   w  = K_j pi(h_c)  (pinhole of the target image)
//   h_c = R_b_c^T (R_w_bj^T (R_w_bi (R_b_a f_a + rho t_b_a) + rho p_w_bi
//                            - rho p_w_bj) - rho t_b_c),  f_a = K_i^-1 p
//   W  = (2 sigma_I^2 + (df/drho)^2 V)^-1                         (notes' W_m)
// With a = b = 0 this is the notes' f_m = I_i(p_m) - I_j(w(p_m, D_i, delta));
// DSO's own residual is -f (J. Engel et al., "Direct Sparse Odometry", PAMI
// 2018, eq. 4, without exposure times: EuRoC records none).
//
// h_c is the homogeneous point rho * p_c of factors/inverse_depth_chain.h:
// the poses are whatever frame the caller keeps (body poses with the camera
// extrinsics T_b_a, T_b_c given here as constants, or camera poses with
// identity extrinsics), and the host may be seen by another camera of the
// same rig (stereo: T_b_c = the right camera's extrinsic). With pose_i held at
// the identity, pose_j is the relative pose T_i_j, the notes' delta^-1.
//
// Parameter blocks, in this order:
//   pose_i  T_w_bi (7) [t, q(x, y, z, w)]   host
//   pose_j  T_w_bj (7)                       target
//   rho     inverse depth of the pixel in the host camera [1/m] (1)
//   ab_i    affine brightness (a, b) of the host image [-, grey] (2)
//   ab_j    affine brightness (a, b) of the target image (2)
// Hold ab_i and ab_j constant (at 0) to use no brightness model. Pose
// Jacobians are taken on PoseManifold's tangent space (right perturbation)
// and lifted through its MinusJacobian (factors/pose_manifold.h).
//
// The weight. W depends on the state through df/drho, which holds the image
// gradient at w; differentiating W would need the image's second derivatives.
// As in the notes (W_m(delta) re-evaluated once per iteration) and in
// LSD-SLAM, W is held constant while the residual is linearised: the factor
// carries sqrt(W) as a constant, set at construction or by set_sqrt_weight,
// and PhotometricWeight computes the notes' W from df/drho at a state
// (InverseDepthDerivative). The Jacobians below are exact for that constant.
//
// Inactive residual. When h_c.z < kMinProjectiveDepth (behind or at the
// target camera) or w is less than kImageGridMargin px from the target
// image's edge, the target image says nothing about the pixel: the residual
// and every Jacobian are 0 (DSO and LSD-SLAM drop such pixels likewise).
// Evaluate returns false only for non-finite input.

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <memory>

#include "factors/image_grid.h"
#include "factors/inverse_depth_chain.h"
#include "geometry/pinhole.h"

namespace vio {

// The notes' weight W = (2 sigma_I^2 + (df/drho)^2 V)^-1 [1/grey^2], with the
// intensity noise sigma_I [grey] of each image, df/drho [grey m] and the
// inverse-depth variance V [1/m^2]. V = 0 gives the unweighted 1/(2 sigma_I^2).
double PhotometricWeight(double sigma_intensity, double d_f_d_rho,
                         double rho_variance);

// What the factor knows of its host pixel.
struct PhotometricHost {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // pixel p in image i [px]
  double intensity = 0.0;                        // I_i(p) [grey]
  Pinhole camera;                                // K_i of image i
};

class PhotometricFactor final
    : public ceres::SizedCostFunction<1, 7, 7, 1, 2, 2> {
 public:
  enum Block {
    kPoseI = 0,
    kPoseJ = 1,
    kInverseDepth = 2,
    kAffineI = 3,
    kAffineJ = 4
  };

  // `target` is image j (shared by all its factors) with its pinhole K_j;
  // T_b_a, T_b_c are the host and target camera extrinsics (constants);
  // sqrt_weight = sqrt(W) [1/grey].
  PhotometricFactor(const PhotometricHost& host,
                    std::shared_ptr<const ImageGrid> target,
                    const Pinhole& target_camera, const Rigid& T_b_a,
                    const Rigid& T_b_c, double sqrt_weight);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  // The unweighted f and df/drho [grey m] at a state; false when the
  // residual is inactive there (see the header comment).
  bool InverseDepthDerivative(double const* const* parameters, double* f,
                              double* d_f_d_rho) const;

  double sqrt_weight() const { return sqrt_weight_; }
  void set_sqrt_weight(double sqrt_weight) { sqrt_weight_ = sqrt_weight; }

 private:
  // f and d f / d h_c (1 x 3) at the state's h_c; false when inactive.
  bool Linearize(const Eigen::Vector3d& h_c, double a_i, double b_i, double a_j,
                 double b_j, double* f, Eigen::RowVector3d* d_f_d_h) const;

  Eigen::Vector3d f_a_;  // host bearing K_i^-1 p
  double intensity_;     // I_i(p)
  std::shared_ptr<const ImageGrid> target_;
  Pinhole target_camera_;
  Rigid T_b_a_, T_b_c_;
  double sqrt_weight_;
};

}  // namespace vio

#endif  // VIO_FACTORS_PHOTOMETRIC_FACTOR_H_
