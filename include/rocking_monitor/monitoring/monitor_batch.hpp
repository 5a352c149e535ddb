#pragma once

// Many live items stepped together on one input sample each (issue 12: the batch engine in the node).
//
// Why: with thousands of items, most item-samples are quiet: the item stands at rest and the sample
// changes nothing that anybody reads (no corner lifts, no criterion changes, no running maximum of
// its intensity grows). Stepped one by one, each such sample still walks the item's whole object
// graph (two PlaneMonitors, their adaptive, rocking and contact models and running spectra: ~10 KB
// per item, far beyond the caches at 10,000 items), so the monitor is bound by memory, not by
// arithmetic. The batch keeps what a quiet sample needs in one compact record per item (~0.5 KB:
// the uplift coefficients of both corners, friction, the last input and the running-intensity
// filter states) and advances quiet samples there; the ItemMonitor, which stays the authority,
// is brought up to date (sync) before it steps a sample that is not quiet and before anybody reads it.
//
// Exactness: a deferred sample is one that ItemMonitor::step would have run as "nothing happens"
// (RockingModel at REST, no uplift, sample end inside the scene without sliding or flight, no new
// PGA / PGV / PSV maximum, so no criterion changes). The uplift and sample-end tests use a margin
// of 1e-9 of the input (the model interpolates the input, which can differ in the last bit); the
// intensity filters run the same arithmetic in the same order. Every item therefore ends every
// sample bit for bit as if stepped alone (test/monitoring/test_monitor_batch.cpp).
//
// Deferred too: planes that overturned before the sample, in the rocking or the contact model
// (their model only counts time then); and each plane on its own: of an item whose one plane
// rocks, the other plane at rest (or on its side) is deferred while the rocking plane is stepped
// (ItemMonitor::step_planes). Items with a 3-D description as a whole: their planes and the 3-D
// model at rest (no edge of the base lifts) or on its side.
// Deferred too (issue 28 part 3): planes rocking on the adaptive model's nonlinear rocking model
// (dopri5), stepped in rocking lanes by BatchRocking's vector kernel with exact trigonometry (the
// scalar model's step sizes and arithmetic, lane by lane) when the sample has no event (impact,
// turning point, first passage beyond the tipping angle, overturn) and its end changes nothing
// the item reports besides the rocking state itself: no free flight, sliding or switch margin
// (|R_x| below friction_safety mu_s R_y, R_y above lift_off_margin g, both with margins), not newly
// committed, no linearized entry, input inside the scene, no running maximum growing. The item's
// summary then changes (theta, omega, ratio, margin): summary() syncs such items first.
// Not deferred (stepped by ItemMonitor::step): impacts and other rocking events, sliding, the contact
// model before an overturn, the linearized tier, spectra with a pre-filter or several periods.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rocking_monitor/model/batch_rocking.hpp"
#include "rocking_monitor/monitoring/item_monitor.hpp"
#include "rocking_monitor/monitoring/item_summary.hpp"
#include "rocking_monitor/motion/streaming_intensity.hpp"

namespace rocking_monitor::core {

class MonitorBatch {
 public:
  /// items: started ItemMonitors, not owned; they must outlive the batch, and while the batch holds
  /// deferred samples of an item nobody else may step it (sync() it first).
  explicit MonitorBatch(std::vector<ItemMonitor*> items = {});

  std::size_t size() const { return items_.size(); }

  /// Item k was (re)started or stepped outside the batch: read its state again (no deferred samples
  /// of it may be pending: call sync(k) before touching it).
  void refresh(std::size_t k);

  /// One sample for items begin..end-1 with active == nullptr or active[k] != 0: exactly
  /// items[k]->step(ax[k], ay[k], az[k], dt) (item frame, m/s^2, dt s). Disjoint ranges may run on
  /// different threads. Returns how many of those item-samples were deferred. No allocation.
  std::size_t step(std::size_t begin, std::size_t end, const double* ax, const double* ay, const double* az,
                   double dt, const std::uint8_t* active = nullptr);

