#ifndef VIO_DATASET_FLIGHT_ROOM_H_
#define VIO_DATASET_FLIGHT_ROOM_H_

// The scene around a recorded flight: a box room sized to the flight's extent
// (walls, floor and ceiling carrying point landmarks at a given density) and
// clutter, points spread through the room's volume but kept clear of the
// flight path, so that a camera sees structure at many depths, as in EuRoC's
// machine hall and Vicon room.

#include <Eigen/Core>
#include <random>
#include <string>
#include <vector>

namespace vio {

struct FlightRoomOptions {
  double wall_margin_m = 3.0;  // walls beyond the flight's x, y extent [m]
  // The room is at least this long and wide (a flight that stays within a
  // metre, as a hand-held start, still sees walls a few metres away) [m].
  double min_width_m = 12.0;
  double floor_margin_m = 0.5;    // floor below the lowest position [m]
  double ceiling_margin_m = 2.0;  // ceiling above the highest position [m]
  // Landmarks per square metre of wall, floor and ceiling [1/m^2] (the
  // built-in presets' room has about 11).
  double landmarks_per_m2 = 11.0;
  // Clutter landmarks per cubic metre of the room's volume [1/m^3].
  double clutter_per_m3 = 1.0;
  // Clutter is at least this far from every position of the flight [m].
  double clutter_clearance_m = 1.0;

  // True when the margins and the clearance are finite and >= 0, and the
  // densities finite, >= 0 and not both zero; otherwise false with a message
  // naming the field.
  bool Validate(std::string* message) const;
};

// The room's box and what was placed in it.
struct FlightRoom {
  Eigen::Vector3d min_corner = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d max_corner = Eigen::Vector3d::Zero();  // [m]
  int surface_landmarks = 0;
  int clutter_landmarks = 0;
  std::vector<Eigen::Vector3d> landmarks_w;  // surface first, then clutter
};

// The room around `path` (the flight's positions, at least one; densely
// enough sampled for the clearance test, e.g. every 0.1 s). Throws
// std::invalid_argument for invalid options or an empty path.
FlightRoom MakeFlightRoom(const std::vector<Eigen::Vector3d>& path,
                          const FlightRoomOptions& options, std::mt19937* rng);

}  // namespace vio

#endif  // VIO_DATASET_FLIGHT_ROOM_H_
