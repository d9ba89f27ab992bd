// mmh-bench: the paper's experiment (docs/benchmark.md) in lock-step, every method on the same
// worlds, start, goal and sensor; results.json, summary.md and plots in --out.
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "bench_report.hpp"
#include "config_overrides.hpp"
#include "mmh/common/cli.hpp"
#include "mmh/common/geofence.hpp"
#include "mmh/common/log.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/sim/world_file.hpp"
#include "run_flight.hpp"

#ifndef MMH_SOURCE_DIR
#define MMH_SOURCE_DIR "."
#endif

namespace fs = std::filesystem;
using mmh::bench::FlightResult;
using mmh::bench::FlightSpec;

namespace {

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  std::string part;
  while (std::getline(s, part, ',')) {
    if (!part.empty()) out.push_back(part);
  }
  return out;
}

std::string formatDuration(double s) {
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof(buf), "%dh%02dm", int(s / 3600), int(s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof(buf), "%dm%02ds", int(s / 60), int(s) % 60);
  else
    std::snprintf(buf, sizeof(buf), "%ds", int(s));
  return buf;
}

void progress(size_t done, size_t total, double elapsed_s, int failed) {
  const int width = 30;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  const double eta = done ? elapsed_s / done * (total - done) : 0.0;
  std::fprintf(stderr, "\r[%s%s] %zu/%zu flights  %s elapsed  ETA %s  failed %d   ",
               std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), done,
               total, formatDuration(elapsed_s).c_str(), done ? formatDuration(eta).c_str() : "?",
               failed);
  std::fflush(stderr);
}

