#include "replay_report.hpp"

#include <iomanip>

namespace mmh {

void printReplayReport(const std::string& log_path, const std::string& policy,
                       const ReplayResult& r, const DecisionComparison& c, bool list,
                       std::ostream& out) {
  const auto flags = out.flags();
  out << std::fixed << std::setprecision(2);
  out << "log:        " << log_path << " (prefix \"" << r.prefix << "\", policy "
      << (policy.empty() ? "from the config" : policy) << ")\n";
  out << "inputs:     GOAL " << r.goals << ", ODOMETRY " << r.odometry << ", POINTCLOUD "
      << r.pointclouds;
  if (r.undecodable) out << " (" << r.undecodable << " undecodable)";
  out << " of " << r.events << " events, fed in " << r.steps << " lock-step steps: " << r.flight_s
      << " s of flight replayed in " << r.wall_s << " s\n";
  out << "decisions:  recorded " << c.recorded << ", replayed " << c.replayed << "\n";
  out << "matched:    " << c.matched << " (" << std::setprecision(1) << 100.0 * c.matchedShare()
      << " % of recorded" << (c.aligned ? ", in order" : ", index by index") << ")\n"
      << std::setprecision(2);
  out << "differed:   " << c.recorded - c.matched << " recorded only, " << c.replayed - c.matched
      << " replayed only\n";
  out << "commits:    recorded " << commitCounts(r.recorded) << " | replayed "
      << commitCounts(r.replayed) << "\n";
  if (!c.diverged) {
    out << "first divergence: none (the replay took every recorded decision)\n";
  } else {
    const size_t i = c.first_divergence;
    out << "first divergence: decision " << i + 1 << "\n";
    out << "  recorded: " << (i < r.recorded.size() ? r.recorded[i].describe() : "(no more)")
        << "\n";
    if (i < r.recorded.size() && !r.recorded[i].detail.empty())
      out << "            " << r.recorded[i].detail << "\n";
    out << "  replayed: " << (i < r.replayed.size() ? r.replayed[i].describe() : "(no more)")
        << "\n";
    if (i < r.replayed.size() && !r.replayed[i].detail.empty())
      out << "            " << r.replayed[i].detail << "\n";
  }
  if (list) {
    out << "decisions (= both, - recorded only, + replayed only):\n";
    for (const DecisionDiffLine& line : c.diff)
      out << "  " << line.kind << " " << line.decision->describe() << "\n";
  }
  out.flags(flags);
}

}  // namespace mmh
