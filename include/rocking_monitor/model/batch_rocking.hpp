#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rocking_monitor/model/rocking_model.hpp"

namespace rocking_monitor::core {

/// How the batch engine evaluates sin/cos inside its vectorized dopri5 stages.
enum class BatchTrig : std::uint8_t {
  /// std::sin / std::cos per lane (the scalar model's own calls): every lane is bit-identical to
  /// a RockingModel stepped alone (the option for cross-checks; the bit-for-bit tests use it).
  Exact,
  /// Highway's vectorized Sin/Cos (hwy/contrib/math, a few ulp): faster, not bit-identical. Default:
  /// it passes the accuracy policy (`rocking_accuracy policy`, docs/performance.md): its decisions
  /// and event times agree with a converged reference wherever the scalar tol-1e-8 run's do.
  Fast,
};

/// Per-sample counters of the last step() (what bounds the batch's cost).
struct BatchStats {
  std::size_t rest_fast = 0;  ///< lanes at REST shown by the vector uplift test to stay there, and OVERTURNED lanes
  std::size_t rocking_fast = 0;    ///< ROCKING lanes stepped by the vector dopri5 and committed
  std::size_t scalar = 0;          ///< lanes stepped by RockingModel::step (events, uplift, ...)
  std::size_t rocking_fallback = 0;  ///< of those: vector-stepped lanes rolled back to scalar
};

/// N planar pure-rocking bodies that share input samples, stepped together: structure-of-arrays
/// mirrors and SIMD across lanes (Highway, runtime dispatch: AVX-512 / AVX2 / SSE / scalar).
///
/// Exactness: the batch owns one RockingModel per lane, which stays the authority. Per sample:
///  - lanes at REST: a vectorized closed-form uplift test on the piecewise-linear input (the sign
///    of theta'' at theta = 0, eq. 19, at both ends of the sample, with a safety margin). Lanes
///    that surely stay at rest only advance (RockingModel::advance_at_rest); the others are
///    stepped by RockingModel::step.
///  - ROCKING lanes (dopri5 only): vectorized dopri5 steps over the sample with the scalar
///    controller (same step-size sequence, rejections, FSAL, arithmetic order), on the lane's
///    state kept in place in per-lane arrays (gathered by the kernel). A lane in which a step
///    meets anything (theta reaching 0 = impact, a turning point of
///    theta, |theta| crossing alpha for the first time, the overturn angle, a non-finite value)
///    is dropped and stepped from its state at the sample start by RockingModel::step. The kernel
///    also screens the sample end (Highway Sin/Cos, wide margins): when the ground reaction is
///    surely > 0 (no free flight), sliding is not checked (mu_s not given) and the body is surely
///    not committed (or already latched), nothing at the sample end can change the model's
///    criteria or committed flag. Such clean samples stay in the lanes (deferred rocking: the
///    model is not touched; RockingModel::apply_rocking_samples brings it up to date when it is
///    read or must step itself); other clean samples are written back with
///    RockingModel::commit_rocking_sample, which finishes the sample exactly as step() does.
///  - everything else (rk4 / analytic settings, the linearized model) is stepped by
///    RockingModel::step.
///  - deferred rest: a lane at REST that stays there and whose sample end violates nothing
///    (mu_s not given, a_yg + g > 0 with a margin) is not touched at all: the batch adds dt to
///    its own copy of the lane's time (the same additions as RockingModel::step) and counts the
///    sample; the model is brought up to date (RockingModel::apply_rest_samples) before it is
///    stepped again and whenever model(k) / report(k) is called.
///    Lanes OVERTURNED with committed latched are deferred the same way (step() only counts time).
/// With BatchTrig::Exact every lane equals a RockingModel stepped alone, bit for bit; with Fast (the
/// default) its decisions and event times meet the accuracy policy.
/// step() does no allocation (the work arrays are sized at construction).
class BatchRocking {
 public:
  BatchRocking(const std::vector<BodyParameters>& bodies, const SolverSettings& settings,
               BatchTrig trig = BatchTrig::Fast);