FlightResult readResult(const std::string& path, const FlightSpec& spec) {
  try {
    std::ifstream in(path);
    return mmh::bench::fromJson(nlohmann::json::parse(in));
  } catch (const std::exception& e) {
    FlightResult r;
    r.spec = spec;
    r.error = std::string("worker gave no result: ") + e.what();
    return r;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string command;
  for (int i = 0; i < argc; ++i) command += (i ? " " : "") + std::string(argv[i]);
  std::vector<std::string> overrides = mmh::takeSetOptions(&argc, argv);
  std::string set_help, sensor = "depth";
  std::string methods_text = "mmh,ego,som", densities_text = "0,0.05,0.1,0.2", out_dir;
  std::string config_path, world = "forest", worker_spec, worker_out, paths_dir;
  int maps = 3, trials = 5, jobs = 1, seed = 1;
  double timeout_s = 120.0;
  bool no_plots = false, fit_geofence = false;
  FlightSpec defaults;
  Eigen::Vector3d start = defaults.start, goal = defaults.goal, size = defaults.size_m;
  mmh::ArgParser parser(
      "mmh-bench",
      "Runs the mission benchmark of docs/benchmark.md in lock-step: every method on "
      "the same worlds, start, goal and sensor; writes results.json, summary.md "
      "and plots to --out.");
  parser.addString(
      "--methods", &methods_text,
      "comma-separated arbiter policies: mmh, ego, som, mmh-no-lazy, mmh-no-awareness");
  parser.addString("--densities", &densities_text, "comma-separated forest densities (obs/m^2)");
  parser.addInt("--maps", &maps, "forest maps per density");
  parser.addInt("--trials", &trials, "flights per map (each with its own sensor-noise seed)");
  parser.addInt("--jobs", &jobs, "flights run in parallel processes");
  parser.addInt("--seed", &seed, "base of the map seeds");
  parser.addString("--out", &out_dir, "output directory (required)");
  parser.addString("--config", &config_path, "configuration (default: deploy/config/default.yaml)");
  parser.addString("--world", &world,
                   "forest, ego-forest (EGO-Planner's pillars and rings), or a PCD file of your "
                   "own world");
  parser.addVector3("--size", &size, "forest / ego-forest box x,y,z (m), centred on x = y = 0");
  parser.addString("--sensor", &sensor, "depth or lidar");
  parser.addString("--set", &set_help,
                   "key=value: override one configuration key for every flight (repeatable; a key "
                   "of docs/configuration.md, also one the file leaves out)");
  parser.addVector3("--start", &start, "start x,y,z");
  parser.addVector3("--goal", &goal, "goal x,y,z");
  parser.addDouble("--timeout", &timeout_s, "simulated seconds before a flight counts as failed");
  parser.addFlag("--fit-geofence", &fit_geofence,
                 "with --world FILE.pcd: set geofence.min_m / max_m to the file's bounds plus 1 m "
                 "in x and y (z as configured) for every flight, and print them");
  parser.addFlag("--no-plots", &no_plots, "skip the matplotlib plots");
  parser.addString("--worker-spec", &worker_spec, "(internal) run one flight");
  parser.addString("--worker-out", &worker_out, "(internal) where the worker writes its result");
  parser.addString("--paths", &paths_dir, "(internal) where the worker writes the flown path");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogLevel(mmh::LogLevel::kError);

  mmh::NodeOptions node;
  node.config_path = config_path;
  mmh::Config config;
  try {
    config = mmh::loadConfigWithOverrides(node, overrides);
    mmh::setLogLevel(mmh::LogLevel::kError);
  } catch (const std::exception& e) {
    std::cerr << "mmh-bench: " << e.what() << "\n";
    return 1;
  }

  if (!worker_spec.empty()) {  // one flight, in this process
    FlightSpec spec = mmh::bench::fromJson(nlohmann::json::parse(worker_spec)).spec;
    const FlightResult r = mmh::bench::runFlight(spec, config, timeout_s, paths_dir);
    std::ofstream(worker_out) << mmh::bench::toJson(r).dump() << "\n";
    return 0;
  }
  if (out_dir.empty()) {
    std::cerr << "mmh-bench: --out DIR is required\n" << parser.usage();
    return 2;
  }
  if (maps < 1 || trials < 1 || jobs < 1) {
    std::cerr << "mmh-bench: --maps, --trials and --jobs must be >= 1\n";
    return 2;
  }
  if (sensor != "depth" && sensor != "lidar") {
    std::cerr << "mmh-bench: unknown sensor '" << sensor << "' (use depth or lidar)\n";
    return 2;
  }
  const std::vector<std::string> methods = splitList(methods_text);
  std::vector<double> densities;
  for (const std::string& d : splitList(densities_text)) densities.push_back(std::stod(d));
  const bool generated_world = world == "forest" || world == "ego-forest";
  if (!generated_world) {
    densities = {-1.0};
    maps = 1;
    if (!fs::exists(world)) {
      std::cerr << "mmh-bench: world file " << world << " not found\n";
      return 2;
    }
    world = fs::absolute(world).string();
  }
  // A start or goal the arbiter would refuse, or off the world's points, would only make every
  // flight time out: stop now, with the simulator's own check.
  try {
    std::optional<mmh::sim::WorldBounds> bounds;
    if (!generated_world) bounds = mmh::sim::readPcdBounds(world);
    if (fit_geofence) {
      std::string report;
      const mmh::Geofence fence = mmh::sim::fitGeofenceToPcd(world, config, &report);
      config = mmh::sim::configWithGeofence(config, fence);
      // The workers read the configuration again: they get the fence as --set.
      for (const std::string& a : mmh::sim::geofenceAssignments(fence)) overrides.push_back(a);
      std::cerr << "mmh-bench: " << report << "\n";
    }
    const std::string why = mmh::sim::startGoalViolation(start, goal, mmh::loadGeofence(config),
                                                         bounds ? &*bounds : nullptr, world);
    if (!why.empty()) {
      std::cerr << "mmh-bench: " << why << "\n";
      return 2;
    }
  } catch (const std::exception& e) {
    std::cerr << "mmh-bench: " << e.what() << "\n";
    return 2;
  }

  // The flights: every method on the same map and trial seeds.
  std::vector<FlightSpec> flights;
  for (size_t di = 0; di < densities.size(); ++di) {
    for (int m = 0; m < maps; ++m) {
      for (int t = 0; t < trials; ++t) {
        for (const std::string& method : methods) {
          FlightSpec f;
          f.method = method;
          f.density = densities[di];
          f.world = world;
          f.size_m = size;
          f.sensor = sensor;
          f.map_index = m;
          f.map_seed = seed * 1000 + static_cast<int64_t>(di) * 100 + m;
          f.trial = t;
          f.noise_seed = f.map_seed * 100 + t + 1;
          f.start = start;
          f.goal = goal;
          flights.push_back(f);
        }
      }
    }
  }

  fs::create_directories(fs::path(out_dir) / "flights");
  fs::create_directories(fs::path(out_dir) / "paths");
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<FlightResult> results(flights.size());
  std::map<pid_t, size_t> running;
  size_t next = 0, done = 0;
  int failed = 0;
  progress(0, flights.size(), 0.0, 0);
  while (done < flights.size()) {
    while (next < flights.size() && static_cast<int>(running.size()) < jobs) {
      const FlightSpec& f = flights[next];
      FlightResult stub;
      stub.spec = f;
      const std::string spec_json = mmh::bench::toJson(stub).dump();
      const std::string result_path = (fs::path(out_dir) / "flights" / (f.id() + ".json")).string();
      const std::string paths = (fs::path(out_dir) / "paths").string();
      const std::string timeout = std::to_string(timeout_s);
      const pid_t pid = fork();
      if (pid == 0) {
        std::vector<const char*> args = {self.c_str(),   "--worker-spec",     spec_json.c_str(),
                                         "--worker-out", result_path.c_str(), "--paths",
                                         paths.c_str(),  "--timeout",         timeout.c_str()};
        if (!config_path.empty()) {
          args.push_back("--config");
          args.push_back(config_path.c_str());
        }
        for (const std::string& assignment : overrides) {
          args.push_back("--set");
          args.push_back(assignment.c_str());
        }
        args.push_back(nullptr);
        execv(self.c_str(), const_cast<char* const*>(args.data()));
        _exit(127);
      }
      if (pid < 0) {
        std::cerr << "\nmmh-bench: fork failed\n";
        return 1;
      }
      running[pid] = next++;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) break;
    auto it = running.find(pid);
    if (it == running.end()) continue;
    const size_t i = it->second;
    running.erase(it);
    const std::string result_path =
        (fs::path(out_dir) / "flights" / (flights[i].id() + ".json")).string();
    results[i] = readResult(result_path, flights[i]);
    if (WIFSIGNALED(status)) {
      results[i].error = "worker died with signal " + std::to_string(WTERMSIG(status));
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) != 0 && results[i].error.empty()) {
      results[i].error = "worker exited with status " + std::to_string(WEXITSTATUS(status));
    }
    // Every failure says why: `error` (it could not fly) or `reason` (it flew and failed).
    if (!results[i].success && results[i].error.empty() && results[i].reason.empty()) {
      results[i].reason = "failed without a recorded reason";
    }
    if (!results[i].success) ++failed;
    ++done;
    progress(done, flights.size(), elapsed(), failed);
  }
  std::fprintf(stderr, "\n");

  nlohmann::json all = nlohmann::json::array();
  for (const FlightResult& r : results) all.push_back(mmh::bench::toJson(r));
  std::ofstream(fs::path(out_dir) / "results.json") << all.dump(1) << "\n";
  std::ofstream(fs::path(out_dir) / "summary.md")
      << mmh::bench::summaryMarkdown(results, command, elapsed());
  std::cout << "wrote " << (fs::path(out_dir) / "results.json").string() << " and summary.md ("
            << flights.size() << " flights, " << formatDuration(elapsed()) << ")\n\n"
            << mmh::bench::stopCensusMarkdown(results);
  for (const FlightResult& r : results) {
    if (!r.error.empty()) std::cerr << r.spec.id() << ": " << r.error << "\n";
    if (!r.success && r.error.empty()) std::cerr << r.spec.id() << ": " << r.reason << "\n";
  }
  if (!no_plots) {
    const std::string cmd = "/usr/bin/python3 " + std::string(MMH_SOURCE_DIR) +
                            "/tools/bench/plot_bench.py '" + out_dir + "'";
    if (std::system(cmd.c_str()) != 0) std::cerr << "mmh-bench: plotting failed (" << cmd << ")\n";
  }
  return 0;
}
