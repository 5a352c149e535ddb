// BatchRocking: the per-sample orchestration (which lane goes where); the vector kernels are in
// batch_rocking_simd.cpp. See model/batch_rocking.hpp for the exactness policy.
#include "rocking_monitor/model/batch_rocking.hpp"

#include <algorithm>
#include <limits>
#include <cmath>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"

namespace rocking_monitor::core {

namespace {
constexpr std::size_t kPad = batch_detail::kBlock;  // the kernels run whole blocks of vectors
std::size_t padded(std::size_t n) { return (n + kPad - 1) / kPad * kPad; }
}  // namespace

BatchRocking::BatchRocking(const std::vector<BodyParameters>& bodies,
                           const SolverSettings& settings, BatchTrig trig)
    : settings_(settings), trig_(trig) {
  models_.reserve(bodies.size());
  for (const BodyParameters& b : bodies) models_.emplace_back(b, settings);
  vector_rocking_ = settings.method == Method::Dopri5 && settings.model == ModelKind::Nonlinear;
  const std::size_t n = models_.size(), np = padded(n);
  const bool lin = settings.model == ModelKind::Linearized;
  for (int j = 0; j < 2; ++j) {
    lanes_.sin_a[j].assign(np, 0.0);
    lanes_.cos_a[j].assign(np, 1.0);
  }
  for (std::size_t k = 0; k < n; ++k) {
    for (int j = 0; j < 2; ++j) {
      const Pivot& pv = models_[k].body().pivot(j == 0 ? 1 : -1);
      // uplift_function(): s ax cos(alpha) - (ay + g) sin(alpha); linearized: cos -> 1, sin -> alpha.
      lanes_.sin_a[j][k] = lin ? pv.alpha : pv.sin_alpha;
      lanes_.cos_a[j][k] = lin ? 1.0 : pv.cos_alpha;
    }
  }
  lanes_.size_rocking(np);
  lanes_.t.assign(np, 0.0);
  lanes_.deferred.assign(np, 0);
  lanes_.mu_inf.assign(np, 0);
  seen_.assign(n, 0);
  first_violation_.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < n; ++k) lanes_.mu_inf[k] = std::isinf(models_[k].body().mu_s());
  lanes_.rest.assign(np, 0);
  lanes_.over.assign(np, 0);
  lanes_.maybe_lift.assign(np, 0);
  bcast_ax_.assign(n, 0.0);
  bcast_ay_.assign(n, 0.0);
}

const char* BatchRocking::simd_target() { return batch_detail::target_name(); }

void BatchRocking::note_violations(std::size_t k) {
  const std::uint8_t onsets = models_[k].last_report().violation_onsets;
  if (onsets == 0) return;
  if (seen_[k] == 0) first_violation_[k] = models_[k].time();
  seen_[k] |= onsets;
}

void BatchRocking::reset(double t, double ax, double ay) {
  std::fill(seen_.begin(), seen_.end(), 0);
  std::fill(first_violation_.begin(), first_violation_.end(), std::numeric_limits<double>::quiet_NaN());
  std::fill(lanes_.deferred.begin(), lanes_.deferred.end(), 0);
  std::fill(lanes_.rocking_deferred.begin(), lanes_.rocking_deferred.end(), 0);
  std::fill(lanes_.pending_steps.begin(), lanes_.pending_steps.end(), 0);
  std::fill(lanes_.pending_max.begin(), lanes_.pending_max.end(), 0.0);
  for (RockingModel& m : models_) m.reset(t, ax, ay);
  mirrors_stale_ = true;
}

void BatchRocking::flush(std::size_t k) const {
  models_[k].apply_rest_samples(lanes_.t[k], lanes_.ax_prev[k], lanes_.ay_prev[k],
                                lanes_.deferred[k]);
  lanes_.deferred[k] = 0;
}

void BatchRocking::flush_rocking(std::size_t k) const {
  Lanes& l = lanes_;
  models_[k].apply_rocking_samples(l.t[k], l.ax_prev[k], l.ay_prev[k], l.last_dt[k], l.rocking_deferred[k],
                                   l.theta[k], l.omega[k], l.h[k], l.k1a[k], l.k1b[k], l.pending_steps[k],
                                   l.last_steps[k], l.pending_max[k]);
  l.rocking_deferred[k] = 0;
  l.pending_steps[k] = 0;
  l.pending_max[k] = 0.0;
}

