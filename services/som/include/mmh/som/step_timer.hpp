// Measures the steps of a SOM plan: wall clock, and CPU time of the calling thread (what a step
// costs when the machine is shared).
#pragma once

#include <chrono>
#include <ctime>

namespace mmh::som {

// Time of one step of a plan() call, microseconds.
struct StepTime {
  double wall_us = 0.0;
  double cpu_us = 0.0;
  StepTime& operator+=(const StepTime& other) {
    wall_us += other.wall_us;
    cpu_us += other.cpu_us;
    return *this;
  }
};

class StepTimer {
 public:
  StepTimer() { restart(); }
  void restart() {
    wall_ = std::chrono::steady_clock::now();
    cpu_ = threadCpuUs();
  }
  // Adds the time since restart() to *out (a step made twice, e.g. a replan, counts both).
  void addTo(StepTime* out) const {
    out->wall_us +=
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - wall_).count();
    out->cpu_us += threadCpuUs() - cpu_;
  }

 private:
  static double threadCpuUs() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e6 + ts.tv_nsec * 1e-3;
  }
  std::chrono::steady_clock::time_point wall_;
  double cpu_ = 0.0;
};

}  // namespace mmh::som
