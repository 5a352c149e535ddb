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
constexpr std::size_t kPad = 16;  // the kernels run whole vectors; >= the widest lane count
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
  for (auto* v : {&lanes_.ax_prev, &lanes_.ay_prev, &lanes_.ax_now, &lanes_.ay_now})
    v->assign(np, 0.0);
  lanes_.t.assign(np, 0.0);
  lanes_.deferred.assign(np, 0);
  lanes_.mu_inf.assign(np, 0);
  seen_.assign(n, 0);
  first_violation_.assign(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < n; ++k) lanes_.mu_inf[k] = std::isinf(models_[k].body().mu_s());
  lanes_.rest.assign(np, 0);
  lanes_.maybe_lift.assign(np, 0);
  lanes_.idx.assign(np, 0);
  for (auto* v : {&lanes_.side, &lanes_.alpha, &lanes_.p2, &lanes_.atol_th, &lanes_.atol_om,
                  &lanes_.overturn, &lanes_.beyond, &lanes_.ax0, &lanes_.axs, &lanes_.ay0,
                  &lanes_.ays, &lanes_.theta, &lanes_.omega, &lanes_.h, &lanes_.k1a, &lanes_.k1b,
                  &lanes_.fsal, &lanes_.max_ratio, &lanes_.steps, &lanes_.radius, &lanes_.inertia,
                  &lanes_.cos_al, &lanes_.slide_checked, &lanes_.committed})
    v->assign(np, 0.0);
  lanes_.clean.assign(np, 0);
  lanes_.end_clear.assign(np, 0);
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
  for (RockingModel& m : models_) m.reset(t, ax, ay);
  mirrors_stale_ = true;
}

void BatchRocking::flush(std::size_t k) const {
  models_[k].apply_rest_samples(lanes_.t[k], lanes_.ax_prev[k], lanes_.ay_prev[k],
                                lanes_.deferred[k]);
  lanes_.deferred[k] = 0;
}

void BatchRocking::refresh_mirror(std::size_t k) {
  const RockingModel& m = models_[k];
  lanes_.rest[k] = m.mode() == Mode::Rest;
  lanes_.ax_prev[k] = m.last_ax();
  lanes_.ay_prev[k] = m.last_ay();
  lanes_.t[k] = m.time();
}

void BatchRocking::step_all(double ax, double ay, double dt) {
  std::fill(bcast_ax_.begin(), bcast_ax_.end(), ax);
  std::fill(bcast_ay_.begin(), bcast_ay_.end(), ay);
  step(bcast_ax_.data(), bcast_ay_.data(), dt);
}