void BatchRocking::refresh_mirror(std::size_t k) {
  const RockingModel& m = models_[k];
  Lanes& l = lanes_;
  l.rest[k] = m.mode() == Mode::Rest;
  l.over[k] = m.mode() == Mode::Overturned && m.outcome().committed;
  l.ax_prev[k] = m.last_ax();
  l.ay_prev[k] = m.last_ay();
  l.t[k] = m.time();
  const double vr = vector_rocking_ && m.mode() == Mode::Rocking ? 1.0 : 0.0;
  vr_count_ += static_cast<long>(vr) - static_cast<long>(l.vr[k]);
  l.vr[k] = vr;
  if (vr == 0.0) return;
  // The model just stepped (or was set up): its pivot, flags and integrator state, read once here
  // instead of every sample.
  mirror_rocking(l, k, m);
}

void BatchRocking::Lanes::size_rocking(std::size_t n) {
  for (auto* v : {&vr, &side, &alpha, &p2, &atol_th, &atol_om, &overturn, &beyond, &theta, &omega, &h, &k1a, &k1b,
                  &fsal, &radius, &inertia, &cos_al, &slide_checked, &committed, &mu_clear, &ry_min, &ax_prev,
                  &ay_prev, &ax_now, &ay_now, &theta_out, &omega_out, &h_out, &k1a_out, &k1b_out, &max_ratio, &steps,
                  &pending_max, &last_dt})
    v->assign(n, 0.0);
  clean.assign(n, 0);
  end_clear.assign(n, 0);
  rocking_deferred.assign(n, 0);
  pending_steps.assign(n, 0);
  last_steps.assign(n, 0);
  idx.assign(n, 0);
}

void BatchRocking::mirror_rocking(Lanes& l, std::size_t k, const RockingModel& m) {
  const int s = m.side();
  const Pivot& pv = m.body().pivot(s);
  const Dopri5Stepper& st = m.dopri5();
  const double tol = m.settings().tol;
  l.side[k] = s;
  l.alpha[k] = pv.alpha;
  l.p2[k] = pv.p2;
  l.atol_th[k] = tol * pv.alpha;
  l.atol_om[k] = tol * pv.p * pv.alpha;
  l.overturn[k] = m.body().overturn_angle();
  l.beyond[k] = m.outcome().beyond_tipping ? 1.0 : 0.0;
  l.theta[k] = m.theta();
  l.omega[k] = m.omega();
  l.h[k] = st.step_size();
  l.k1a[k] = st.fsal_k1(0);
  l.k1b[k] = st.fsal_k1(1);
  l.fsal[k] = st.fsal_valid() ? 1.0 : 0.0;
  l.radius[k] = pv.radius;
  l.inertia[k] = pv.inertia;
  l.cos_al[k] = pv.cos_alpha;
  l.slide_checked[k] = std::isinf(m.body().mu_s()) ? 0.0 : 1.0;
  l.committed[k] = m.outcome().committed ? 1.0 : 0.0;
}

void BatchRocking::step_all(double ax, double ay, double dt) {
  std::fill(bcast_ax_.begin(), bcast_ax_.end(), ax);
  std::fill(bcast_ay_.begin(), bcast_ay_.end(), ay);
  step(bcast_ax_.data(), bcast_ay_.data(), dt);
}

void BatchRocking::check_sample(const double* ax, const double* ay, double dt) const {
  const std::size_t n = models_.size();
  bool finite = std::isfinite(dt) && dt > 0.0;
  for (std::size_t k = 0; k < n; ++k) finite &= std::isfinite(ax[k]) & std::isfinite(ay[k]);
  if (!finite)
    for (std::size_t k = 0; k < n; ++k) require_valid_sample(ax[k], ay[k], dt, "BatchRocking::step");
}

void BatchRocking::refresh_mirrors() {
  const std::size_t n = models_.size();
  for (std::size_t k = 0; k < n; ++k) {
    sync(k);  // deferred samples first: the mirrors are re-read from the models
    refresh_mirror(k);
  }
  mirrors_stale_ = false;
}

// 1. Lanes at REST: the vector uplift test (mirrors: mode, last inputs).
void BatchRocking::test_uplift(const double* ax, const double* ay) {
  const std::size_t n = models_.size();
  Lanes& l = lanes_;
  std::copy(ax, ax + n, l.ax_now.begin());
  std::copy(ay, ay + n, l.ay_now.begin());
  batch_detail::uplift_test(l, padded(n), settings_.model == ModelKind::Linearized);
}

