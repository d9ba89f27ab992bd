#include "viewer_server.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

#include "mmh/common/log.hpp"
#include "mmh/viewer/foxglove_protocol.hpp"

namespace mmh::viewer {
namespace {
using WsServer = websocketpp::server<websocketpp::config::asio>;
using websocketpp::connection_hdl;

// A client that has this much queued and unsent is closed rather than buffered without bound.
constexpr size_t kMaxBufferedBytes = 32u << 20;

struct PageFile {
  const char* file;
  const char* content_type;
};
// The only files the page consists of; nothing else under the web root is served.
const std::map<std::string, PageFile>& pageFiles() {
  static const std::map<std::string, PageFile> files = {
      {"/", {"index.html", "text/html; charset=utf-8"}},
      {"/index.html", {"index.html", "text/html; charset=utf-8"}},
      {"/viewer.js", {"viewer.js", "text/javascript; charset=utf-8"}},
      {"/viewer.js.map", {"viewer.js.map", "application/json"}},
      {"/viewer.css", {"viewer.css", "text/css; charset=utf-8"}},
  };
  return files;
}

const char* kPageMissing =
    "<!doctype html><title>mmh-viewer</title><p>The page is not built: run deploy/setup.sh "
    "(it needs Node.js and npm), or give mmh-viewer --web-root DIR.";
}  // namespace

class ViewerServer::Impl {
 public:
  Impl(std::vector<ChannelInfo> channels, std::string web_root, SnapshotSource snapshot)
      : channels_(std::move(channels)),
        web_root_(std::move(web_root)),
        snapshot_(std::move(snapshot)) {
    for (const ChannelInfo& c : channels_) topic_of_channel_[c.id] = c.topic;
    server_.clear_access_channels(websocketpp::log::alevel::all);
    server_.clear_error_channels(websocketpp::log::elevel::all);
    server_.init_asio();
    server_.set_reuse_addr(true);
    server_.set_validate_handler([this](connection_hdl h) { return validate(h); });
    server_.set_open_handler([this](connection_hdl h) { onOpen(h); });
    server_.set_close_handler([this](connection_hdl h) { clients_.erase(h); });
    server_.set_fail_handler([this](connection_hdl h) { clients_.erase(h); });
    server_.set_message_handler(
        [this](connection_hdl h, WsServer::message_ptr m) { onMessage(h, m); });
    server_.set_http_handler([this](connection_hdl h) { onHttp(h); });
  }

  void listen(const std::string& address, uint16_t port) {
    websocketpp::lib::error_code ec;
    const asio::ip::address ip = asio::ip::make_address(address, ec);
    if (ec) throw std::runtime_error("bad bind address '" + address + "': " + ec.message());
    server_.listen(asio::ip::tcp::endpoint(ip, port), ec);
    if (ec)
      throw std::runtime_error("cannot listen on " + address + ":" + std::to_string(port) + ": " +
                               ec.message());
    server_.start_accept(ec);
    if (ec) throw std::runtime_error("cannot accept connections: " + ec.message());
  }

  uint16_t port() {
    websocketpp::lib::error_code ec;
    const auto endpoint = server_.get_local_endpoint(ec);
    return ec ? 0 : endpoint.port();
  }

  void poll() { server_.poll(); }

  void stop() {
    websocketpp::lib::error_code ec;
    server_.stop_listening(ec);
    for (auto& [hdl, client] : clients_)
      server_.close(hdl, websocketpp::close::status::going_away, "mmh-viewer stopping", ec);
    clients_.clear();
    server_.poll();
  }

  void publish(const SceneMessage& message) {
    std::string payload;  // encoded once, only if someone listens
    std::vector<connection_hdl> too_slow;
    for (auto& [hdl, client] : clients_) {
      for (const auto& [subscription, channel] : client.subscriptions) {
        if (topic_of_channel_[channel] != message.topic) continue;
        if (payload.empty()) payload = message.payload.dump();
        if (!send(hdl, subscription, message.utime, payload)) too_slow.push_back(hdl);
      }
    }
    for (const connection_hdl& hdl : too_slow) closeSlow(hdl);
  }

  void resendSnapshots(const std::string& except_topic) {
    for (auto& [hdl, client] : clients_) {
      for (const auto& [subscription, channel] : client.subscriptions) {
        if (topic_of_channel_[channel] != except_topic) sendSnapshot(hdl, subscription, channel);
      }
    }
  }

  size_t numClients() const { return clients_.size(); }
  ServerCounters counters;
  ParameterHandler parameter_handler;

 private:
  struct Client {
    std::map<uint32_t, uint32_t> subscriptions;  // subscription id -> channel id
  };

  bool validate(connection_hdl hdl) {
    WsServer::connection_ptr con = server_.get_con_from_hdl(hdl);
    for (const std::string& p : con->get_requested_subprotocols()) {
      if (p == foxglove::kSubprotocol) {
        con->select_subprotocol(p);
        return true;
      }
    }
    logWarn(std::string("refused a WebSocket without the ") + foxglove::kSubprotocol +
            " subprotocol");
    return false;
  }

  void onOpen(connection_hdl hdl) {
    clients_[hdl] = Client{};
    ++counters.connections;
    const std::string session = std::to_string(counters.connections);
    std::vector<std::string> capabilities;
    if (parameter_handler) capabilities.push_back("parameters");
    sendText(hdl, foxglove::serverInfo("mmh-viewer", session, capabilities));
    sendText(hdl, foxglove::advertise(channels_));
  }

