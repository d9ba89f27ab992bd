// mmh-viewer's node: subscribes to one vehicle's channels, feeds the scene state and sends the
// resulting scene messages to the server's clients. Its HEARTBEAT counters: viewer_clients
// (connected now), viewer_connections, viewer_frames_sent, viewer_slow_clients_closed,
// viewer_bad_requests, viewer_maps_refused.
#pragma once

#include "mmh/common/lcm_runtime.hpp"
#include "mmh/viewer/scene_state.hpp"
#include "viewer_server.hpp"

namespace mmh::viewer {

class ViewerNode {
 public:
  ViewerNode(ServiceContext& ctx, SceneState& scene, ViewerServer& server);
  // Serves the sockets and copies the server's counters into the HEARTBEAT counters.
  void poll();

 private:
  void send(const SceneMessages& messages);
  template <class Msg>
  void on(const Msg& msg) {
    send(scene_.apply(msg));
  }

  ServiceContext& ctx_;
  SceneState& scene_;
  ViewerServer& server_;
};

}  // namespace mmh::viewer
