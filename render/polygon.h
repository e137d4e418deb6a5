#ifndef VIO_RENDER_POLYGON_H_
#define VIO_RENDER_POLYGON_H_

// Convex polygon clipping (Sutherland-Hodgman against one half-space), for
// the renderer's near plane, view rectangle and mip bands.

#include <Eigen/Core>
#include <vector>

namespace vio {

using Polygon = std::vector<Eigen::Vector3d>;

// The part of the convex polygon where k.head<3>() . p + k[3] >= 0. New
// vertices are interpolated linearly along the cut edges, which is exact for
// any affine k; 2-D points are passed as (u, v, 1) with k = (a, b, c, 0).
Polygon ClipPolygon(const Polygon& polygon, const Eigen::Vector4d& k);

}  // namespace vio

#endif  // VIO_RENDER_POLYGON_H_