  std::size_t size() const { return models_.size(); }
  /// Every lane back to REST at time t with the same ground acceleration.
  void reset(double t, double ax = 0.0, double ay = 0.0);
  /// Steps every lane one sample: lane k's ground acceleration goes linearly from its previous
  /// input to (ax[k], ay[k]) over dt seconds. Throws std::invalid_argument (nothing stepped) for a
  /// non-finite input or dt <= 0.
  void step(const double* ax, const double* ay, double dt);
  /// The same input for every lane.
  void step_all(double ax, double ay, double dt);

  /// Lane k's model, brought up to date (see "Deferred rest" above). The reference is valid until
  /// the next step().
  const RockingModel& model(std::size_t k) const {
    sync(k);
    return models_[k];
  }
  /// For set-up only (set_state, reset of one lane); never while step() runs.
  RockingModel& model(std::size_t k) {
    sync(k);
    mirrors_stale_ = true;
    return models_[k];
  }
  const StepReport& report(std::size_t k) const { return model(k).last_report(); }
  /// Lane k's violation onsets since reset(), OR-ed over every sample (bit 1 << Criterion), and the
  /// time of the first one (NaN: none): what a caller that does not read report(k) after every step
  /// (which would undo the deferred rest) needs. A deferred-rest sample has no onset by construction.
  std::uint8_t violations_seen(std::size_t k) const { return seen_[k]; }
  double first_violation_time(std::size_t k) const { return first_violation_[k]; }
  const BatchStats& stats() const { return stats_; }
  BatchTrig trig() const { return trig_; }
  /// The SIMD target Highway chose at run time (e.g. "AVX3", "AVX2").
  static const char* simd_target();

  /// Work arrays of the vector kernels, structure of arrays (public for the kernels only).
  struct Lanes {
    // Per lane, constant: both pivots (index 0: corner 1, index 1: corner 2).
    std::vector<double> sin_a[2], cos_a[2];
    // Uplift test (per lane): inputs and a result flag (1 = may lift: scalar).
    std::vector<double> ax_prev, ay_prev, ax_now, ay_now;
    std::vector<std::uint8_t> rest, maybe_lift;
    // OVERTURNED with committed latched: its samples only count time (deferred like rest).
    std::vector<std::uint8_t> over;
    // Mirrors of the models (valid when mirrors_stale_ is false) and the deferred rest samples.
    std::vector<double> t;
    std::vector<long> deferred;
    std::vector<std::uint8_t> mu_inf;
    // ROCKING lanes, kept in place (index = lane): vr = 1.0 when the lane's model is ROCKING under
    // dopri5 and the arrays below mirror it (constants of its pivot, state at the sample start).
    // Clean samples stay here (rocking_deferred) until the model is read or must step itself.
    std::vector<double> vr;
    std::vector<double> side, alpha, p2, atol_th, atol_om, overturn, beyond;
    std::vector<double> theta, omega, h, k1a, k1b, fsal;
    // Sample-end screen (criteria, committed test): per lane pivot R, I_O/m, cos(alpha), whether
    // sliding is checked (finite mu_s) and whether committed is already latched.
    std::vector<double> radius, inertia, cos_al, slide_checked, committed;
    // Screens of other callers (MonitorBatch: the adaptive model's early switch margins), 0 for
    // BatchRocking: a checked sliding criterion also counts as clear when |R_x| stays below
    // mu_clear R_y, and the sample end is clear only with R_y above ry_min (m/s^2), both with margins.
    std::vector<double> mu_clear, ry_min;
    // Kernel results of this sample (the state above is left as it was at the sample start).
    std::vector<double> theta_out, omega_out, h_out, k1a_out, k1b_out, max_ratio, steps;
    std::vector<std::uint8_t> clean, end_clear;
    // Clean samples not yet applied to the model: count, step counts, largest |theta|/alpha.
    std::vector<long> rocking_deferred, pending_steps;
    std::vector<int> last_steps;
    std::vector<double> pending_max, last_dt;
    // The vr lanes of this sample (the kernel's work list), padded with copies of the last.
    std::vector<std::uint32_t> idx;

