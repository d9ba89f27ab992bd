// HTTP and WebSocket on one port (websocketpp on standalone Asio): GET / serves the page's files
// from the web root; a WebSocket with the foxglove.websocket.v1 subprotocol gets the channels
// advertised, and on each subscription first that channel's snapshot, then its live messages.
// Single-threaded: poll() runs whatever the sockets have ready and returns.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "mmh/viewer/channel_schemas.hpp"
#include "mmh/viewer/scene_state.hpp"

namespace mmh::viewer {

struct ServerCounters {
  int64_t connections = 0;  // WebSocket clients accepted
  int64_t http_requests = 0;
  int64_t frames_sent = 0;
  int64_t slow_clients_closed = 0;  // clients that fell too far behind
  int64_t bad_requests = 0;         // malformed client frames
};

class ViewerServer {
 public:
  using SnapshotSource = std::function<SceneMessages(const std::string& topic)>;
  // Takes the parameters a client sets (a JSON array of {name, value}; empty for getParameters)
  // and returns every parameter's current value in the same form.
  using ParameterHandler = std::function<nlohmann::json(const nlohmann::json& parameters)>;

  ViewerServer(std::vector<ChannelInfo> channels, std::string web_root, SnapshotSource snapshot);
  ~ViewerServer();
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  // Listens on address:port (port 0: any free port); throws std::runtime_error if it cannot.
  void listen(const std::string& address, uint16_t port);
  uint16_t port() const;
  void poll();
  void stop();

  // With a handler the server offers the "parameters" capability (mmh-viewer --log); set before
  // listen().
  void setParameterHandler(ParameterHandler handler);

  // Sends the message to every client subscribed to its topic.
  void publish(const SceneMessage& message);
  // Sends every client the snapshot of each channel it subscribes to but except_topic (after the
  // scene jumped).
  void resendSnapshots(const std::string& except_topic = "");
  size_t numClients() const;
  const ServerCounters& counters() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mmh::viewer