  /// Planes of item k stepped in its last sample in step() (bit p: plane p; 0: deferred as a whole).
  unsigned stepped_planes(std::size_t k) const { return lanes_[k].stepped ? lanes_[k].busy : 0u; }
  /// Events of item k's last sample in step() (none when it was deferred).
  const ItemEvents& events(std::size_t k) const { return lanes_[k].stepped ? items_[k]->events() : kNoEvents; }
  /// What events(k) holds, from a compact array: kHasChanges (criterion changes), kHasAlarms. A
  /// caller that scans every item for events reads these bytes instead of each item's object (a
  /// cache miss each with thousands of items).
  static constexpr std::uint8_t kHasChanges = 1, kHasAlarms = 2;
  std::uint8_t event_flags(std::size_t k) const { return event_flags_[k]; }

  /// Brings item k's monitor up to date (applies its deferred samples). Before reading it.
  void sync(std::size_t k);
  void sync_all();
  /// Deferred samples still pending for item k.
  long pending(std::size_t k) const {
    const Lane& l = lanes_[k];
    return l.planes > 1 ? std::max(l.plane[0].deferred, l.plane[1].deferred) : l.plane[0].deferred;
  }

  /// Plane-samples of item k deferred in rocking lanes so far (tests: that the path is taken).
  long rocking_deferred(std::size_t k) const {
    const Lane& l = lanes_[k];
    return l.plane[0].rocking_samples + (l.planes > 1 ? l.plane[1].rocking_samples : 0);
  }

  /// What item k's monitor would report now, without sync (issue 28). Taken when read, if the item
  /// was stepped in full (or refreshed) since the last read: deferred samples change none of its
  /// fields, so pending ones need no sync, and the per-sample path pays nothing for it. Not while
  /// step() runs.
  const ItemSummary& summary(std::size_t k) {
    if (summary_due_[k]) {
      if (rocking_pending(k)) sync(k);  // deferred rocking samples move theta and omega
      summarize(*items_[k], summaries_[k]);
      summary_due_[k] = 0;
    }
    return summaries_[k];
  }

