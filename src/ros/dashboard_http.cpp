// Dashboard's HTTP server (cpp-httplib): the page and its assets, /api/snapshot and /api/events.
// Read-only: GET only, no commands.
// The project's headers first: httplib pulls in <resolv.h>, whose `_res` macro breaks Eigen's
// headers (reached through the catalogue's 3-D items) when they come after it.
#include "rocking_monitor/ros/dashboard.hpp"

#include <httplib.h>

namespace rocking_monitor::live {
namespace {

// An integer parameter within [lo, hi]; false (after a ROS_FATAL naming it, its unit and its range)
// when it has another type or lies outside.
bool int_param(const ::ros::NodeHandle& pnh, const char* name, int lo, int hi, const char* unit, int& out) {
  XmlRpc::XmlRpcValue v;
  if (pnh.getParam(name, v)) {
    if (v.getType() != XmlRpc::XmlRpcValue::TypeInt) {
      ROS_FATAL("dashboard: parameter ~%s has the wrong type (expected an integer, %s)", name, unit);
      return false;
    }
    out = static_cast<int>(v);
  }
  if (out < lo || out > hi) {
    ROS_FATAL("dashboard: ~%s = %d %s must be in [%d, %d]", name, out, unit, lo, hi);
    return false;
  }
  return true;
}

// Issue 54: no client may hold a pool thread or memory without bound. cpp-httplib 0.11.4 (Debian 12)
// gives each connection one pool thread while it is open, so idle keep-alive connections are closed
// after keep_alive_timeout_s. It checks Content-Length bodies against the payload limit (413, the
// body discarded as read, never stored), but reads a chunked body, or a POST without a length until the
// peer closes, into memory without any limit: those are refused before the library reads them.
void set_limits(httplib::Server& server, int keep_alive_timeout_s, int keep_alive_max_requests, int read_timeout_s,
                int max_request_body_bytes) {
  server.set_keep_alive_timeout(keep_alive_timeout_s);
  server.set_keep_alive_max_count(static_cast<std::size_t>(keep_alive_max_requests));
  server.set_read_timeout(read_timeout_s, 0);
  server.set_payload_max_length(static_cast<std::size_t>(max_request_body_bytes));
  server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response& res) {
    const bool reads_body = req.method == "POST" || req.method == "PUT" || req.method == "PATCH" || req.method == "PRI";
    if (req.has_header("Transfer-Encoding") || (reads_body && !req.has_header("Content-Length"))) {
      res.status = 411;  // Length Required: a body's size must be known before it is read
      res.set_content("a request body needs Content-Length (its size is checked before it is read)\n", "text/plain");
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
}

}  // namespace

bool Dashboard::load_server_limits() {
  return int_param(pnh_, "keep_alive_timeout_s", 1, 3600, "s", keep_alive_timeout_s_) &&
         int_param(pnh_, "keep_alive_max_requests", 1, 100000, "requests", keep_alive_max_requests_) &&
         int_param(pnh_, "read_timeout_s", 1, 3600, "s", read_timeout_s_) &&
         int_param(pnh_, "max_request_body_bytes", 0, 64 << 20, "bytes", max_request_body_bytes_);
}

bool Dashboard::start_server() {
  server_ = std::make_unique<httplib::Server>();
  // Each SSE stream holds one thread for its lifetime: room for max_clients_ streams plus page loads.
  const std::size_t threads = static_cast<std::size_t>(max_clients_) + 4;
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  set_limits(*server_, keep_alive_timeout_s_, keep_alive_max_requests_, read_timeout_s_, max_request_body_bytes_);

  auto asset = [](const char* body, const char* type) {
    return [body, type](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      res.set_content(body, type);
    };
  };
  server_->Get("/", asset(kWebAssets[0].body, kWebAssets[0].type));  // index.html
  for (std::size_t i = 0; i < kWebAssetCount; ++i)
    server_->Get(kWebAssets[i].path, asset(kWebAssets[i].body, kWebAssets[i].type));
  server_->Get("/api/snapshot", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(snapshot_json(), "application/json");
  });
  server_->Get("/api/item", [this](const httplib::Request& req, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    std::string body = item_json(req.get_param_value("id"));
    if (body.empty()) {
      res.status = 404;
      res.set_content("{\"error\":\"no such item\"}", "application/json");
      return;
    }
    res.set_content(body, "application/json");
  });
  server_->Get("/api/history", [this](const httplib::Request& req, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(history_json(req.get_param_value("id")), "application/json");
  });
  server_->Get("/api/input", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    res.set_content(input_json(), "application/json");
  });
  server_->Get("/api/events", [this](const httplib::Request&, httplib::Response& res) {
    const std::uint64_t id = add_client();
    if (id == 0) {
      res.status = 503;
      res.set_content("too many live connections (~max_clients)\n", "text/plain");
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Accel-Buffering", "no");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, id](std::size_t, httplib::DataSink& sink) {
          std::string frames;
          if (!next_frames(id, std::chrono::milliseconds(1000), frames)) return false;
          if (frames.empty()) frames = ": keep-alive\n\n";  // also finds a closed connection within 1 s
          return sink.write(frames.data(), frames.size());
        },
        [this, id](bool) { remove_client(id); });
  });

  const int port = port_ == 0 ? server_->bind_to_any_port(bind_address_)
                              : (server_->bind_to_port(bind_address_, port_) ? port_ : -1);
  if (port <= 0) {
    ROS_FATAL("dashboard: cannot listen on %s:%d (address not local, or port in use: set ~port)",
              bind_address_.c_str(), port_);
    return false;
  }
  url_ = "http://" + bind_address_ + ":" + std::to_string(port) + "/";
  server_thread_ = std::thread([this] { server_->listen_after_bind(); });
  return true;
}

void Dashboard::stop_server() {
  {
    std::lock_guard<std::mutex> lock(clients_mutex_);
    stopping_ = true;  // wakes and ends every SSE stream
  }
  clients_cv_.notify_all();
  if (server_) server_->stop();  // closes the listening socket: the port is free when we exit
  if (server_thread_.joinable()) server_thread_.join();
}

}  // namespace rocking_monitor::live
