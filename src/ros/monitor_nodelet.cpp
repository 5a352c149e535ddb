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
  // Debian 12's libnodeletlib writes members up to offset 0xe8 of nodelet::Nodelet while its header
  // declares sizeof(nodelet::Nodelet) == 184: a derived member right after the base gets clobbered by
  // Nodelet::init(). Keep ours clear of that region.
  char abi_guard_[128] = {};
  std::unique_ptr<RockingMonitor> monitor_;
};

}  // namespace rocking_monitor::live

PLUGINLIB_EXPORT_CLASS(rocking_monitor::live::MonitorNodelet, nodelet::Nodelet)
