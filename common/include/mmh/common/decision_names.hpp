// Short names of the arbiter's decision fields (arbiter_status_t triggers and outcomes,
// plan_request_t modes) and of heartbeat_t states, for the tools that print them: mmh-log-summary,
// mmh-replay, mmh-top, mmh-viewer.
#pragma once

#include <string>

namespace mmh {

const char* modeName(int mode);        // "-", "FPM", "SOM", "EAM", "STOP" ("?" if unknown)
const char* triggerName(int trigger);  // "none", "initial", "halfway", ... ("?" if unknown)
const char* outcomeName(int outcome);  // "committed", "failed", ... ("?" if unknown)
std::string modesMaskName(int mask);
const char* heartbeatStateName(int state);  // "STARTING", "OK", "DEGRADED", "STOPPING" ("?")   //
                                            // bit mask 1 << MODE_*: "SOM+EAM", "-" if none

}  // namespace mmh