    /// n lanes (a multiple of batch_detail::kBlock) of everything the rocking kernel reads and writes,
    /// its inputs and the deferred samples' accumulators, all zero.
    void size_rocking(std::size_t n);
    /// Lane k's clean sample whose end changes nothing stays in the lane: the kernel's sample end
    /// becomes its state, the sample's steps and largest ratio are accumulated, (x1, y1) is its last input.
    void keep_rocking_sample(std::size_t k, double x1, double y1) {
      theta[k] = theta_out[k];
      omega[k] = omega_out[k];
      h[k] = h_out[k];
      k1a[k] = k1a_out[k];
      k1b[k] = k1b_out[k];
      fsal[k] = 1.0;
      const int n = static_cast<int>(steps[k]);
      pending_steps[k] += n;
      last_steps[k] = n;
      pending_max[k] = std::max(pending_max[k], max_ratio[k]);
      ax_prev[k] = x1;
      ay_prev[k] = y1;
    }
  };
  /// Lane k of the rocking kernel from a ROCKING model under dopri5 (nonlinear): its pivot's constants,
  /// flags and integrator state (not the inputs, vr, mu_clear or ry_min). Also for other owners of lanes.
  static void mirror_rocking(Lanes& l, std::size_t k, const RockingModel& m);

 private:
  void sync(std::size_t k) const {
    if (lanes_.deferred[k] != 0) flush(k);
    if (lanes_.rocking_deferred[k] != 0) flush_rocking(k);
  }
  void flush(std::size_t k) const;
  void flush_rocking(std::size_t k) const;
  void refresh_mirror(std::size_t k);
  void note_violations(std::size_t k);  // after lane k's model stepped this sample
  // step()'s steps, in its order (batch_rocking.cpp).
  void check_sample(const double* ax, const double* ay, double dt) const;  // throws, nothing stepped
  void refresh_mirrors();
  void test_uplift(const double* ax, const double* ay);
  void rock_lanes(double dt);
  bool defer_sample(std::size_t k, const double* ax, const double* ay, double dt);
  void step_model(std::size_t k, const double* ax, const double* ay, double dt);

  mutable std::vector<RockingModel> models_;
  bool mirrors_stale_ = true;
  SolverSettings settings_;
  BatchTrig trig_;
  bool vector_rocking_ = false;  // dopri5 + nonlinear model
  long vr_count_ = 0;            // lanes with lanes_.vr set
  mutable Lanes lanes_;
  BatchStats stats_;
  std::vector<double> bcast_ax_, bcast_ay_;
  std::vector<std::uint8_t> seen_;
  std::vector<double> first_violation_;
};

namespace batch_detail {
/// Vector uplift test over all lanes (l.maybe_lift for lanes with l.rest set), n lanes.
void uplift_test(BatchRocking::Lanes& l, std::size_t n, bool linearized);
/// The rocking kernel's work list is padded to a multiple of this (of every SIMD width x unroll).
constexpr std::size_t kBlock = 16;
/// Vector dopri5 over the sample [0, dt] for the m lanes l.idx[0..m) (m a multiple of kBlock):
/// reads their state in place, writes their *_out arrays, l.clean and l.end_clear.
void rocking_sample(BatchRocking::Lanes& l, std::size_t m, double dt, double tol, bool exact_trig);
/// The same for the lanes idx[0..m) (a caller's own work list; disjoint lists may run on different threads).
void rocking_sample(BatchRocking::Lanes& l, const std::uint32_t* idx, std::size_t m, double dt, double tol,
                    bool exact_trig);
const char* target_name();
/// sin and cos of n values (n a multiple of 16) the way the dopri5 kernel evaluates them
/// (benchmarks: the cost of the trigonometry per stage).
void sincos_lanes(const double* x, double* s, double* c, std::size_t n, bool exact_trig);
}  // namespace batch_detail

}  // namespace rocking_monitor::core
