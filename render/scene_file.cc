#include "render/scene_file.h"

#include <charconv>
#include <filesystem>
#include <fstream>

#include "dataset/csv.h"
#include "dataset/euroc_reader.h"
#include "dataset/trajectory_io.h"

namespace vio {
namespace {

std::string Number(double v) {
  char buffer[32];
  const std::to_chars_result r =
      std::to_chars(buffer, buffer + sizeof(buffer), v);
  return std::string(buffer, r.ptr);
}

void Put(std::ofstream& out, const Eigen::Vector3d& v) {
  out << ',' << Number(v.x()) << ',' << Number(v.y()) << ',' << Number(v.z());
}

}  // namespace

std::string RenderTruthFolder(const std::string& sequence_folder) {
  return JoinPath(JoinPath(sequence_folder, "mav0"), "render");
}

void WriteSceneCsv(const std::string& path, const SceneGeometry& scene) {
  std::ofstream out(path);
  if (!out) throw DatasetError(path + ": cannot open the file for writing");
  out << "#plane,origin_x [m],origin_y [m],origin_z [m],axis_u_x,axis_u_y,"
         "axis_u_z,axis_v_x,axis_v_y,axis_v_z,size_u [m],size_v [m]\n";
  for (size_t i = 0; i < scene.planes().size(); ++i) {
    const ScenePlane& p = scene.planes()[i];
    out << i;
    Put(out, p.origin_w);
    Put(out, p.axis_u_w);
    Put(out, p.axis_v_w);
    out << ',' << Number(p.size_u_m) << ',' << Number(p.size_v_m) << '\n';
  }
  out.close();
  if (!out) throw DatasetError(path + ": write failed");
}

SceneGeometry ReadSceneCsv(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw DatasetError(path + ": no such file");
  }
  CsvReader csv(path);
  std::vector<ScenePlane> planes;
  while (csv.Next()) {
    csv.ExpectAtLeast(12);
    if (csv.size() != 12) {
      csv.Fail(
          "expected 12 fields (plane, origin, axis_u, axis_v, sizes), "
          "got " +
          std::to_string(csv.size()));
    }
    if (csv.Int64(0) != static_cast<int64_t>(planes.size())) {
      csv.Fail("plane index " + csv.String(0) + " out of order (expected " +
               std::to_string(planes.size()) + ")");
    }
    ScenePlane p;
    p.origin_w = {csv.Double(1), csv.Double(2), csv.Double(3)};
    p.axis_u_w = {csv.Double(4), csv.Double(5), csv.Double(6)};
    p.axis_v_w = {csv.Double(7), csv.Double(8), csv.Double(9)};
    p.size_u_m = csv.Double(10);
    p.size_v_m = csv.Double(11);
    if (!p.IsValid()) {
      csv.Fail(
          "plane is not valid (axes must be unit and orthogonal, sizes "
          "> 0)");
    }
    planes.push_back(p);
  }
  if (planes.empty()) throw DatasetError(path + ": holds no plane");
  return SceneGeometry(std::move(planes));
}

bool HasRenderTruth(const std::string& sequence_folder) {
  std::error_code ec;
  return std::filesystem::is_regular_file(
      JoinPath(RenderTruthFolder(sequence_folder), "scene.csv"), ec);
}

RenderTruth ReadRenderTruth(const std::string& sequence_folder) {
  const std::string folder = RenderTruthFolder(sequence_folder);
  RenderTruth truth;
  truth.scene = ReadSceneCsv(JoinPath(folder, "scene.csv"));
  truth.frame_poses = ReadTum(JoinPath(folder, "frame_poses.tum"));
  return truth;
}

}  // namespace vio
