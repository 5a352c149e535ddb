#pragma once
// What the Bullet reference tests (test_bullet_reference.cpp: the box, test_bullet_granite.cpp: the
// granite specimens) share: a body for both codes, one run of each, a one-sine pulse, the overturn tilt.

#include <gtest/gtest.h>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "bullet_rocking.hpp"
#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/study/shaking_table_experiments.hpp"

#ifndef ROCKING_EXPERIMENTS_DIR
#define ROCKING_EXPERIMENTS_DIR "../shared/experiments"
#endif
#ifndef ROCKING_SOURCE_DIR
#define ROCKING_SOURCE_DIR "."
#endif
#ifndef ROCKING_PYTHON
#define ROCKING_PYTHON "python3"
#endif

namespace rocking_monitor {
namespace {

namespace fs = std::filesystem;
using namespace core;
using reference::BulletBody;
using reference::BulletRocking;
using reference::BulletSettings;

struct Result {
  bool overturned = false;
  double overturn_time = std::nan("");
  double max_tilt = 0.0;
  double first_impact_time = std::nan("");
  double uplift_time = std::nan("");
  long impacts = 0;
  bool vertex = false;  // core: pivoted on a hull vertex at some sample (the corner wobble)
  long forced_rests = 0;  // core: samples that hit the event bound and were put down flat
};

// ---------------------------------------------------------------- bodies

struct Pair {
  BaseBodyParameters core;
  BulletBody bullet;
};

// A homogeneous B x D x 2h box, mass m, its base corner at the origin.
inline Pair box(double b, double d, double h, double mass, double overturn) {
  BodyParameters x;
  x.width = b;
  x.cg_height = h;
  x.nu1 = 0.5;
  Pair p;
  p.core = box_base_body(x, d, 0.5, std::nan(""));
  p.core.mass = mass;
  p.core.central_inertia *= mass;  // box_base_body gives it per unit mass
  p.core.overturn_angle = overturn;
  p.bullet.mass = mass;
  p.bullet.centre_of_mass = p.core.centre_of_mass;
  p.bullet.central_inertia = p.core.central_inertia;
  for (double z : {0.0, 2.0 * h})
    for (const Eigen::Vector2d& c : p.core.base) p.bullet.points.emplace_back(c.x(), c.y(), z);
  return p;
}

// ---------------------------------------------------------------- runs

using Series = std::vector<Eigen::Vector3d>;  // ground acceleration at t = k dt, m/s^2

inline Result run_core(const BaseBodyParameters& params, const Series& a, double dt) {
  SolverSettings s;
  s.tol = 1e-8;
  Rocking3DModel m(BaseBody(params), s);
  m.reset(0.0, a.front());
  Result r;
  for (std::size_t k = 1; k < a.size(); ++k) {
    const StepReport& rep = m.step(a[k], dt);
    if (rep.impacts > 0 && std::isnan(r.first_impact_time)) r.first_impact_time = rep.first_impact_time;
    r.vertex = r.vertex || m.mode() == Mode3D::Vertex;
    if (m.outcome().overturned) break;
  }
  r.overturned = m.outcome().overturned;
  r.overturn_time = m.outcome().overturn_time;
  r.max_tilt = m.outcome_3d().max_tilt;
  r.uplift_time = m.outcome().uplift_time;
  r.impacts = m.outcome().impacts;
  r.forced_rests = m.outcome().forced_rest_captures;
  return r;
}

// First impact in Bullet: the first time the tilt comes back down to `floor_ratio` of the first
// excursion's peak (Bullet has no impact event; the base lands where the tilt returns to ~0).
inline double bullet_first_return(const std::vector<Eigen::Vector2d>& h, double floor_ratio) {
  double peak = 0.0;
  std::size_t k = 0;
  for (; k < h.size(); ++k) {
    if (h[k].y() > peak) peak = h[k].y();
    else if (peak > 1e-3 && h[k].y() < 0.5 * peak) break;  // past the first peak
  }
  for (; k < h.size(); ++k)
    if (h[k].y() <= floor_ratio * peak) return h[k].x();
  return std::nan("");
}

inline Result run_bullet(const BulletBody& body, const BulletSettings& settings, const Series& a, double dt,
               std::vector<Eigen::Vector2d>* history = nullptr) {
  BulletRocking b(body, settings);
  b.set_input(a.front());
  b.record_history(history != nullptr);
  for (std::size_t k = 1; k < a.size(); ++k) {
    b.step(a[k], dt);
    if (b.outcome().overturned) break;
  }
  Result r;
  r.overturned = b.outcome().overturned;
  r.overturn_time = b.outcome().overturn_time;
  r.max_tilt = b.outcome().max_tilt;
  if (history) *history = b.history();
  return r;
}

// One-sine pulse of amplitude amp (m/s^2) and frequency f along `direction`, then rest to t_end.
inline Series sine_pulse(const Eigen::Vector3d& direction, double amp, double f, double dt, double t_end) {
  Series s;
  for (long k = 0; k * dt <= t_end + 1e-12; ++k) {
    const double t = k * dt;
    const double v = t < 1.0 / f ? amp * std::sin(2.0 * kPi * f * t) : 0.0;
    s.push_back(v * direction.normalized());
  }
  return s;
}

// Both codes count a body overturned at a tilt of 1.2 rad (69 deg): far past every tipping angle
// here (the box's corner 25 deg, the specimens' base edges <= 48 deg), so nothing brings it back,
// and short of 90 deg, where a box lies on its side and Bullet's compliant contact would make
// "reached 90 deg" a matter of microns.
inline constexpr double kOverturn = 1.2;  // rad

}  // namespace
}  // namespace rocking_monitor
