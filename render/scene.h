#ifndef VIO_RENDER_SCENE_H_
#define VIO_RENDER_SCENE_H_

// The geometry of the rendered world: textured rectangles (the room's walls,
// floor and ceiling, and the faces of boxes standing on the floor). Eigen
// only: the truth of a rendered sequence (where a pixel's ray meets the
// scene) needs no image code.
//
// A plane is the rectangle
//   X(a, b) = origin_w + a axis_u_w + b axis_v_w,  a in [0, size_u_m],
//                                                  b in [0, size_v_m],
// seen only from the side its normal n = axis_u_w x axis_v_w points to (the
// room's faces look inwards, a box's faces outwards). (a, b) are the plane's
// own coordinates [m]; the texture is laid out along them.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace vio {

struct ScenePlane {
  Eigen::Vector3d origin_w = Eigen::Vector3d::Zero();   // a corner [m]
  Eigen::Vector3d axis_u_w = Eigen::Vector3d::UnitX();  // unit
  Eigen::Vector3d axis_v_w = Eigen::Vector3d::UnitY();  // unit, _|_ axis_u
  double size_u_m = 1.0;                                // [m]
  double size_v_m = 1.0;                                // [m]

  // The side the plane is seen from.
  Eigen::Vector3d Normal() const { return axis_u_w.cross(axis_v_w); }
  // True when the axes are unit and orthogonal (1e-9), sizes > 0, all finite.
  bool IsValid() const;
};

// A box standing on the floor of the room, axis-aligned.
struct SceneBox {
  // Centre of its footprint, from the centre of the room's floor [m].
  Eigen::Vector2d center_xy_m = Eigen::Vector2d::Zero();
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();  // x, y, height [m]
};

// The room (the simulator's, dataset/simulator.h, or one sized to a
// recorded flight) and the boxes in it; kept here so that render/ needs
// nothing of the simulator.
struct SceneLayout {
  Eigen::Vector3d min_corner{-7.0, -6.0, 0.0};  // floor at min z [m]
  Eigen::Vector3d max_corner{7.0, 6.0, 4.0};    // ceiling at max z [m]
  std::vector<SceneBox> boxes;

  // The world position of the centre of the floor [m].
  Eigen::Vector3d FloorCentre() const;
  // True when the room has sizes > 0, every box has sizes > 0, lies inside
  // the room and below its ceiling, and no two boxes overlap; else false
  // with a message that starts with the field ("boxes[2].size_m ...").
  bool Validate(std::string* message) const;
};

// Where a ray meets the scene.
struct SceneHit {
  double distance = 0.0;  // along the unit ray [m]
  int plane = -1;         // index into SceneGeometry::planes()
  Eigen::Vector2d ab = Eigen::Vector2d::Zero();  // plane coordinates [m]
};

class SceneGeometry {
 public:
  SceneGeometry() = default;
  // Throws std::invalid_argument when a plane is not IsValid() or
  // num_enclosing exceeds the planes. The first num_enclosing planes bound
  // a convex space that every camera stays inside (the room): seen from
  // inside they never overlap one another and lie behind every other
  // plane, which lets a renderer draw them without a depth test. 0 claims
  // nothing.
  explicit SceneGeometry(std::vector<ScenePlane> planes, int num_enclosing = 0);

  // The nearest plane that the ray origin_w + t direction_w (t > min_t)
  // meets from its visible side, within the plane's rectangle. Returns false
  // when it meets none. `direction_w` need not be unit; distance is in its
  // units times its norm, i.e. metres along the unit ray.
  bool Intersect(const Eigen::Vector3d& origin_w,
                 const Eigen::Vector3d& direction_w, SceneHit* hit,
                 double min_t = 1e-9) const;

  // True when the segment from eye_w to point_w is not blocked: no plane is
  // met closer than `tolerance_m` before the point.
  bool Visible(const Eigen::Vector3d& eye_w, const Eigen::Vector3d& point_w,
               double tolerance_m = 1e-6) const;

  const std::vector<ScenePlane>& planes() const { return planes_; }
  int num_enclosing() const { return num_enclosing_; }

 private:
  std::vector<ScenePlane> planes_;
  int num_enclosing_ = 0;
};

// The six inward faces of the room (floor, ceiling, four walls; the
// enclosing planes), then five outward faces of each box (no bottom: it
// stands on the floor). Throws
// std::invalid_argument when the layout is invalid.
SceneGeometry MakeRoomScene(const SceneLayout& layout);

}  // namespace vio

#endif  // VIO_RENDER_SCENE_H_
