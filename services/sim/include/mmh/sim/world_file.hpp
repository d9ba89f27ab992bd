// The world as a file: the bounds of a PCD world (the box start, goal and geofence are checked
// against), the geofence fitted to them (--fit-geofence), and a generated world (forest,
// ego-forest) written as a PCD of surface points (--export-world), so that it can be flown again
// with --world FILE.pcd or inspected in other tools.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mmh/common/config.hpp"
#include "mmh/common/geofence.hpp"

namespace mmh::sim {

struct SimOptions;

// The axis-aligned bounding box of a world's points.
struct WorldBounds {
  Eigen::Vector3d min_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_m = Eigen::Vector3d::Zero();
};

bool isPcdWorld(const std::string& world);  // a path ending in .pcd

// The points of a PCD file (x, y, z as stored, non-finite ones included); throws
// std::runtime_error when it cannot be read.
std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path);

// The bounding box of the finite points of a PCD file; throws std::runtime_error with the reason
// (unreadable file, no finite point).
WorldBounds readPcdBounds(const std::string& path);

// Empty when p lies within the bounds in x and y (z is the geofence's business); else a sentence
// naming `what` ("the goal"), its coordinates, the axis that is out and the world's bounds.
std::string worldBoundsViolation(const WorldBounds& bounds, const Eigen::Vector3d& p,
                                 const std::string& what, const std::string& world_name);

// The one check of a run's start and goal (the simulator's, and mmh-bench's before any flight):
// empty when both lie in the geofence and, with `bounds` (a PCD world), within its bounds in x
// and y; else the first violation (geofenceViolation / worldBoundsViolation).
std::string startGoalViolation(const Eigen::Vector3d& start, const Eigen::Vector3d& goal,
                               const Geofence& fence, const WorldBounds* bounds,
                               const std::string& world_name);

// The geofence of --fit-geofence: the world's bounds in x and y widened by margin_xy_m (rounded
// outwards to the centimetre); z as configured.
Geofence fitGeofence(const WorldBounds& bounds, const Geofence& configured,
                     double margin_xy_m = 1.0);

// --fit-geofence for a PCD world: the configuration's fence fitted to the file's bounds, and a
// line saying what was set (for the tool to print).
Geofence fitGeofenceToPcd(const std::string& path, const Config& config, std::string* report);

// `--set` assignments ("geofence.min_m=[x, y, z]", "geofence.max_m=[...]") for that fence.
std::vector<std::string> geofenceAssignments(const Geofence& fence);

// The configuration with geofence.min_m / max_m replaced (the rest as it was).
Config configWithGeofence(const Config& config, const Geofence& fence);

// Surface points of the generated world the options describe (forest or ego-forest): cylinder
// mantles and top discs, the pillars' columns, the rings' tubes, about `spacing_m` apart.
// Throws std::runtime_error for a PCD world or an impossible forest.
std::vector<Eigen::Vector3f> generatedWorldPoints(const SimOptions& options,
                                                  double spacing_m = 0.05);

// Writes the points as a binary PCD (x, y, z); throws std::runtime_error on failure.
void writePcd(const std::string& path, const std::vector<Eigen::Vector3f>& points);

// --export-world: the generated world's surface points written to `path`; returns the line that
// says what was written (for the tool to print).
std::string exportWorld(const SimOptions& options, const std::string& path);

}  // namespace mmh::sim
