#pragma once

#include <array>
#include <memory>

#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/monitoring/item_modes.hpp"
#include "rocking_monitor/monitoring/item_spec.hpp"
#include "rocking_monitor/monitoring/friction_share.hpp"
#include "rocking_monitor/monitoring/plane_monitor.hpp"

namespace rocking_monitor::core {

/// One item of the live monitor: a PlaneMonitor for its x-z plane (width, under a_x and the vertical)
/// and, when the item has a depth, one for its y-z plane (depth, under a_y and the vertical). The
/// planes are independent planar bodies (planar decomposition, README "Two rocking planes"); the item
/// is at the more severe level of its planes, and an overturning level is alarmed once per item, by
/// the plane that reaches it first. ROS-free: the node and offline runs give the same numbers.
class ItemMonitor {
 public:
  using Options = PlaneMonitor::Options;

  /// Throws std::invalid_argument (message from validate(ItemSpec)) for a bad spec.
  ItemMonitor(const ItemSpec& spec, const Options& options);

  /// (Re)starts at time t (s) at rest with the first sample, in the item's frame (m/s^2, z up,
  /// gravity removed); dt_nominal (s) sizes the running spectra. Allocates; not per sample.
  void start(double t, double ax, double ay, double az, double dt_nominal);
  bool started() const { return started_; }

  /// The item already alarmed `level` (BeyondTipping, Committed or Overturned) in this event, e.g. in
  /// the journal before a restart: that level is not alarmed again by this monitor, also across
  /// start(); only a new ItemMonitor (the node's ~reset) re-arms it. Other levels are unchanged.
  void mark_alarmed(ItemMode level);
  /// A new event (issue 29: the last one's shaking stopped): the levels alarmed or marked are
  /// forgotten, so that the next shaking alarms them again; an item at rest starts afresh where it is
  /// at time t (s, the models' clock: its last sample's) with its last input (its models' latched
  /// levels, running intensities and criteria cleared: start()). An overturned item stays on its side
  /// (it cannot alarm until set upright: start()). Allocates, as start() does.
  void new_event(double t);
  /// Whether `level` was alarmed (or marked) since this monitor was made or last started.
  bool alarmed(ItemMode level) const;

  /// One sample in the item's frame: horizontal ax, ay and vertical az (m/s^2), dt seconds after the
  /// previous one. No allocation.
  const ItemEvents& step(double ax, double ay, double az, double dt);
  const ItemEvents& events() const { return events_; }

  /// Everything one sample carries to the next (state snapshots, issue 29): both planes, the 3-D
  /// model, the levels alarmed. Restored into a monitor of the same spec and options it continues
  /// bit for bit as the saved one would.
  struct Saved {
    bool started = false;
    std::array<PlaneMonitor::Saved, kPlaneCount> planes;  ///< y: when two_planes()
    bool two_planes = false;
    std::array<bool, 3> alarmed{};  ///< BEYOND_TIPPING, COMMITTED, OVERTURNED
    std::array<std::array<double, 2>, kPlaneCount> last_input{};  ///< m/s^2
    bool has_solid = false;
    Rocking3DModel::Saved solid;
    bool solid_active = false;
    double peak_x = 0.0, peak_y = 0.0;  ///< m/s^2
    double t = 0.0;                     ///< s
    Eigen::Vector3d last_a = Eigen::Vector3d::Zero();  ///< m/s^2
  };
  /// Reuses out's storage (no allocation once it has been filled before).
  void save(Saved& out) const;
  /// Continues from a saved state; levels marked alarmed (mark_alarmed) stay alarmed. Allocates, as
  /// start() does. std::invalid_argument (naming the item and plane) when in was saved by a monitor
  /// of another shape (planes, 3-D model, adaptive model): the monitor is then to be remade.
  void restore(const Saved& in);

  const ItemSpec& spec() const { return spec_; }
  bool two_planes() const { return planes_[1] != nullptr; }
  int plane_count() const { return two_planes() ? 2 : 1; }
  /// The y plane exists only when two_planes().
  const PlaneMonitor& plane(Plane p) const { return *planes_[static_cast<int>(p)]; }
  /// The more severe plane: higher mode, then larger rotation ratio, then x.
  Plane worst_plane() const;
  /// The more severe mode of the planes; OVERTURNED once any plane overturned.
  ItemMode mode() const;
  /// The 3-D model, when the item has a 3-D description and the options allow it (else null).
  const Rocking3DModel* solid() const { return solid_.get(); }
  /// Whether the 3-D model decides the item's state and alarms now (SolidChoice, Options::solid).
  bool solid_active() const { return solid_active_; }
  /// Screening criterion exceeded so far in plane p.
  bool screening_exceeded(Plane p, CriterionId id) const { return plane(p).screening_exceeded(id); }

 private:
  friend class MonitorBatch;  // defers quiet samples of many items (monitoring/monitor_batch.hpp)
  // step() for the planes in `planes` (bit p: plane p) only: MonitorBatch defers a quiet plane of an
  // item whose other plane moves (the deferred plane has no events; the batch applies its samples).
  // Planes in `model_done` had their model's sample applied by the batch already: they step the rest
  // (PlaneMonitor::step_after_model).
  const ItemEvents& step_planes(double ax, double ay, double az, double dt, unsigned planes,
                                unsigned model_done = 0);
  // Auto: whether the 3-D model takes over at the next step with the running peaks as they are (the
  // item at rest and the shaking bidirectional).
  bool solid_takes_over() const;
  // The 3-D model's step of a sample and its alarms (the item's levels while it is in charge).
  void step_solid(double dt);
  // The pair's one friction budget (friction_share.hpp): the shares for the next sample (its end's
  // input (ax, ay, az), dt later) from the planes' states, and whether the planes are engaged (then
  // both must step; it depends on the state at the sample's start alone).
  FrictionShare friction_share_now(double ax, double ay, double az, double dt) const;
  void share_friction(double ax, double ay, double az, double dt, unsigned planes, unsigned model_done);
  bool friction_engaged() const {
    const double x0[2] = {last_input_[0][0], last_input_[0][1]}, y0[2] = {last_input_[1][0], last_input_[1][1]};
    return shares_friction_ && core::friction_engaged(*planes_[0]->adaptive(), *planes_[1]->adaptive(), x0, y0);
  }
  ItemSpec spec_;
  bool shares_friction_ = false;  // two planes that both model friction
  std::array<std::unique_ptr<PlaneMonitor>, kPlaneCount> planes_;
  std::array<bool, 3> alarmed_{};  // BEYOND_TIPPING, COMMITTED, OVERTURNED reached by the item
  std::array<bool, 3> marked_{};   // levels marked alarmed by mark_alarmed: kept by start()
  bool started_ = false;
  ItemEvents events_;
  std::array<std::array<double, 2>, kPlaneCount> last_input_{};  // each plane's last (horizontal, vertical), m/s^2
  // 3-D: the model, whether it is in charge, whether it always is (base not an axis-aligned
  // rectangle, or SolidChoice::Solid), the running horizontal peaks for the bidirectional test.
  std::unique_ptr<Rocking3DModel> solid_;
  bool solid_active_ = false, solid_always_ = false;
  double bidirectional_ratio_ = 0.3;
  double peak_x_ = 0.0, peak_y_ = 0.0, t_ = 0.0;
  Eigen::Vector3d last_a_ = Eigen::Vector3d::Zero();
};

}  // namespace rocking_monitor::core
