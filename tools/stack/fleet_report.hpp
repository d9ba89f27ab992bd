// mmh-stack --vehicles N (N > 1): flies every vehicle in the one lock-step simulation and prints
// per vehicle the result and planning compute times, plus the process's memory (resident set
// sampled every 10 simulated seconds, and its peak, VmHWM).
#pragma once

#include "stack.hpp"

namespace mmh {

// Exit code: 0 when every vehicle reached its goal without collision, 3 otherwise.
int reportFleet(Stack& stack, bool json);

// Resident set size and its peak (VmRSS, VmHWM of /proc/self/status) in MB; -1 if unknown.
double residentMb();
double peakResidentMb();

}  // namespace mmh
