// rocking_monitor nodelet: a thin shim around RockingMonitor (see monitor.hpp).
#include <memory>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "rocking_monitor/ros/monitor.hpp"

namespace rocking_monitor::live {

class MonitorNodelet : public nodelet::Nodelet {
 private:
  void onInit() override {
    monitor_ = std::make_unique<RockingMonitor>(getNodeHandle(), getPrivateNodeHandle());
    if (!monitor_->init()) {
      NODELET_FATAL("rocking_monitor nodelet: configuration rejected (see the message above)");
      monitor_.reset();
    }
  }
  std::unique_ptr<RockingMonitor> monitor_;
};

}  // namespace rocking_monitor::live

PLUGINLIB_EXPORT_CLASS(rocking_monitor::live::MonitorNodelet, nodelet::Nodelet)
