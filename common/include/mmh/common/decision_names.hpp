// Short names of the arbiter's decision fields (arbiter_status_t triggers and outcomes,
// plan_request_t modes) for the tools that print decisions: mmh-log-summary, mmh-replay.
#pragma once

#include <string>

namespace mmh {

const char* modeName(int mode);        // "-", "FPM", "SOM", "EAM", "STOP" ("?" if unknown)
const char* triggerName(int trigger);  // "none", "initial", "halfway", ... ("?" if unknown)
const char* outcomeName(int outcome);  // "committed", "failed", ... ("?" if unknown)
std::string modesMaskName(int mask);   // bit mask 1 << MODE_*: "SOM+EAM", "-" if none

}  // namespace mmh
