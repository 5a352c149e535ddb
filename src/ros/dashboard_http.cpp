// Dashboard's HTTP server (cpp-httplib): the page and its assets, /api/snapshot and /api/events.
// Read-only: GET only, no commands.
// The project's headers first: httplib pulls in <resolv.h>, whose `_res` macro breaks Eigen's
// headers (reached through the catalogue's 3-D items) when they come after it.
#include "rocking_monitor/ros/dashboard.hpp"

#include <httplib.h>

namespace rocking_monitor::live {

bool Dashboard::start_server() {
  server_ = std::make_unique<httplib::Server>();
  // Each SSE stream holds one thread for its lifetime: room for max_clients_ streams plus page loads.
  const std::size_t threads = static_cast<std::size_t>(max_clients_) + 4;
  server_->new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  server_->set_keep_alive_max_count(100);

  auto asset = [](const char* body, const char* type) {
    return [body, type](const httplib::Request&, httplib::Response& res) {
      res.set_header("Cache-Control", "no-cache");
      res.set_content(body, type);
    };
  };
  server_->Get("/", asset(kIndexHtml, "text/html; charset=utf-8"));
  server_->Get("/index.html", asset(kIndexHtml, "text/html; charset=utf-8"));
  server_->Get("/app.js", asset(kAppJs, "application/javascript; charset=utf-8"));
  server_->Get("/style.css", asset(kStyleCss, "text/css; charset=utf-8"));
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
