// SampleHistoryServer (see include/rocking_monitor/ros/sample_history_server.hpp).
#include "rocking_monitor/ros/sample_history_server.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rocking_monitor::live {

double read_history_length(const ros::NodeHandle& pnh) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam("history_length", v)) return kDefaultHistoryLength;
  double s = 0.0;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) s = static_cast<double>(v);
  else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) s = static_cast<int>(v);
  else throw std::invalid_argument("~history_length: must be a number of seconds (0 = no history)");
  if (!(s >= 0.0) || !std::isfinite(s) || s > 86400.0)
    throw std::invalid_argument("~history_length: " + std::to_string(s) + " s must be in [0, 86400] (0 = no history)");
  return s;
}

std::size_t SampleHistoryServer::add_topic(const std::string& topic, const std::string& type, const std::string& frame_id,
                                           double rate_hz) {
  const std::size_t capacity = feeds::SampleHistory::capacity_for(length_s_, rate_hz);
  std::lock_guard<std::mutex> lock(mutex_);
  topics_.push_back(std::make_unique<Topic>(topic, type, frame_id, capacity));
  scratch_.reserve(std::max(scratch_.capacity(), capacity));
  return topics_.size() - 1;
}

void SampleHistoryServer::advertise(ros::NodeHandle& pnh) {
  server_ = pnh.advertiseService("history", &SampleHistoryServer::serve, this);
}

void SampleHistoryServer::push(std::size_t topic, const ros::Time& stamp, double x, double y, double z) {
  std::lock_guard<std::mutex> lock(mutex_);
  topics_[topic]->history.push(static_cast<std::int64_t>(stamp.toNSec()), x, y, z);
}

bool SampleHistoryServer::serve(SampleHistory::Request& req, SampleHistory::Response& res) {
  std::lock_guard<std::mutex> serving(serve_mutex_);  // scratch_ is used after mutex_ is released
  std::unique_lock<std::mutex> lock(mutex_);
  const Topic* t = nullptr;
  for (const auto& p : topics_)
    if (p->name == req.topic) t = p.get();
  if (t == nullptr) {
    res.ok = false;
    res.message = "no history of topic '" + req.topic + "' here; this bridge keeps:";
    for (const auto& p : topics_) res.message += " " + p->name;
    return true;
  }
  const feeds::SampleHistory::Range r = t->history.since(static_cast<std::int64_t>(req.after.toNSec()), scratch_);
  const std::size_t overwritten = t->history.overwritten();
  lock.unlock();  // the response is filled from the copy: the publisher waits only for the copy
  res.ok = true;
  res.complete = r.complete;
  res.oldest.fromNSec(static_cast<std::uint64_t>(r.oldest_ns));
  res.type = t->type;
  res.frame_id = t->frame_id;
  res.stamps.resize(r.count);
  res.x.resize(r.count);
  res.y.resize(r.count);
  res.z.resize(r.count);
  for (std::size_t i = 0; i < r.count; ++i) {
    res.stamps[i].fromNSec(static_cast<std::uint64_t>(scratch_[i].stamp_ns));
    res.x[i] = scratch_[i].x;
    res.y[i] = scratch_[i].y;
    res.z[i] = scratch_[i].z;
  }
  char text[256];
  std::snprintf(text, sizeof text, "%zu samples of %s after %.9f%s (history holds %.1f s, %zu overwritten)", r.count,
                req.topic.c_str(), req.after.toSec(), r.complete ? "" : ": INCOMPLETE, the history does not reach back that far",
                r.count > 0 ? 1e-9 * static_cast<double>(r.newest_ns - r.oldest_ns) : 0.0, overwritten);
  res.message = text;
  ROS_INFO("sample history: served %s", text);
  return true;
}

}  // namespace rocking_monitor::live