// 2. ROCKING lanes: the vector dopri5 on their state in place.
void BatchRocking::rock_lanes(double dt) {
  const std::size_t n = models_.size();
  Lanes& l = lanes_;
  std::size_t m = 0;
  if (vr_count_ > 0)  // no walk over the lanes when none rocks
    for (std::size_t k = 0; k < n; ++k)
      if (l.vr[k] != 0.0) l.idx[m++] = static_cast<std::uint32_t>(k);
  if (m > 0) {
    const std::size_t mp = padded(m);
    for (std::size_t i = m; i < mp; ++i) l.idx[i] = l.idx[m - 1];  // same lane again: same results
    batch_detail::rocking_sample(l, mp, dt, settings_.tol, trig_ == BatchTrig::Exact);
  }
}

// 3a. The sample stays in lane k, its model untouched: at rest (fast), overturned, or rocking with the
// kernel's result clean and nothing happening at its end. Forced inline, as the loop it came from:
// it runs for every lane and sample.
[[gnu::always_inline]] inline bool BatchRocking::defer_sample(std::size_t k, const double* ax, const double* ay,
                                                              double dt) {
  Lanes& l = lanes_;
  if (l.rest[k] && !l.maybe_lift[k]) {
    // free_flight() and slides_from_rest() at the sample end, as RockingModel::update_criteria
    // evaluates them (ay + g < 0; mu_s given), with room for its rounding of the input line.
    const double margin = 1e-12 * (std::abs(ay[k]) + std::abs(l.ay_prev[k]) + kGravity);
    if (l.mu_inf[k] && ay[k] + kGravity > margin) {
      l.t[k] += dt;  // RockingModel::step's t_ += dt
      l.ax_prev[k] = ax[k];
      l.ay_prev[k] = ay[k];
      ++l.deferred[k];
      ++stats_.rest_fast;
      return true;
    }
  }
  if (l.over[k]) {  // RockingModel::apply_rest_samples: what step() does on its side
    l.t[k] += dt;
    l.ax_prev[k] = ax[k];
    l.ay_prev[k] = ay[k];
    ++l.deferred[k];
    ++stats_.rest_fast;
    return true;
  }
  if (l.vr[k] != 0.0 && l.clean[k] && l.end_clear[k]) {
    // Nothing can change at the sample end: the sample stays in the lane (the same additions as
    // commit_rocking_sample, applied by flush_rocking).
    l.keep_rocking_sample(k, ax[k], ay[k]);
    l.t[k] += dt;
    l.last_dt[k] = dt;
    ++l.rocking_deferred[k];
    ++stats_.rocking_fast;
    return true;
  }
  return false;
}

// 3b. Lane k's model takes the sample: the kernel's result committed (or rolled back to the scalar
// step), rest or overturned advanced, anything else the scalar step; then its mirror is re-read.
[[gnu::always_inline]] inline void BatchRocking::step_model(std::size_t k, const double* ax, const double* ay,
                                                            double dt) {
  Lanes& l = lanes_;
  sync(k);
  RockingModel& m = models_[k];
  if (l.vr[k] != 0.0) {
    if (l.clean[k]) {
      m.commit_rocking_sample(ax[k], ay[k], dt, l.theta_out[k], l.omega_out[k], l.h_out[k], l.k1a_out[k],
                              l.k1b_out[k], static_cast<int>(l.steps[k]), l.max_ratio[k], l.end_clear[k] != 0);
      ++stats_.rocking_fast;
    } else {
      m.step(ax[k], ay[k], dt);  // the model was not touched: this is the roll-back
      ++stats_.scalar;
      ++stats_.rocking_fallback;
    }
  } else if ((l.rest[k] && !l.maybe_lift[k]) || m.mode() == Mode::Overturned) {
    // An OVERTURNED body's step() only advances time and re-evaluates the (empty) criteria.
    m.advance_at_rest(ax[k], ay[k], dt);
    ++stats_.rest_fast;
  } else {
    m.step(ax[k], ay[k], dt);
    ++stats_.scalar;
  }
  note_violations(k);
  refresh_mirror(k);
}

void BatchRocking::step(const double* ax, const double* ay, double dt) {
  check_sample(ax, ay, dt);
  stats_ = BatchStats{};
  if (mirrors_stale_) refresh_mirrors();
  test_uplift(ax, ay);
  rock_lanes(dt);
  // 3. Per lane: rest (fast), rocking (the kernel's result kept or committed), everything else (scalar).
  const std::size_t n = models_.size();
  for (std::size_t k = 0; k < n; ++k)
    if (!defer_sample(k, ax, ay, dt)) step_model(k, ax, ay, dt);
}

}  // namespace rocking_monitor::core