void BatchRocking::step(const double* ax, const double* ay, double dt) {
  const std::size_t n = models_.size();
  bool finite = std::isfinite(dt) && dt > 0.0;
  for (std::size_t k = 0; k < n; ++k) finite &= std::isfinite(ax[k]) & std::isfinite(ay[k]);
  if (!finite)
    for (std::size_t k = 0; k < n; ++k) require_valid_sample(ax[k], ay[k], dt, "BatchRocking::step");
  stats_ = BatchStats{};
  Lanes& l = lanes_;
  if (mirrors_stale_) {
    for (std::size_t k = 0; k < n; ++k) {
      sync(k);  // deferred samples first: the mirrors are re-read from the models
      refresh_mirror(k);
    }
    mirrors_stale_ = false;
  }

  // 1. Lanes at REST: the vector uplift test (mirrors: mode, last inputs).
  std::copy(ax, ax + n, l.ax_now.begin());
  std::copy(ay, ay + n, l.ay_now.begin());
  batch_detail::uplift_test(l, padded(n), settings_.model == ModelKind::Linearized);

  // 2. Sort the lanes: rest (fast), rocking (vector dopri5), everything else (scalar).
  std::size_t m_count = 0;
  for (std::size_t k = 0; k < n; ++k) {
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
        continue;
      }
    }
    sync(k);
    RockingModel& m = models_[k];
    // An OVERTURNED body's step() only advances time and re-evaluates the (empty) criteria.
    if ((l.rest[k] && !l.maybe_lift[k]) || m.mode() == Mode::Overturned) {
      m.advance_at_rest(ax[k], ay[k], dt);
      note_violations(k);
      refresh_mirror(k);
      ++stats_.rest_fast;
      continue;
    }
    if (!vector_rocking_ || m.mode() != Mode::Rocking) {
      m.step(ax[k], ay[k], dt);
      note_violations(k);
      refresh_mirror(k);
      ++stats_.scalar;
      continue;
    }
    const std::size_t i = m_count++;
    const int s = m.side();
    const Pivot& pv = m.body().pivot(s);
    const Dopri5Stepper& st = m.dopri5();
    l.idx[i] = static_cast<std::uint32_t>(k);
    l.side[i] = s;
    l.alpha[i] = pv.alpha;
    l.p2[i] = pv.p2;
    l.atol_th[i] = settings_.tol * pv.alpha;
    l.atol_om[i] = settings_.tol * pv.p * pv.alpha;
    l.overturn[i] = m.body().overturn_angle();
    l.beyond[i] = m.outcome().beyond_tipping ? 1.0 : 0.0;
    l.ax0[i] = m.last_ax();
    l.axs[i] = (ax[k] - m.last_ax()) / dt;  // GroundInput::first_order_hold
    l.ay0[i] = m.last_ay();
    l.ays[i] = (ay[k] - m.last_ay()) / dt;
    l.theta[i] = m.theta();
    l.omega[i] = m.omega();
    l.h[i] = st.step_size();
    l.k1a[i] = st.fsal_k1(0);
    l.k1b[i] = st.fsal_k1(1);
    l.fsal[i] = st.fsal_valid() ? 1.0 : 0.0;
    l.max_ratio[i] = 0.0;
    l.steps[i] = 0.0;
    l.radius[i] = pv.radius;
    l.inertia[i] = pv.inertia;
    l.cos_al[i] = pv.cos_alpha;
    l.slide_checked[i] = std::isinf(m.body().mu_s()) ? 0.0 : 1.0;
    l.committed[i] = m.outcome().committed ? 1.0 : 0.0;
  }
  if (m_count == 0) return;
  // Pad to whole vectors with copies of the last lane (results ignored).
  const std::size_t mp = padded(m_count);
  for (std::size_t i = m_count; i < mp; ++i) {
    const std::size_t j = m_count - 1;
    for (auto* v : {&l.side, &l.alpha, &l.p2, &l.atol_th, &l.atol_om, &l.overturn, &l.beyond,
                    &l.ax0, &l.axs, &l.ay0, &l.ays, &l.theta, &l.omega, &l.h, &l.k1a, &l.k1b,
                    &l.fsal, &l.max_ratio, &l.steps, &l.radius, &l.inertia, &l.cos_al,
                    &l.slide_checked, &l.committed})
      (*v)[i] = (*v)[j];
  }

  // 3. Vector dopri5 over the sample; commit clean lanes, re-step the others from the sample start.
  batch_detail::rocking_sample(l, mp, dt, settings_.tol, trig_ == BatchTrig::Exact);
  for (std::size_t i = 0; i < m_count; ++i) {
    const std::size_t k = l.idx[i];
    RockingModel& m = models_[k];
    if (l.clean[i]) {
      m.commit_rocking_sample(ax[k], ay[k], dt, l.theta[i], l.omega[i], l.h[i], l.k1a[i],
                              l.k1b[i], static_cast<int>(l.steps[i]), l.max_ratio[i],
                              l.end_clear[i] != 0);
      ++stats_.rocking_fast;
    } else {
      m.step(ax[k], ay[k], dt);  // the model was not touched: this is the roll-back
      ++stats_.scalar;
      ++stats_.rocking_fallback;
    }
    note_violations(k);
    refresh_mirror(k);
  }
}

}  // namespace rocking_monitor::core
