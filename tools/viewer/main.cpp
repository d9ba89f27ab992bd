// mmh-viewer: the ground station in the browser. Serves the page and a Foxglove WebSocket
// stream of one vehicle's map, state, trajectories, decisions and health (docs/viewer.md).
#include <iostream>

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/common/node_options.hpp"
#include "mmh/viewer/bind_address.hpp"
#include "viewer_node.hpp"

#ifndef MMH_VIEWER_WEB_ROOT
#define MMH_VIEWER_WEB_ROOT ""
#endif

int main(int argc, char** argv) {
  mmh::NodeOptions options;
  std::string bind = "127.0.0.1:8765";
  std::string web_root = MMH_VIEWER_WEB_ROOT;
  mmh::ArgParser parser("mmh-viewer",
                        "Serves the 3D ground-station page and a Foxglove WebSocket stream "
                        "(foxglove.websocket.v1) of one vehicle's LCM channels. No "
                        "authentication: bind to a trusted network only.");
  mmh::addNodeOptions(parser, &options);
  parser.addString("--bind", &bind, "ADDR:PORT to serve HTTP and WebSocket on (127.0.0.1:8765)");
  parser.addString("--web-root", &web_root, "directory of the built page (the build's viewer-web)");
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
    auto lcm = mmh::openLcm(options.lcm_url);
    mmh::ServiceContext ctx(*lcm, "mmh-viewer", options.prefix);
    mmh::viewer::SceneState scene;
    mmh::viewer::ViewerServer server(
        mmh::viewer::viewerChannels(), web_root,
        [&scene](const std::string& topic) { return scene.snapshot(topic); });
    server.listen(address, port);
    mmh::viewer::ViewerNode node(ctx, scene, server);
    const std::string host = address.find(':') == std::string::npos ? address : "[" + address + "]";
    mmh::logInfo("serving http://" + host + ":" + std::to_string(server.port()) + "/");
    const int status = mmh::runNode(
        *lcm, {&ctx}, [&node] { node.poll(); }, 10);
    server.stop();
    return status;
  } catch (const std::exception& e) {
    std::cerr << "mmh-viewer: " << e.what() << "\n";
    return 1;
  }
}
