#include "viewer_node.hpp"

#include "scene_channels.hpp"

namespace mmh::viewer {

ViewerNode::ViewerNode(ServiceContext& ctx, SceneState& scene, ViewerServer& server)
    : ctx_(ctx), scene_(scene), server_(server) {
  forEachSceneChannel([this](const char* channel, auto type) {
    using Msg = typename decltype(type)::type;
    ctx_.subscribe(channel, &ViewerNode::on<Msg>, this);
  });
}

void ViewerNode::send(const SceneMessages& messages) {
  for (const SceneMessage& m : messages) server_.publish(m);
}

void ViewerNode::poll() {
  server_.poll();
  const ServerCounters& c = server_.counters();
  ctx_.setCounter("viewer_clients", static_cast<int64_t>(server_.numClients()));
  ctx_.setCounter("viewer_connections", c.connections);
  ctx_.setCounter("viewer_frames_sent", c.frames_sent);
  ctx_.setCounter("viewer_slow_clients_closed", c.slow_clients_closed);
  ctx_.setCounter("viewer_bad_requests", c.bad_requests);
  ctx_.setCounter("viewer_maps_refused", scene_.mapsRefused());
}

}  // namespace mmh::viewer
