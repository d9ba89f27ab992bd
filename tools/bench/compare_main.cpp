// mmh-bench-compare: the paired comparison of two mmh-bench runs (see bench_compare.hpp).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "bench_compare.hpp"
#include "mmh/common/cli.hpp"

namespace {

// A run is its --out directory or its results.json.
std::vector<mmh::bench::FlightResult> readRun(const std::string& path) {
  std::filesystem::path file(path);
  if (std::filesystem::is_directory(file)) file /= "results.json";
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  const nlohmann::json j = nlohmann::json::parse(in);
  if (!j.is_array()) throw std::runtime_error(file.string() + " is not a list of flights");
  std::vector<mmh::bench::FlightResult> flights;
  for (const auto& f : j) flights.push_back(mmh::bench::fromJson(f));
  return flights;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> runs;
  std::string out_path;
  double confidence = 0.95;
  int resamples = 10000;
  mmh::ArgParser parser(
      "mmh-bench-compare",
      "Compares two mmh-bench runs flight by flight (the same forests and "
      "noise seeds): per method and density, the change of time / bound with "
      "a bootstrap interval, stops, success, energy and iterations, as Markdown.");
  parser.addPositional("BASELINE CANDIDATE", &runs,
                       "two --out directories of mmh-bench (or their results.json)");
  parser.addString("--out", &out_path, "write the Markdown here instead of standard output");
  parser.addDouble("--confidence", &confidence, "confidence of the interval (0.5-0.999)");
  parser.addInt("--resamples", &resamples, "bootstrap resamples (100-1000000)");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  if (runs.size() != 2) {
    std::cerr << "mmh-bench-compare: give two runs, the baseline and the candidate (got "
              << runs.size() << ")\n";
    return 2;
  }
  if (!(confidence >= 0.5 && confidence <= 0.999) || resamples < 100 || resamples > 1000000) {
    std::cerr << "mmh-bench-compare: --confidence must lie in [0.5, 0.999] and --resamples in "
                 "[100, 1000000]\n";
    return 2;
  }
  try {
    const auto comparison =
        mmh::bench::comparePaired(readRun(runs[0]), readRun(runs[1]), confidence, resamples);
    if (comparison.groups.empty()) {
      std::cerr << "mmh-bench-compare: the two runs have no flight in common (different "
                   "--seed, --densities order, world or start and goal?)\n";
      return 1;
    }
    const std::string md = mmh::bench::comparisonMarkdown(comparison, runs[0], runs[1], confidence);
    if (out_path.empty()) {
      std::cout << md;
    } else {
      std::ofstream(out_path) << md;
    }
  } catch (const std::exception& e) {
    std::cerr << "mmh-bench-compare: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
