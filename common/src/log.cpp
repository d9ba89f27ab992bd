#include "mmh/common/log.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <mutex>

namespace mmh {
namespace {

LogLevel g_level = LogLevel::kInfo;
std::string g_service = "mmh";
std::mutex g_mutex;

const char* levelName(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug:
      return "DEBUG";
    case LogLevel::kInfo:
      return "INFO";
    case LogLevel::kWarn:
      return "WARN";
    case LogLevel::kError:
      return "ERROR";
  }
  return "?";
}

}  // namespace

void setLogLevel(LogLevel level) {
  g_level = level;
}
void setLogServiceName(const std::string& name) {
  g_service = name;
}

void logMessage(LogLevel level, const std::string& text) {
  if (level < g_level) return;
  const auto now = std::chrono::system_clock::now();
  const std::time_t secs = std::chrono::system_clock::to_time_t(now);
  const int ms = static_cast<int>(
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000);
  std::tm tm{};
  localtime_r(&secs, &tm);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%H:%M:%S", &tm);
  std::lock_guard<std::mutex> lock(g_mutex);
  std::fprintf(stderr, "%s.%03d %-5s [%s] %s\n", stamp, ms, levelName(level), g_service.c_str(),
               text.c_str());
}

}  // namespace mmh
