#include "fleet_report.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace mmh {
namespace {

double statusFieldMb(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(field + ":", 0) == 0) {
      std::istringstream is(line.substr(field.size() + 1));
      double kb = -1;
      is >> kb;
      return kb / 1024.0;
    }
  }
  return -1;
}

// Nearest-rank percentile of a sorted list (0 when empty).
double percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return 0.0;
  const size_t rank = static_cast<size_t>(std::ceil(p / 100.0 * sorted.size()));
  return sorted[std::min(sorted.size() - 1, rank > 0 ? rank - 1 : 0)];
}

}  // namespace

double residentMb() {
  return statusFieldMb("VmRSS");
}
double peakResidentMb() {
  return statusFieldMb("VmHWM");
}

int reportFleet(Stack& stack, bool json) {
  std::vector<double> rss_mb;
  int seconds = 0;
  const auto records = stack.flyAll([&](double) {
    if (seconds++ % 10 == 0) rss_mb.push_back(residentMb());
  });
  rss_mb.push_back(residentMb());
  std::vector<double> all_ms;
  int ok = 0;
  double wall = 0;
  std::ostringstream vehicles;
  for (size_t i = 0; i < records.size(); ++i) {
    const FlightRecord& r = records[i];
    std::vector<double> ms;
    for (const auto& c : r.calls) ms.push_back(c.compute_ms);
    std::sort(ms.begin(), ms.end());
    all_ms.insert(all_ms.end(), ms.begin(), ms.end());
    ok += r.success() ? 1 : 0;
    wall = std::max(wall, r.wall_time_s);
    const std::string prefix = stack.vehiclePrefix(static_cast<int>(i));
    if (json) {
      vehicles << (i ? ", " : "") << "{\"prefix\": \"" << prefix << "\", \"result\": \""
               << r.end_reason << "\", \"flight_time_s\": " << r.metrics.flight_time_s
               << ", \"iterations\": " << r.calls.size()
               << ", \"compute_ms_p50\": " << percentile(ms, 50)
               << ", \"compute_ms_p99\": " << percentile(ms, 99)
               << ", \"compute_ms_max\": " << (ms.empty() ? 0.0 : ms.back()) << "}";
    } else {
      std::cout << prefix << ": " << r.end_reason << ", flight " << r.metrics.flight_time_s
                << " s, " << r.calls.size() << " planning calls, compute p50 " << percentile(ms, 50)
                << " ms, p99 " << percentile(ms, 99) << " ms\n";
    }
  }
  std::sort(all_ms.begin(), all_ms.end());
  const double peak = peakResidentMb();
  if (json) {
    std::cout << "{\"vehicles\": [" << vehicles.str() << "], \"succeeded\": " << ok
              << ", \"compute_ms_p50\": " << percentile(all_ms, 50)
              << ", \"compute_ms_p90\": " << percentile(all_ms, 90)
              << ", \"compute_ms_p99\": " << percentile(all_ms, 99) << ", \"rss_mb\": [";
    for (size_t i = 0; i < rss_mb.size(); ++i) std::cout << (i ? ", " : "") << rss_mb[i];
    std::cout << "], \"peak_rss_mb\": " << peak << ", \"wall_time_s\": " << wall << "}\n";
  } else {
    std::cout << "vehicles:      " << ok << " of " << records.size() << " reached\n"
              << "compute:       p50 " << percentile(all_ms, 50) << " ms, p90 "
              << percentile(all_ms, 90) << " ms, p99 " << percentile(all_ms, 99) << " ms\n"
              << "memory:        peak " << peak << " MB, resident every 10 s:";
    for (double m : rss_mb) std::cout << " " << m;
    std::cout << " MB\n"
              << "wall time:     " << wall << " s\n";
  }
  return ok == static_cast<int>(records.size()) ? 0 : 3;
}

}  // namespace mmh
