// Runs one benchmark flight in lock-step (mmh-stack's engine) and turns the flight record into
// the benchmark's result; also writes the flown path and the world's obstacles for the plots.
#pragma once

#include <string>

#include "flight_spec.hpp"
#include "mmh/common/config.hpp"

namespace mmh::bench {

// paths_dir: where <id>.path.json goes (empty: not written).
FlightResult runFlight(const FlightSpec& spec, const Config& config, double timeout_s,
                       const std::string& paths_dir);

}  // namespace mmh::bench
