// The rendered world's geometry (render/scene.h) and its truth file
// (render/scene_file.h): rays meet the room and the boxes where the room's
// dimensions say, from the visible side only, and the file reads back what
// was written.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "dataset/csv.h"
#include "render/render_options.h"
#include "render/scene.h"
#include "render/scene_file.h"
#include "test/testing/expect_error.h"
#include "test/testing/temp_folder.h"

namespace vio {
namespace {

SceneLayout DefaultLayout() {
  SceneLayout layout;  // 14 x 12 x 4 m, floor centre at the origin
  layout.boxes = DefaultSceneBoxes();
  return layout;
}

TEST(SceneGeometry, RaysFromInsideMeetTheRoomWhereItsSizeSays) {
  const SceneGeometry scene = MakeRoomScene(SceneLayout());  // no boxes
  const Eigen::Vector3d eye(1.0, -2.0, 1.5);
  struct Case {
    Eigen::Vector3d direction;
    double distance;
  };
  const Case cases[] = {{{1, 0, 0}, 6.0},  {{-1, 0, 0}, 8.0}, {{0, 1, 0}, 8.0},
                        {{0, -1, 0}, 4.0}, {{0, 0, 1}, 2.5},  {{0, 0, -1}, 1.5},
                        {{0, 0, -2}, 1.5}};  // direction need not be unit
  for (const Case& c : cases) {
    SceneHit hit;
    ASSERT_TRUE(scene.Intersect(eye, c.direction, &hit))
        << c.direction.transpose();
    EXPECT_NEAR(hit.distance, c.distance, 1e-12) << c.direction.transpose();
    // The reported plane coordinates give back the hit point.
    const ScenePlane& p = scene.planes()[hit.plane];
    const Eigen::Vector3d on_plane =
        p.origin_w + hit.ab.x() * p.axis_u_w + hit.ab.y() * p.axis_v_w;
    EXPECT_LT((on_plane - (eye + c.distance * c.direction.normalized())).norm(),
              1e-12);
  }
}

TEST(SceneGeometry, EveryRoomFaceLooksInwardsAndEveryBoxFaceOutwards) {
  const SceneLayout layout = DefaultLayout();
  const SceneGeometry scene = MakeRoomScene(layout);
  ASSERT_EQ(scene.planes().size(), 6u + 5u * layout.boxes.size());
  EXPECT_EQ(scene.num_enclosing(), 6);
  const Eigen::Vector3d room_centre(0.0, 0.0, 2.0);
  for (int i = 0; i < 6; ++i) {
    const ScenePlane& p = scene.planes()[i];
    EXPECT_GT(p.Normal().dot(room_centre - p.origin_w), 0.0)
        << "room face " << i;
  }
  for (size_t b = 0; b < layout.boxes.size(); ++b) {
    const Eigen::Vector3d box_centre(layout.boxes[b].center_xy_m.x(),
                                     layout.boxes[b].center_xy_m.y(),
                                     0.5 * layout.boxes[b].size_m.z());
    for (int f = 0; f < 5; ++f) {
      const ScenePlane& p = scene.planes()[6 + 5 * b + f];
      EXPECT_LT(p.Normal().dot(box_centre - p.origin_w), 0.0)
          << "box " << b << " face " << f;
    }
  }
}

TEST(SceneGeometry, ABoxHidesTheWallBehindIt) {
  SceneLayout layout;
  SceneBox box;
  box.center_xy_m = {3.0, 0.0};
  box.size_m = {1.0, 2.0, 1.0};
  layout.boxes = {box};
  const SceneGeometry scene = MakeRoomScene(layout);
  const Eigen::Vector3d eye(0.0, 0.0, 0.5);
  SceneHit hit;
  ASSERT_TRUE(scene.Intersect(eye, Eigen::Vector3d::UnitX(), &hit));
  EXPECT_NEAR(hit.distance, 2.5, 1e-12);  // the box's face at x = 2.5
  EXPECT_EQ(hit.plane, 6 + 2);            // its -x face
  // Over the box the ray reaches the wall at x = 7.
  ASSERT_TRUE(scene.Intersect({0.0, 0.0, 1.5}, Eigen::Vector3d::UnitX(), &hit));
  EXPECT_NEAR(hit.distance, 7.0, 1e-12);
  EXPECT_FALSE(scene.Visible(eye, {7.0, 0.0, 0.5}));
  EXPECT_TRUE(scene.Visible(eye, {2.5, 0.0, 0.5}));  // on the face itself
  EXPECT_TRUE(scene.Visible(eye, {7.0, 0.0, 3.5}));  // passes above the box
  // From inside the box, its faces are seen from behind: not met.
  ASSERT_TRUE(scene.Intersect({3.0, 0.0, 0.5}, Eigen::Vector3d::UnitX(), &hit));
  EXPECT_NEAR(hit.distance, 4.0, 1e-12);
}

TEST(SceneGeometry, RandomRaysEndOnTheSurfaceOfTheRoomOrABox) {
  const SceneLayout layout = DefaultLayout();
  const SceneGeometry scene = MakeRoomScene(layout);
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int on_boxes = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d eye(3.0 * u(rng), 2.0 * u(rng), 1.2 + 0.4 * u(rng));
    const Eigen::Vector3d d(u(rng), u(rng), u(rng));
    SceneHit hit;
    ASSERT_TRUE(scene.Intersect(eye, d, &hit));
    const Eigen::Vector3d X = eye + hit.distance * d.normalized();
    // Inside the room's box, and on the wall, floor or ceiling when the
    // plane is the room's; else on the surface of a box.
    EXPECT_LE(std::abs(X.x()), 7.0 + 1e-9);
    EXPECT_LE(std::abs(X.y()), 6.0 + 1e-9);
    EXPECT_GE(X.z(), -1e-9);
    EXPECT_LE(X.z(), 4.0 + 1e-9);
    if (hit.plane < 6) {
      const double to_boundary = std::min(
          {7.0 - std::abs(X.x()), 6.0 - std::abs(X.y()), X.z(), 4.0 - X.z()});
      EXPECT_LT(to_boundary, 1e-9);
    } else {
      ++on_boxes;
      const SceneBox& b = layout.boxes[(hit.plane - 6) / 5];
      const Eigen::Vector3d c(b.center_xy_m.x(), b.center_xy_m.y(),
                              0.5 * b.size_m.z());
      const Eigen::Vector3d r = ((X - c).cwiseAbs() - 0.5 * b.size_m);
      EXPECT_LT(std::abs(r.maxCoeff()), 1e-9);  // on its surface
    }
    // Nothing is met before the hit.
    EXPECT_TRUE(scene.Visible(eye, X, 1e-6));
  }
  EXPECT_GT(on_boxes, 20);
}

TEST(SceneLayout, RefusesBoxesOutsideTheRoomOrOverlapping) {
  SceneLayout layout = DefaultLayout();
  std::string message;
  EXPECT_TRUE(layout.Validate(&message)) << message;
  layout.boxes[1].center_xy_m = {6.8, 0.0};
  EXPECT_FALSE(layout.Validate(&message));
  EXPECT_THAT(message, ::testing::HasSubstr("boxes[1] must lie inside"));
  layout = DefaultLayout();
  layout.boxes[2].center_xy_m = layout.boxes[0].center_xy_m;
  EXPECT_FALSE(layout.Validate(&message));
  EXPECT_THAT(message, ::testing::HasSubstr("boxes[2] overlaps boxes[0]"));
  layout = DefaultLayout();
  layout.boxes[0].size_m.z() = 4.0;
  EXPECT_FALSE(layout.Validate(&message));
  layout = DefaultLayout();
  layout.max_corner.z() = layout.min_corner.z();
  EXPECT_FALSE(layout.Validate(&message));
  EXPECT_THAT(message, ::testing::HasSubstr("room sizes"));
  ExpectErrorContaining<std::invalid_argument>([&] { MakeRoomScene(layout); },
                                               "scene layout: room sizes");
}

TEST(SceneLayout, AnOffCentreRoomCarriesItsBoxesAlong) {
  SceneLayout layout;
  layout.min_corner = {10.0, 20.0, -1.0};
  layout.max_corner = {20.0, 30.0, 2.0};
  SceneBox box;
  box.center_xy_m = {1.0, 0.0};
  box.size_m = {1.0, 1.0, 1.0};
  layout.boxes = {box};
  EXPECT_EQ(layout.FloorCentre(), Eigen::Vector3d(15.0, 25.0, -1.0));
  const SceneGeometry scene = MakeRoomScene(layout);
  SceneHit hit;
  ASSERT_TRUE(
      scene.Intersect({15.0, 25.0, -0.5}, Eigen::Vector3d::UnitX(), &hit));
  EXPECT_NEAR(hit.distance, 0.5, 1e-12);  // the box's face at x = 15.5
  ASSERT_TRUE(
      scene.Intersect({15.0, 25.0, 0.5}, -Eigen::Vector3d::UnitZ(), &hit));
  EXPECT_NEAR(hit.distance, 1.5, 1e-12);  // the floor at z = -1
}

TEST(SceneFile, ReadsBackExactlyWhatWasWritten) {
  testing::TempFolder folder;
  const SceneGeometry scene = MakeRoomScene(DefaultLayout());
  const std::string path = folder.Path("scene.csv");
  WriteSceneCsv(path, scene);
  const SceneGeometry back = ReadSceneCsv(path);
  ASSERT_EQ(back.planes().size(), scene.planes().size());
  for (size_t i = 0; i < scene.planes().size(); ++i) {
    const ScenePlane& a = scene.planes()[i];
    const ScenePlane& b = back.planes()[i];
    EXPECT_EQ(a.origin_w, b.origin_w);
    EXPECT_EQ(a.axis_u_w, b.axis_u_w);
    EXPECT_EQ(a.axis_v_w, b.axis_v_w);
    EXPECT_EQ(a.size_u_m, b.size_u_m);
    EXPECT_EQ(a.size_v_m, b.size_v_m);
  }
}

TEST(SceneFile, BadLinesNameTheFileAndLine) {
  testing::TempFolder folder;
  const std::string header = "#plane,origin,...\n";
  folder.Write("short.csv", header + "0,0,0,0,1,0,0,0,1,0,1\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadSceneCsv(folder.Path("short.csv")); },
      "short.csv:2: expected 12 fields");
  folder.Write("skew.csv", header + "0,0,0,0,1,0,0,0.5,1,0,1,1\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadSceneCsv(folder.Path("skew.csv")); },
      "skew.csv:2: plane is not valid");
  folder.Write("order.csv", header + "1,0,0,0,1,0,0,0,1,0,1,1\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadSceneCsv(folder.Path("order.csv")); },
      "order.csv:2: plane index 1 out of order");
  folder.Write("nan.csv", header + "0,nan,0,0,1,0,0,0,1,0,1,1\n");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadSceneCsv(folder.Path("nan.csv")); }, "nan.csv:2:");
  folder.Write("empty.csv", header);
  ExpectErrorContaining<DatasetError>(
      [&] { ReadSceneCsv(folder.Path("empty.csv")); }, "holds no plane");
  ExpectErrorContaining<DatasetError>(
      [&] { ReadSceneCsv(folder.Path("absent.csv")); }, "no such file");
  EXPECT_FALSE(HasRenderTruth(folder.path()));
}

}  // namespace
}  // namespace vio
