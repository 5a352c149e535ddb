#include "rocking_monitor/monitoring/monitor_batch.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <stdexcept>
#include <type_traits>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/prefetch.hpp"

namespace rocking_monitor::core {

const ItemEvents MonitorBatch::kNoEvents{};

MonitorBatch::MonitorBatch(std::vector<ItemMonitor*> items) : items_(std::move(items)), lanes_(items_.size()), summaries_(items_.size()), event_flags_(items_.size(), 0), summary_due_(items_.size(), 1) {
  for (std::size_t k = 0; k < items_.size(); ++k) {
    if (items_[k] == nullptr) throw std::invalid_argument("MonitorBatch: item " + std::to_string(k) + " is null");
    for (int p = 0; p < items_[k]->plane_count(); ++p)  // the kernel runs one tolerance
      if (const AdaptiveModel* a = items_[k]->planes_[p]->adaptive_.get(); a != nullptr && rk_tol_ < 0.0)
        rk_tol_ = a->nonlinear_model().settings().tol;
  }
  // Rocking lanes: BatchRocking's arrays, one lane per plane (2 k + p), padded for the kernel's blocks;
  // none without an adaptive plane (~0.55 KB per item).
  const std::size_t nr = rk_tol_ < 0.0 ? 0 : (kPlaneCount * items_.size() + batch_detail::kBlock - 1) / batch_detail::kBlock * batch_detail::kBlock;
  rk_.size_rocking(nr);
  for (std::size_t k = 0; k < items_.size(); ++k) {
    if (const Rocking3DModel* solid = items_[k]->solid()) {
      lanes_[k].solid = static_cast<int>(solids_.size());
      solids_.emplace_back();
      // (on a support the contact's edges change as the item slides: room for the base's and the support's)
      solids_.back().edges.reserve(solid->body().whole_base().size() + solid->body().parameters().support.size());
      solids_.back().edges.resize(static_cast<std::size_t>(solid->body().vertex_count()));
      solids_.back().mu_s = solid->body().parameters().mu_s;
    }
    refresh(k);
  }
}

// The friction a deferred plane's sample must stay below. Sharing one budget (friction_share.hpp), a
// plane is deferred only below the engaging demand: the item then stays not engaged, and its planes
// may be deferred each on its own.
double MonitorBatch::deferrable_mu(const ItemMonitor& item, double mu_s) {
  return item.shares_friction_ ? mu_s * kShareEngage : mu_s;
}

void MonitorBatch::refresh(std::size_t k) { refresh_planes(k, (1u << kPlaneCount) - 1); }

// What an item's lanes must hold again after the item stepped (or at the start): for each plane
// given, whether it may defer its next sample and, if so, what the quiet test reads; then the item as
// a whole (with a 3-D description: the 3-D model's lane too).
void MonitorBatch::refresh_planes(std::size_t k, unsigned planes) {
  const ItemMonitor& item = *items_[k];
  Lane& lane = lanes_[k];
  summary_due_[k] = 1;
  lane.planes = item.plane_count();
  const bool item_ok = item.started();
  for (int p = 0; p < lane.planes; ++p) {
    if (!((planes >> p) & 1u)) continue;
    const PlaneMonitor& pm = *item.planes_[p];
    PlaneLane& pl = lane.plane[p];
    pl.deferred = 0;
    pl.rocking = false;
    if (!rk_.vr.empty()) rk_.vr[kPlaneCount * k + static_cast<std::size_t>(p)] = 0.0;
    const AdaptiveModel* adaptive = pm.adaptive_.get();
    if (adaptive != nullptr) pl.model_hint = adaptive->prefetch_hint();
    pl.eligible = plane_deferrable(item_ok && pm.started_, pm, lane.solid, pl);
    if (!pl.eligible) continue;
    copy_plane_state(item, p, pl);
    if (pl.rocking) mirror_rocking(k, p, *adaptive);
  }
  if (item_ok && item.friction_engaged()) {
    // Engaged, the planes share the budget: both step, every sample (a deferred plane's pending
    // samples, rocking or at rest, are applied as they are by sync_planes first).
    for (int p = 0; p < lane.planes; ++p) lane.plane[p].eligible = false;
  }
  const bool second = lane.planes > 1 && lane.plane[1].eligible;
  if (lane.solid < 0) {
    lane.eligible = lane.plane[0].eligible || second;  // each plane on its own
    return;
  }
  refresh_solid(item, lane, second);
}

bool MonitorBatch::plane_deferrable(bool started, const PlaneMonitor& pm, int solid, PlaneLane& pl) const {
  const AdaptiveModel* adaptive = pm.adaptive_.get();
  bool ok = started && pm.intensity_ && pm.intensity_->lane_eligible();
  if (adaptive != nullptr) {
    // Rocking lanes for items without a 3-D description (those are deferred as a whole only).
    pl.rocking = ok && solid < 0 && adaptive->rocking_deferrable() &&
                 adaptive->nonlinear_model().settings().tol == rk_tol_;
    return ok && (pl.rocking || adaptive->rest_deferrable());
  }
  // Pure rocking: at rest with no validity criterion standing (a stale one is cleared by a step).
  ok = ok && (pm.model_.mode() == Mode::Rest ||
              (pm.model_.mode() == Mode::Overturned && pm.model_.outcome().committed)) &&
       !pm.slid_at_uplift_;
  for (CriterionId id : {CriterionId::FreeFlight, CriterionId::SlideFromRest, CriterionId::SlideAtUplift,
                         CriterionId::SlideWhileRocking})
    ok = ok && !pm.exceeded_[static_cast<int>(id)];
  return ok;
}

void MonitorBatch::copy_plane_state(const ItemMonitor& item, int p, PlaneLane& pl) {
  const PlaneMonitor& pm = *item.planes_[p];
  const AdaptiveModel* adaptive = pm.adaptive_.get();
  // From the adaptive model when there is one (just stepped, in cache): the same body and solver
  // as the plane's, whose own model_ and options_ are then cold (perf: half of this function's time).
  const Body& body = adaptive != nullptr ? adaptive->body() : pm.model_.body();
  const ModelKind kind = adaptive != nullptr ? adaptive->settings().rocking.model : pm.options_.solver.model;
  const bool linear = kind == ModelKind::Linearized;
  for (int i = 0; i < 2; ++i) {
    const Pivot& pv = body.pivot(i == 0 ? 1 : -1);
    pl.cs[i] = linear ? 1.0 : pv.cos_alpha;  // uplift_function(): linearized cos -> 1, sin -> alpha
    pl.sn[i] = linear ? pv.alpha : pv.sin_alpha;
  }
  pl.mu = deferrable_mu(item, body.mu_s());
  pl.overturned = (adaptive != nullptr ? adaptive->mode() : pm.contact_mode()) == ContactMode::Overturned;
  const SceneEnvelope scene = adaptive != nullptr ? adaptive->settings().scene : SceneEnvelope{};
  pl.scene_h = scene.horizontal;
  pl.scene_v = scene.vertical;
  // The inputs the model interpolates from (the item's last step, as the plane saw it) and its
  // clock (AdaptiveModel resets its rocking model at its own time on every switch down).
  pl.t = adaptive != nullptr ? adaptive->time() : pm.model_.time();
  pm.intensity_->to_lane(pl.intensity);
  pl.ax_prev = item.last_input_[p][0];
  pl.ay_prev = item.last_input_[p][1];
}

void MonitorBatch::refresh_solid(const ItemMonitor& item, Lane& lane, bool second) {
  // With a 3-D description, as a whole: every plane, and the 3-D model (or the bidirectional test).
  SolidLane& sl = solids_[static_cast<std::size_t>(lane.solid)];
  const Rocking3DModel& solid = *item.solid();
  sl.active = item.solid_active();
  lane.eligible = lane.plane[0].eligible && (lane.planes == 1 || second) &&
                  (sl.active ? solid.rest_deferrable() : !item.solid_takes_over());
  if (!lane.eligible) return;
  sl.deferred = 0;
  sl.t_item = item.t_;
  for (int i = 0; i < 3; ++i) sl.last_a[i] = item.last_a_[i];
  sl.peak_x = item.peak_x_;
  sl.peak_y = item.peak_y_;
  sl.overturned = solid.mode() == Mode3D::Overturned;
  sl.t = solid.time();
  sl.edges.resize(static_cast<std::size_t>(solid.body().vertex_count()));  // (within its reserve: no allocation)
  for (std::size_t e = 0; e < sl.edges.size(); ++e) {
    const Eigen::Vector3d n = solid.edge_normal(static_cast<int>(e));
    const Pivot& pv = solid.body().edge(static_cast<int>(e)).pivot;
    sl.edges[e] = {n.x(), n.y(), pv.cos_alpha, pv.sin_alpha};
  }
}

// Inlined into the step loop (called, they cost the batch benchmark ~5 %).
[[gnu::always_inline]] inline bool MonitorBatch::quiet_test(const PlaneLane& pl, double x1, double y1, StreamingIntensity::Lane& next) {
  const double x0 = pl.ax_prev, y0 = pl.ay_prev;
  if (x1 > pl.scene_h || -x1 > pl.scene_h || y1 > pl.scene_v || -y1 > pl.scene_v) return false;  // SceneEnvelope::contains
  next = pl.intensity;
  if (!StreamingIntensity::push_quiet(next, x1)) return false;
  if (!pl.overturned) {
    // Margin: the model evaluates the input interpolated at the sample ends, which may differ from
    // (x0, y0), (x1, y1) in the last bit.
    const double m = 1e-9 * (std::abs(x0) + std::abs(y0) + std::abs(x1) + std::abs(y1) + kGravity);
    for (int i = 0; i < 2; ++i) {
      const double s = i == 0 ? 1.0 : -1.0;
      // uplift_function() at both ends: linear in the input, so negative all through the sample.
      if (!(s * x0 * pl.cs[i] - (y0 + kGravity) * pl.sn[i] < -m)) return false;
      if (!(s * x1 * pl.cs[i] - (y1 + kGravity) * pl.sn[i] < -m)) return false;
    }
    const double normal = y1 + kGravity;
    if (!(normal > m)) return false;                                               // free flight
    if (!std::isinf(pl.mu) && !(std::abs(x1) + m * (1.0 + pl.mu) < pl.mu * normal)) return false;  // sliding
  }
  return true;
}

[[gnu::always_inline]] inline void MonitorBatch::defer(PlaneLane& pl, const StreamingIntensity::Lane& next, double x1, double y1, double dt) {
  pl.intensity = next;
  defer_model(pl, x1, y1, dt);
}

[[gnu::always_inline]] inline void MonitorBatch::defer_model(PlaneLane& pl, double x1, double y1, double dt) {
  pl.ax_prev = x1;
  pl.ay_prev = y1;
  pl.t += dt;
  pl.dt = dt;
  ++pl.deferred;
}

void MonitorBatch::mirror_rocking(std::size_t k, int p, const AdaptiveModel& a) {
  // As BatchRocking::refresh_mirror: the model just stepped (or was set up); read once here.
  const std::size_t r = kPlaneCount * k + static_cast<std::size_t>(p);
  const RockingModel& m = a.nonlinear_model();
  const double mu = deferrable_mu(*items_[k], m.body().mu_s());
  BatchRocking::Lanes& l = rk_;
  l.vr[r] = 1.0;
  BatchRocking::mirror_rocking(l, r, m);
  // The sample end must give no sliding (RockingModel's criterion, mu_s R_y) and none of
  // AdaptiveModel::check_rocking's early margins (friction_safety mu_s R_y, lift_off_margin g): both
  // are checked only with a friction coefficient.
  const bool friction = !std::isinf(mu);
  l.mu_clear[r] = friction ? std::min(mu, a.settings().friction_safety * mu) : 0.0;
  l.ry_min[r] = friction ? std::max(0.0, a.settings().lift_off_margin * kGravity) : 0.0;
  l.ax_prev[r] = m.last_ax();  // the model's own input line starts there (the plane's last input too)
  l.ay_prev[r] = m.last_ay();
  l.pending_steps[r] = 0;
  l.pending_max[r] = 0.0;
  lanes_[k].plane[p].lin_ratio = a.linearized_entry_ratio();
}

static_assert(std::is_trivially_copyable_v<StreamingIntensity::Lane> &&
                  std::is_trivially_destructible_v<StreamingIntensity::Lane>,
              "step() keeps intensity lanes in raw storage");

[[gnu::always_inline]] inline void MonitorBatch::defer_rocking(PlaneLane& pl, std::size_t r,
                                                                const StreamingIntensity::Lane& next, double x1,
                                                                double y1, double dt) {
  pl.intensity = next;
  defer_rocking_model(pl, r, x1, y1, dt);
}

[[gnu::always_inline]] inline void MonitorBatch::defer_rocking_model(PlaneLane& pl, std::size_t r, double x1,
                                                                      double y1, double dt) {
  rk_.keep_rocking_sample(r, x1, y1);  // BatchRocking::step's deferred rocking
  ++pl.rocking_samples;
  defer_model(pl, x1, y1, dt);
}

bool MonitorBatch::quiet_solid(Lane& lane, double ax, double ay, double az, double dt) {
  SolidLane& sl = solids_[static_cast<std::size_t>(lane.solid)];
  if (!sl.active) {
    // A running peak grows (the planes' PGA test below implies it today: kept as the 3-D model's own
    // condition).
    if (std::abs(ax) > sl.peak_x || std::abs(ay) > sl.peak_y) return false;
  } else if (!sl.overturned) {
    // Rocking3DModel::find_uplift: no edge's uplift function positive at either end of the sample
    // (linear in the input), with the planes' margin for the interpolated input's last bit.
    const double x0 = sl.last_a[0], y0 = sl.last_a[1], z0 = sl.last_a[2];
    const double m = 1e-9 * (std::abs(x0) + std::abs(y0) + std::abs(z0) + std::abs(ax) + std::abs(ay) + std::abs(az) +
                             kGravity);
    for (const SolidEdge& e : sl.edges) {
      if (!(-(x0 * e.nx + y0 * e.ny) * e.cs - (z0 + kGravity) * e.sn < -m)) return false;
      if (!(-(ax * e.nx + ay * e.ny) * e.cs - (az + kGravity) * e.sn < -m)) return false;
    }
    // Rocking3DModel::find_slip: the demand inside the friction cone at both ends (a convex cone:
    // then all through the sample).
    if (std::isfinite(sl.mu_s) && (!(std::hypot(x0, y0) < sl.mu_s * (z0 + kGravity) - m) ||
                                   !(std::hypot(ax, ay) < sl.mu_s * (az + kGravity) - m)))
      return false;
  }
  StreamingIntensity::Lane next[kPlaneCount];
  for (int p = 0; p < lane.planes; ++p)
    if (!quiet_test(lane.plane[p], p == 0 ? ax : ay, az, next[p])) return false;
  for (int p = 0; p < lane.planes; ++p) defer(lane.plane[p], next[p], p == 0 ? ax : ay, az, dt);
  if (sl.active) sl.t += dt;  // the 3-D model's clock: the same additions as its step()
  sl.t_item += dt;            // and the item's (ItemMonitor::step)
  sl.dt = dt;
  sl.last_a[0] = ax;
  sl.last_a[1] = ay;
  sl.last_a[2] = az;
  ++sl.deferred;
  return true;
}

// An item that is not quiet touches ~10 KB of its objects, spread over the heap: with 10,000 items
// none of it is in cache, and every first touch stalls (perf). The objects of the items a few places
// ahead are prefetched along the pointer chain in three stages (the item, its planes, their models),
// each stage reading only pointers the stage before brought in. Only the lines a step touches: an
// item's spec and event arrays (~1.1 KB of its 1.2) are read only when it has events, and prefetching
// them cost 7 % of the strongest shaking's time (docs/performance.md, session 14).
void MonitorBatch::prefetch_item(std::size_t k) const {
  const ItemMonitor* item = items_[k];
  prefetch_lines(&item->planes_);  // with the change count
  prefetch_lines(&item->events_.alarm_count);
  prefetch_lines(&item->last_input_, item + 1);
}

void MonitorBatch::prefetch_planes(std::size_t k) const {
  const ItemMonitor& item = *items_[k];
  for (int p = 0; p < lanes_[k].planes; ++p) {
    if (!((lanes_[k].busy >> p) & 1u)) continue;  // a deferred plane is not touched
    const PlaneMonitor* pm = item.planes_[p].get();
    // The model and intensity pointers, the flags and the event counts (the event arrays are
    // written only when there are events).
    prefetch_lines(&pm->adaptive_, &pm->events_.change_count + 1);
    prefetch_lines(&pm->events_.alarm_count);
  }
}

void MonitorBatch::prefetch_models(std::size_t k) const {
  const ItemMonitor& item = *items_[k];
  for (int p = 0; p < lanes_[k].planes; ++p) {
    if (!((lanes_[k].busy >> p) & 1u)) continue;
    const PlaneMonitor& pm = *item.planes_[p];
    if (pm.intensity_) prefetch_lines(pm.intensity_.get(), sizeof(StreamingIntensity));
    if (pm.adaptive_) pm.adaptive_->prefetch(lanes_[k].plane[p].model_hint);
  }
}

// The block's rocking candidates: stepped together by the vector kernel (a few are not worth a
// kernel block of 16: they step in full); a quiet sample is deferred, any other goes back to its
// item's planes to step (added to `busy`).
void MonitorBatch::settle_rocking(std::uint32_t* rix, std::size_t nr, StreamingIntensity::Lane* const* rnext,
                                  const bool* grows, const double* ax, const double* ay, const double* az, double dt,
                                  std::size_t* busy, std::size_t& n, std::size_t& deferred) {
  const bool kernel = nr >= 4;
  if (kernel) {
    const std::size_t padded = (nr + batch_detail::kBlock - 1) / batch_detail::kBlock * batch_detail::kBlock;
    for (std::size_t i = nr; i < padded; ++i) rix[i] = rix[nr - 1];  // the same lane again: same results
    batch_detail::rocking_sample(rk_, rix, padded, dt, rk_tol_, true);
  }
  for (std::size_t i = 0; i < nr; ++i) {
    const std::size_t r = rix[i], k = r / kPlaneCount;
    const int p = static_cast<int>(r % kPlaneCount);
    Lane& lane = lanes_[k];
    PlaneLane& pl = lane.plane[p];
    // AdaptiveModel::maybe_enter_linearized: below the ratio the next step() changes tier.
    if (kernel && rk_.clean[r] && rk_.end_clear[r] && std::abs(rk_.theta_out[r]) / rk_.alpha[r] > pl.lin_ratio) {
      if (!grows[i]) {
        defer_rocking(pl, r, *rnext[i], p == 0 ? ax[k] : ay[k], az[k], dt);
        summary_due_[k] = 1;
      } else {
        // The model's sample is the kernel's, kept as a deferred one (the sync before the item
        // steps applies it); the plane then steps only its running intensity and screening
        // criteria (PlaneMonitor::step_after_model), which the new maximum may change.
        defer_rocking_model(pl, r, p == 0 ? ax[k] : ay[k], az[k], dt);
        lane.model_done |= 1u << p;
        if (lane.busy == 0) busy[n++] = k;
        lane.busy |= 1u << p;
      }
    } else {
      if (lane.busy == 0) busy[n++] = k;  // its first plane to step
      lane.busy |= 1u << p;
    }
    lane.candidates &= ~(1u << p);
    if (lane.candidates == 0 && lane.busy == 0) ++deferred;  // the item's last candidate: all deferred
  }
}

// The block's items that step (their planes in lane.busy), their objects prefetched a few ahead.
void MonitorBatch::step_busy(const std::size_t* busy, std::size_t n, const double* ax, const double* ay,
                             const double* az, double dt) {
  for (std::size_t j = 0; j < std::min<std::size_t>(n, 6); ++j) prefetch_item(busy[j]);
  for (std::size_t j = 0; j < std::min<std::size_t>(n, 4); ++j) prefetch_planes(busy[j]);
  for (std::size_t j = 0; j < std::min<std::size_t>(n, 2); ++j) prefetch_models(busy[j]);
  for (std::size_t j = 0; j < n; ++j) {
    if (j + 6 < n) prefetch_item(busy[j + 6]);
    if (j + 4 < n) prefetch_planes(busy[j + 4]);
    if (j + 2 < n) prefetch_models(busy[j + 2]);
    const std::size_t k = busy[j];
    const unsigned planes = lanes_[k].busy;
    sync_planes(k, planes);
    const ItemEvents& ev = items_[k]->step_planes(ax[k], ay[k], az[k], dt, planes, lanes_[k].model_done);
    event_flags_[k] = static_cast<std::uint8_t>((ev.change_count > 0 ? kHasChanges : 0) | (ev.alarm_count > 0 ? kHasAlarms : 0));
    lanes_[k].stepped = true;
    refresh_planes(k, planes);
  }
}

std::size_t MonitorBatch::step(std::size_t begin, std::size_t end, const double* ax, const double* ay,
                               const double* az, double dt, const std::uint8_t* active) {
  std::size_t deferred = 0;
  // Per block: first the quiet test over the compact lanes, then the other items stepped in order,
  // their objects prefetched ahead. Items are independent: the order changes no result.
  constexpr std::size_t kBlock = 64;
  std::size_t busy[kBlock];
  for (std::size_t b = begin; b < end; b += kBlock) {
    const std::size_t e = std::min(end, b + kBlock);
    // Rocking lanes whose input stays in the scene and raises no running maximum are candidates: the
    // vector kernel steps them together after this loop, which then decides their items.
    std::uint32_t rix[kPlaneCount * kBlock + batch_detail::kBlock];
    // Raw storage: a Lane array would be zero-filled (30 KB) at every block.
    std::aligned_storage_t<sizeof(StreamingIntensity::Lane), alignof(StreamingIntensity::Lane)> raw[kPlaneCount * kBlock];
    StreamingIntensity::Lane* rnext[kPlaneCount * kBlock];  // as placement new returns them
    bool grows[kPlaneCount * kBlock];  // the candidate's sample raises a running PGA, PGV or PSV
    std::size_t nr = 0;
    std::size_t n = 0;
    for (std::size_t k = b; k < e; ++k) {
      Lane& lane = lanes_[k];
      lane.stepped = false;
      lane.candidates = 0;
      lane.model_done = 0;
      event_flags_[k] = 0;
      if (active != nullptr && active[k] == 0) continue;
      // Each plane is deferred on its own; the item is stepped for the others. Invalid samples
      // (non-finite, dt <= 0) go to ItemMonitor::step, which rejects them.
      unsigned planes_busy = (1u << lane.planes) - 1;
      if (lane.eligible && std::isfinite(ax[k]) && std::isfinite(ay[k]) && std::isfinite(az[k]) && dt > 0.0 &&
          std::isfinite(dt)) {
        if (lane.solid >= 0) {
          if (quiet_solid(lane, ax[k], ay[k], az[k], dt)) planes_busy = 0;
        } else {
          for (int p = 0; p < lane.planes; ++p) {
            PlaneLane& pl = lane.plane[p];
            if (!pl.eligible) continue;
            const double x1 = p == 0 ? ax[k] : ay[k], y1 = az[k];
            if (pl.rocking) {
              if (x1 > pl.scene_h || -x1 > pl.scene_h || y1 > pl.scene_v || -y1 > pl.scene_v) continue;  // SceneEnvelope::contains
              rnext[nr] = new (&raw[nr]) StreamingIntensity::Lane(pl.intensity);
              // A sample that raises a running maximum is a candidate too: in the strongest shaking a
              // third of the rocking plane-samples do. The kernel may still give its model sample.
              grows[nr] = !StreamingIntensity::push_quiet(*rnext[nr], x1);
              const std::size_t r = kPlaneCount * k + static_cast<std::size_t>(p);
              rk_.ax_now[r] = x1;
              rk_.ay_now[r] = y1;
              rix[nr++] = static_cast<std::uint32_t>(r);
              lane.candidates |= 1u << p;
              planes_busy &= ~(1u << p);
              continue;
            }
            StreamingIntensity::Lane next;
            if (quiet_test(pl, x1, y1, next)) {
              defer(pl, next, x1, y1, dt);
              planes_busy &= ~(1u << p);
            }
          }
        }
      }
      lane.busy = planes_busy;
      if (planes_busy != 0) busy[n++] = k;
      else if (lane.candidates == 0) ++deferred;
    }
    if (nr > 0) settle_rocking(rix, nr, rnext, grows, ax, ay, az, dt, busy, n, deferred);
    step_busy(busy, n, ax, ay, az, dt);
  }
  return deferred;
}

void MonitorBatch::sync(std::size_t k) { sync_planes(k, (1u << kPlaneCount) - 1); }

void MonitorBatch::sync_planes(std::size_t k, unsigned planes) {
  Lane& lane = lanes_[k];
  ItemMonitor& item = *items_[k];
  for (int p = 0; p < lane.planes; ++p) {
    PlaneLane& pl = lane.plane[p];
    if (!((planes >> p) & 1u) || pl.deferred == 0) continue;
    PlaneMonitor& pm = *item.planes_[p];
    pm.intensity_->from_lane(pl.intensity);
    if (pl.rocking) {
      BatchRocking::Lanes& l = rk_;
      const std::size_t r = kPlaneCount * k + static_cast<std::size_t>(p);
      pm.adaptive_->apply_rocking_samples(pl.t, pl.ax_prev, pl.ay_prev, pl.dt, pl.deferred, l.theta[r], l.omega[r],
                                          l.h[r], l.k1a[r], l.k1b[r], l.pending_steps[r], l.last_steps[r],
                                          l.pending_max[r]);
      l.pending_steps[r] = 0;
      l.pending_max[r] = 0.0;
    } else if (pm.adaptive_) pm.adaptive_->apply_rest_samples(pl.t, pl.ax_prev, pl.ay_prev, pl.dt, pl.deferred);
    else pm.model_.apply_rest_samples(pl.t, pl.ax_prev, pl.ay_prev, pl.deferred);
    // Its last sample was deferred: no events.
    pm.events_.change_count = 0;
    pm.events_.alarm_count = 0;
    item.last_input_[p] = {pl.ax_prev, pl.ay_prev};
    pl.deferred = 0;
  }
  if (!lane.stepped) {  // the item's last sample was deferred as a whole: no events
    item.events_.change_count = 0;
    item.events_.alarm_count = 0;
  }
  // With a 3-D description, the item's own clock and last input (without, nothing reads them) and
  // the 3-D model's.
  if (lane.solid < 0) return;
  SolidLane& sl = solids_[static_cast<std::size_t>(lane.solid)];
  if (sl.deferred == 0) return;
  const Eigen::Vector3d a(sl.last_a[0], sl.last_a[1], sl.last_a[2]);
  if (item.solid_active_) item.solid_->apply_rest_samples(sl.t, a, sl.dt, sl.deferred);
  item.t_ = sl.t_item;
  item.last_a_ = a;
  sl.deferred = 0;
}

void MonitorBatch::sync_all() {
  for (std::size_t k = 0; k < lanes_.size(); ++k) sync(k);
}

}  // namespace rocking_monitor::core
