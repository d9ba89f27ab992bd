#include "viewer_node.hpp"

namespace mmh::viewer {

ViewerNode::ViewerNode(ServiceContext& ctx, SceneState& scene, ViewerServer& server)
    : ctx_(ctx), scene_(scene), server_(server) {
  namespace ch = channels;
  ctx.subscribe(ch::kLocalMap, &ViewerNode::on<local_map_t, &SceneState::onLocalMap>, this);
  ctx.subscribe(ch::kOdometry, &ViewerNode::on<odometry_t, &SceneState::onOdometry>, this);
  ctx.subscribe(ch::kTrajectory, &ViewerNode::on<trajectory_t, &SceneState::onTrajectory>, this);
  ctx.subscribe(ch::kAwareness, &ViewerNode::on<awareness_t, &SceneState::onAwareness>, this);
  for (const char* request : {ch::kPlanRequestFpm, ch::kPlanRequestSom, ch::kPlanRequestEam})
    ctx.subscribe(request, &ViewerNode::on<plan_request_t, &SceneState::onPlanRequest>, this);
  ctx.subscribe(ch::kPlanResult, &ViewerNode::on<plan_result_t, &SceneState::onPlanResult>, this);
  ctx.subscribe(ch::kArbiterStatus, &ViewerNode::on<arbiter_status_t, &SceneState::onArbiterStatus>,
                this);
  ctx.subscribe(ch::kHeartbeat, &ViewerNode::on<heartbeat_t, &SceneState::onHeartbeat>, this);
  ctx.subscribe(ch::kMissionStatus, &ViewerNode::on<mission_status_t, &SceneState::onMissionStatus>,
                this);
}

void ViewerNode::send(const SceneMessages& messages) {
  for (const SceneMessage& m : messages) server_.publish(m);
}

void ViewerNode::poll() {
  server_.poll();
  const ServerCounters& c = server_.counters();
  const auto set = [this](const std::string& name, int64_t value) {
    ctx_.increment(name, value - ctx_.counter(name));
  };
  set("viewer_clients", static_cast<int64_t>(server_.numClients()));
  set("viewer_connections", c.connections);
  set("viewer_frames_sent", c.frames_sent);
  set("viewer_slow_clients_closed", c.slow_clients_closed);
  set("viewer_bad_requests", c.bad_requests);
  set("viewer_maps_refused", scene_.mapsRefused());
}

}  // namespace mmh::viewer
