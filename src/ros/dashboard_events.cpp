// Dashboard's Server-Sent-Events push: ROS threads format a frame once and append it to every
// client's queue (never waiting on a socket); each client's HTTP thread takes its frames and writes.
#include "rocking_monitor/ros/dashboard.hpp"

namespace rocking_monitor::live {
namespace {

// A client this far behind (a stalled browser tab) is told to reload the snapshot instead of being
// fed an ever-growing queue: memory stays bounded whatever the client does.
constexpr std::size_t kMaxQueuedFrames = 256;

}  // namespace

void Dashboard::publish_event(const std::string& event, const std::string& data) {
  std::string frame = "event: " + event + "\ndata: " + data + "\n\n";  // data is one-line JSON
  {
    std::lock_guard<std::mutex> lock(clients_mutex_);
    if (clients_.empty()) return;
    for (auto& [id, c] : clients_) {
      if (c.overflowed) continue;
      if (c.queue.size() >= kMaxQueuedFrames) {
        c.queue.clear();
        c.overflowed = true;
        continue;
      }
      c.queue.push_back(frame);
    }
  }
  clients_cv_.notify_all();
}

std::uint64_t Dashboard::add_client() {
  std::lock_guard<std::mutex> lock(clients_mutex_);
  if (stopping_ || clients_.size() >= static_cast<std::size_t>(max_clients_)) return 0;
  const std::uint64_t id = next_client_++;
  clients_[id] = Client{};
  // First frame: the page knows the stream is live and fetches the snapshot after it.
  clients_[id].queue.push_back("retry: 2000\nevent: hello\ndata: {}\n\n");
  return id;
}

void Dashboard::remove_client(std::uint64_t id) {
  std::lock_guard<std::mutex> lock(clients_mutex_);
  clients_.erase(id);
}

bool Dashboard::next_frames(std::uint64_t id, std::chrono::milliseconds wait, std::string& out) {
  out.clear();
  std::unique_lock<std::mutex> lock(clients_mutex_);
  auto ready = [&] {
    if (stopping_) return true;
    const auto it = clients_.find(id);
    return it == clients_.end() || it->second.overflowed || !it->second.queue.empty();
  };
  clients_cv_.wait_for(lock, wait, ready);
  if (stopping_) return false;
  const auto it = clients_.find(id);
  if (it == clients_.end()) return false;
  Client& c = it->second;
  if (c.overflowed) {
    c.overflowed = false;
    out = "event: catalogue\ndata: {\"reason\":\"lagging\"}\n\n";  // reload the snapshot
    return true;
  }
  while (!c.queue.empty()) {
    out += c.queue.front();
    c.queue.pop_front();
  }
  return true;
}

}  // namespace rocking_monitor::live
