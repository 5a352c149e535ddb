#pragma once
// Helpers shared by the station tests (test_station*.cpp): a negated copy of a signal and the message
// of the StationError a call throws.

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "rocking_monitor/motion/station.hpp"

namespace rocking_monitor::core {
namespace {

inline std::vector<double> negated(std::vector<double> v) {
  for (double& x : v) x = -x;
  return v;
}

inline std::string station_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const StationError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected StationError, got: " << e.what();
    return "<wrong exception>";
  }
  return "";
}

}  // namespace
}  // namespace rocking_monitor::core
