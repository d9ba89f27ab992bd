// mmh-viewer: the ground station in the browser. Serves the page and a Foxglove WebSocket
// stream of one vehicle's map, state, trajectories, decisions and health (docs/viewer.md), live
// from LCM or, with --log FILE, from a recorded flight with a time slider.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <system_error>
#include <thread>

#include "log_viewer.hpp"
#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/viewer/bind_address.hpp"
#include "viewer_node.hpp"

#ifndef MMH_VIEWER_WEB_ROOT
#define MMH_VIEWER_WEB_ROOT ""
#endif

namespace {

// The page next to the executable as the Debian package installs it (/usr/bin/mmh-viewer,
// /usr/share/mmh-planner/viewer-web), else the build's.
std::string defaultWebRoot() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path installed =
        exe.parent_path().parent_path() / "share" / "mmh-planner" / "viewer-web";
    if (std::filesystem::exists(installed / "index.html", ec)) return installed.string();
  }
  return MMH_VIEWER_WEB_ROOT;
}

std::string urlOf(const std::string& address, uint16_t port) {
  const std::string host = address.find(':') == std::string::npos ? address : "[" + address + "]";
  return "http://" + host + ":" + std::to_string(port) + "/";
}

// Live: the vehicle's LCM channels.
int serveLive(const mmh::NodeOptions& options, const std::string& web_root,
              const std::string& address, uint16_t port) {
  auto lcm = mmh::openLcm(options.lcm_url);
  mmh::ServiceContext ctx(*lcm, "mmh-viewer", options.prefix);
  mmh::viewer::SceneState scene;
  mmh::viewer::ViewerServer server(
      mmh::viewer::viewerChannels(), web_root,
      [&scene](const std::string& topic) { return scene.snapshot(topic); });
  server.listen(address, port);
  mmh::viewer::ViewerNode node(ctx, scene, server);
  mmh::logInfo("serving " + urlOf(address, server.port()));
  const int status = mmh::runNode(
      *lcm, {&ctx}, [&node] { node.poll(); }, 10);
  server.stop();
  return status;
}

// A recorded flight: no LCM at all (nothing is published), the log's messages of the prefix.
int serveLog(const mmh::NodeOptions& options, const std::string& log_path,
             const std::string& web_root, const std::string& address, uint16_t port) {
  mmh::viewer::LogReadStats stats;
  mmh::viewer::ScenePlayback playback(mmh::viewer::readFlightLog(log_path, options.prefix, &stats));
  if (playback.numMessages() == 0)
    throw std::runtime_error(log_path + " has no messages of the vehicle's channels (prefix '" +
                             options.prefix + "')");
  mmh::viewer::LogViewer* log_viewer = nullptr;
  mmh::viewer::ViewerServer server(
      mmh::viewer::viewerChannels(true), web_root,
      [&log_viewer](const std::string& topic) { return log_viewer->snapshot(topic); });
  mmh::viewer::LogViewer viewer(playback, server);
  log_viewer = &viewer;
  server.setParameterHandler(
      [&viewer](const nlohmann::json& parameters) { return viewer.onParameters(parameters); });
  server.listen(address, port);
  char span[32];
  std::snprintf(span, sizeof(span), "%.2f s",
                1e-6 * static_cast<double>(playback.endUtime() - playback.startUtime()));
  mmh::logInfo(log_path + ": " + std::to_string(stats.used) + " of " +
               std::to_string(stats.events) + " messages (" + std::to_string(stats.rejected) +
               " refused), " + span + " of flight");
  mmh::logInfo("serving " + urlOf(address, server.port()));
  mmh::installStopHandlers();
  while (!mmh::stopRequested()) {
    server.poll();
    viewer.poll(mmh::wallTimeUs());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  server.stop();
  mmh::logInfo("stopped cleanly");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  std::string bind = "127.0.0.1:8765";
  std::string web_root = defaultWebRoot();
  std::string log_path;
  mmh::ArgParser parser("mmh-viewer",
                        "Serves the 3D ground-station page and a Foxglove WebSocket stream "
                        "(foxglove.websocket.v1) of one vehicle's LCM channels, live or from a "
                        "recorded LCM log (--log). No authentication: bind to a trusted network "
                        "only.");
  mmh::addNodeOptions(parser, &options);
  parser.addString("--bind", &bind, "ADDR:PORT to serve HTTP and WebSocket on (127.0.0.1:8765)");
  parser.addString("--web-root", &web_root,
                   "directory of the built page (the package's /usr/share/mmh-planner/viewer-web, "
                   "else the build's viewer-web)");
  parser.addString("--log", &log_path,
                   "serve this recorded flight (lcm-logger or mmh-stack --log) with a time "
                   "slider instead of the live channels");
  int code = 0;
  if (!parser.parse(argc, argv, &code)) return code;
  mmh::setLogServiceName("mmh-viewer");
  std::string address;
  uint16_t port = 0;
  if (!mmh::viewer::parseBindAddress(bind, &address, &port)) {
    std::cerr << "mmh-viewer: --bind '" << bind << "' is not ADDR:PORT\n";
    return 1;
  }
  try {
    mmh::loadNodeConfig(options);
    if (!log_path.empty()) return serveLog(options, log_path, web_root, address, port);
    return serveLive(options, web_root, address, port);
  } catch (const std::exception& e) {
    std::cerr << "mmh-viewer: " << e.what() << "\n";
    return 1;
  }
}