  void onMessage(connection_hdl hdl, WsServer::message_ptr msg) {
    auto it = clients_.find(hdl);
    if (it == clients_.end() || msg->get_opcode() != websocketpp::frame::opcode::text) return;
    const foxglove::ClientRequest request = foxglove::parseClientRequest(msg->get_payload());
    switch (request.kind) {
      case foxglove::ClientRequest::Kind::kSubscribe:
        for (const auto& [subscription, channel] : request.subscriptions) {
          if (!topic_of_channel_.count(channel)) {
            sendText(hdl, foxglove::status(foxglove::StatusLevel::kWarning,
                                           "no channel " + std::to_string(channel)));
            continue;
          }
          it->second.subscriptions[subscription] = channel;
          sendSnapshot(hdl, subscription, channel);
        }
        break;
      case foxglove::ClientRequest::Kind::kSetParameters:
      case foxglove::ClientRequest::Kind::kGetParameters:
        if (!parameter_handler) {
          sendText(hdl, foxglove::status(foxglove::StatusLevel::kWarning, "no parameters here"));
          break;
        }
        {
          const nlohmann::json values = parameter_handler(request.parameters);
          // The protocol answers a get, and a set that carries an id.
          if (!request.id.empty() || request.kind == foxglove::ClientRequest::Kind::kGetParameters)
            sendText(hdl, foxglove::parameterValues(values, request.id));
        }
        break;
      case foxglove::ClientRequest::Kind::kUnsubscribe:
        for (uint32_t subscription : request.unsubscribed)
          it->second.subscriptions.erase(subscription);
        break;
      case foxglove::ClientRequest::Kind::kMalformed:
        ++counters.bad_requests;
        sendText(hdl, foxglove::status(foxglove::StatusLevel::kError,
                                       "malformed request: " + request.error));
        break;
      case foxglove::ClientRequest::Kind::kIgnored:
        break;
    }
  }

  void sendSnapshot(connection_hdl hdl, uint32_t subscription, uint32_t channel) {
    for (const SceneMessage& m : snapshot_(topic_of_channel_[channel]))
      send(hdl, subscription, m.utime, m.payload.dump());
  }

  void onHttp(connection_hdl hdl) {
    ++counters.http_requests;
    WsServer::connection_ptr con = server_.get_con_from_hdl(hdl);
    std::string resource = con->get_resource();
    resource = resource.substr(0, resource.find('?'));
    const auto file = pageFiles().find(resource);
    if (file == pageFiles().end()) {
      con->set_status(websocketpp::http::status_code::not_found);
      con->set_body("not found\n");
      return;
    }
    std::ifstream in(web_root_ + "/" + file->second.file, std::ios::binary);
    if (!in) {
      con->set_status(resource == "/" ? websocketpp::http::status_code::ok
                                      : websocketpp::http::status_code::not_found);
      con->append_header("Content-Type", "text/html; charset=utf-8");
      con->set_body(kPageMissing);
      return;
    }
    std::ostringstream body;
    body << in.rdbuf();
    con->set_status(websocketpp::http::status_code::ok);
    con->append_header("Content-Type", file->second.content_type);
    con->append_header("Cache-Control", "no-cache");
    con->set_body(body.str());
  }

  void sendText(connection_hdl hdl, const std::string& text) {
    websocketpp::lib::error_code ec;
    server_.send(hdl, text, websocketpp::frame::opcode::text, ec);
  }

  // False if the client is too far behind to take more.
  bool send(connection_hdl hdl, uint32_t subscription, int64_t utime, const std::string& payload) {
    websocketpp::lib::error_code ec;
    WsServer::connection_ptr con = server_.get_con_from_hdl(hdl, ec);
    if (ec) return true;  // already gone; the close handler forgets it
    if (con->get_buffered_amount() > kMaxBufferedBytes) return false;
    const uint64_t timestamp_ns = utime > 0 ? static_cast<uint64_t>(utime) * 1000u : 0u;
    con->send(foxglove::messageData(subscription, timestamp_ns, payload),
              websocketpp::frame::opcode::binary);
    ++counters.frames_sent;
    return true;
  }

  void closeSlow(connection_hdl hdl) {
    ++counters.slow_clients_closed;
    logWarn("closing a WebSocket client that fell more than 32 MB behind");
    websocketpp::lib::error_code ec;
    server_.close(hdl, websocketpp::close::status::try_again_later, "too slow", ec);
    clients_.erase(hdl);
  }

  std::vector<ChannelInfo> channels_;
  std::map<uint32_t, std::string> topic_of_channel_;
  std::string web_root_;
  SnapshotSource snapshot_;
  WsServer server_;
  std::map<connection_hdl, Client, std::owner_less<connection_hdl>> clients_;
};

ViewerServer::ViewerServer(std::vector<ChannelInfo> channels, std::string web_root,
                           SnapshotSource snapshot)
    : impl_(std::make_unique<Impl>(std::move(channels), std::move(web_root), std::move(snapshot))) {
}
ViewerServer::~ViewerServer() = default;
void ViewerServer::listen(const std::string& address, uint16_t port) {
  impl_->listen(address, port);
}
uint16_t ViewerServer::port() const {
  return impl_->port();
}
void ViewerServer::poll() {
  impl_->poll();
}
void ViewerServer::stop() {
  impl_->stop();
}
void ViewerServer::setParameterHandler(ParameterHandler handler) {
  impl_->parameter_handler = std::move(handler);
}
void ViewerServer::publish(const SceneMessage& message) {
  impl_->publish(message);
}
void ViewerServer::resendSnapshots(const std::string& except_topic) {
  impl_->resendSnapshots(except_topic);
}
size_t ViewerServer::numClients() const {
  return impl_->numClients();
}
const ServerCounters& ViewerServer::counters() const {
  return impl_->counters;
}

}  // namespace mmh::viewer