 private:
  struct PlaneLane {
    double cs[2] = {0.0, 0.0}, sn[2] = {0.0, 0.0};  // uplift test, corner s = +1 (0) and -1 (1)
    double mu = 0.0;                                 // friction; inf: not checked
    bool eligible = false;                           // the plane may defer its next sample
    bool overturned = false;                         // the model lies on its side: no uplift or contact test
    double scene_h = 0.0, scene_v = 0.0;             // scene envelope, m/s^2 (inf: unknown)
    double ax_prev = 0.0, ay_prev = 0.0;             // last input of the plane, m/s^2
    double t = 0.0;                                  // the plane's models' clock after the deferred samples, s
    double dt = 0.0;                                 // the last deferred sample's interval, s
    long deferred = 0;                               // samples not yet applied to the plane's monitor
    bool rocking = false;                            // a rocking lane: state in rk_ at 2 k + p
    double lin_ratio = -1.0;                         // a deferred rocking sample must end above this ratio
    long rocking_samples = 0;                        // rocking samples deferred so far (never reset)
    std::uint8_t model_hint = 0;                     // AdaptiveModel::prefetch_hint() after its last step
    StreamingIntensity::Lane intensity{};
  };
  struct Lane {
    bool eligible = false;  // some plane may defer its next sample (an item with a 3-D model: all of it)
    bool stepped = false;   // the last sample went through ItemMonitor::step (some of its planes)
    unsigned busy = 0;      // planes stepped in the last sample (bit p: plane p)
    unsigned candidates = 0;  // step(): rocking planes waiting for the kernel's verdict (bit p)
    unsigned model_done = 0;  // step(): busy planes whose model sample the kernel gave (bit p)
    int planes = 1;
    int solid = -1;         // its SolidLane in solids_, or -1: no 3-D description
    PlaneLane plane[kPlaneCount];
  };
  // An item with a 3-D description (ItemMonitor::solid()) is deferred as a whole only: its planes,
  // and the 3-D model at rest (no edge of its base lifts: the planar uplift test per edge, on the
  // input along the edge's outward normal) or on its side; before the 3-D model takes over, no
  // running peak of the bidirectional test may grow.
  struct SolidEdge {
    double nx = 0.0, ny = 0.0;  // outward normal of the edge, world frame
    double cs = 0.0, sn = 0.0;  // cos and sin of the edge's tipping angle
  };
  struct SolidLane {
    bool active = false;         // the 3-D model decides (ItemMonitor::solid_active)
    bool overturned = false;     // the 3-D model lies on its side
    double peak_x = 0.0, peak_y = 0.0;  // not active: the running peaks of |ax|, |ay|, m/s^2
    double t = 0.0;              // active: the 3-D model's clock after the samples deferred, s
    // The item's clock and last input (x, y, z) after the samples deferred, s and m/s^2 (what the 3-D
    // model starts from when it takes over); the last sample's interval, s; samples not yet applied.
    double t_item = 0.0, last_a[3] = {0.0, 0.0, 0.0}, dt = 0.0;
    long deferred = 0;
    double mu_s = 0.0;           // the body's static friction (+inf: not given): the slip test
    std::vector<SolidEdge> edges;  // sized once (the base's edges), refilled without allocation
  };
  // Whether the sample is quiet for the plane (x1, y1: its horizontal and vertical input). next: the
  // plane's intensity lane after it.
  static bool quiet_test(const PlaneLane& pl, double x1, double y1, StreamingIntensity::Lane& next);
  // A quiet sample applied to the plane's lane.
  static void defer(PlaneLane& pl, const StreamingIntensity::Lane& next, double x1, double y1, double dt);
  // The model's part of defer(): its clock and inputs (the plane's intensity steps in full).
  static void defer_model(PlaneLane& pl, double x1, double y1, double dt);
  // Whether the sample is quiet for the whole item with a 3-D description; if so it is applied.
  bool quiet_solid(Lane& lane, double ax, double ay, double az, double dt);
  void prefetch_item(std::size_t k) const;
  void prefetch_planes(std::size_t k) const;
  void prefetch_models(std::size_t k) const;
  void step_busy(const std::size_t* busy, std::size_t n, const double* ax, const double* ay, const double* az,
                 double dt);
  void settle_rocking(std::uint32_t* rix, std::size_t nr, StreamingIntensity::Lane* const* rnext, const bool* grows,
                      const double* ax, const double* ay, const double* az, double dt, std::size_t* busy,
                      std::size_t& n, std::size_t& deferred);
  void sync_planes(std::size_t k, unsigned planes);   // sync() of these planes
  bool rocking_pending(std::size_t k) const {
    const Lane& l = lanes_[k];
    for (int p = 0; p < l.planes; ++p)
      if (l.plane[p].rocking && l.plane[p].deferred > 0) return true;
    return false;
  }
  // Mirrors the rocking model of plane p of item k in rk_ (the kernel's state in place).
  void mirror_rocking(std::size_t k, int p, const AdaptiveModel& a);
  // Kernel results of a quiet rocking sample applied to the lane.
  void defer_rocking(PlaneLane& pl, std::size_t r, const StreamingIntensity::Lane& next, double x1, double y1,
                     double dt);
  // Its model's part: the plane's intensity steps in full (a sample that raises a running maximum).
  void defer_rocking_model(PlaneLane& pl, std::size_t r, double x1, double y1, double dt);
  void refresh_planes(std::size_t k, unsigned planes);  // refresh() of these planes
  // refresh_planes()' steps. Whether plane pm may defer its next sample (started: the item and the
  // plane; solid: the item's SolidLane or -1); sets pl.rocking.
  bool plane_deferrable(bool started, const PlaneMonitor& pm, int solid, PlaneLane& pl) const;
  // The friction a deferred plane's sample must stay below (mu_s, or the pair's engaging demand).
  static double deferrable_mu(const ItemMonitor& item, double mu_s);
  // An eligible plane's lane: its uplift and slip tests, scene, clock, intensity and last input.
  static void copy_plane_state(const ItemMonitor& item, int p, PlaneLane& pl);
  // An item with a 3-D description: whether it may defer as a whole and, if so, its SolidLane.
  void refresh_solid(const ItemMonitor& item, Lane& lane, bool second);

  static const ItemEvents kNoEvents;
  std::vector<ItemMonitor*> items_;
  std::vector<Lane> lanes_;
  std::vector<SolidLane> solids_;
  // Rocking lanes (index 2 k + p), BatchRocking's layout, so that its kernel steps them in place.
  BatchRocking::Lanes rk_;
  double rk_tol_ = -1.0;  // the kernel's dopri5 tolerance: that of the first rocking lane (others must match)
  std::vector<ItemSummary> summaries_;
  std::vector<std::uint8_t> event_flags_;  // event_flags(): set by step() for the items it was given
  std::vector<std::uint8_t> summary_due_;  // the item was stepped or refreshed since its summary was taken
};

}  // namespace rocking_monitor::core
