#include "mmh/common/geofence.hpp"

namespace mmh {

Geofence loadGeofence(const Config& config) {
  // That max_m exceeds min_m is a registered constraint (config_constraints.cpp), checked with
  // the others by every parameter loader.
  return {config.getVector3("geofence.min_m"), config.getVector3("geofence.max_m")};
}

}  // namespace mmh
