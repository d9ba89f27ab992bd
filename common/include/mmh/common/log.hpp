// Minimal leveled logging to stderr with the service name and wall-clock time, and a limiter
// so that a flood of bad input cannot flood the log.
#pragma once

#include <cstdint>
#include <string>

namespace mmh {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

void setLogLevel(LogLevel level);
void setLogServiceName(const std::string& name);
void logMessage(LogLevel level, const std::string& text);

inline void logInfo(const std::string& text) {
  logMessage(LogLevel::kInfo, text);
}
inline void logWarn(const std::string& text) {
  logMessage(LogLevel::kWarn, text);
}
inline void logError(const std::string& text) {
  logMessage(LogLevel::kError, text);
}
inline void logDebug(const std::string& text) {
  logMessage(LogLevel::kDebug, text);
}

// Logs at most `burst` messages per key, then one in every `every` (with the count suppressed).
class LogLimiter {
 public:
  LogLimiter(int burst = 5, int every = 100) : burst_(burst), every_(every) {}
  bool shouldLog() { return ++count_ <= burst_ || (count_ - burst_) % every_ == 0; }
  int64_t count() const { return count_; }

 private:
  int burst_, every_;
  int64_t count_ = 0;
};

}  // namespace mmh
