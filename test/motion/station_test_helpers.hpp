#pragma once
// What the station tests (test_station*.cpp) share: their includes, the records directory, a negated
// copy of a signal and the message of the StationError a call throws.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/sensor_frame.hpp"
#include "rocking_monitor/motion/station.hpp"
#include "rocking_monitor/motion/synthetic_motion.hpp"

#ifndef ROCKING_RECORDS_DIR
#define ROCKING_RECORDS_DIR "/work/shared/records"
#endif

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
