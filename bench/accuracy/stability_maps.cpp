// rocking_accuracy stability: stability maps of the method settings (stability_map.csv).

#include "accuracy_common.hpp"
#include "accuracy_parts.hpp"

namespace rocking_monitor::bench::accuracy {

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::core;  // NOLINT(google-build-using-namespace): as in every bench file

namespace {

// ------------------------------------------------------------------ stability maps
/// Accumulation time of linearized free rocking from phi0 alpha (closed form, NOTES.md): the
/// quarter period, then the half periods of the decaying amplitudes phi_n, with
/// 1 - (1 - phi_n)^2 = eta^(2n) [1 - (1 - phi0)^2] and eta = 1 - 1.5 sin^2(alpha).
double accumulation_time(double p, double alpha, double phi0) {
  const double eta = 1.0 - 1.5 * std::sin(alpha) * std::sin(alpha);
  const double s0 = std::sqrt(1.0 - (1.0 - phi0) * (1.0 - phi0));
  auto half = [&](double phi) { return 2.0 / p * std::acosh(1.0 / (1.0 - phi)); };
  double t = half(phi0) / 2.0;
  for (int n = 1; n < 100000; ++n) {
    const double s = std::pow(eta, n) * s0;
    const double phi = 1.0 - std::sqrt(1.0 - s * s);
    if (phi < 1e-15) break;
    t += half(phi);
  }
  return t;
}

struct MapBody {
  double p;
  double alpha;  // rad
  double dt;     // input sample interval, s
  GroundMotion free;
  std::vector<double> pulse_wps;     // omega_p / p of the pulses resolved by the input (>= 8 samples)
  std::vector<double> boundary;      // per pulse_wps: the reference's overturning amplitude, m/s^2
  std::vector<GroundMotion> pulses;  // around each boundary
  Run ref_free;
  std::vector<Run> ref_pulses;
};

struct MapCell {
  rb::MethodSetting ms;
  std::size_t body;  // index into the MapBody list
};

}  // namespace

/// The stability maps: every method against the nonlinear reference over body p (and alpha) and
/// the step size (rk4: feed interval / substeps; dopri5: tolerance at a fine and a coarse feed;
/// analytic: alpha, since it is exact for the linearized model at any step).
void stability_maps(const std::string& out_dir, int jobs, bool quick, bool quiet) {
  const std::vector<double> ps = quick ? std::vector<double>{1, 4, 16, 64}
                                       : std::vector<double>{1, 1.5, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
  const std::vector<double> alphas_deg =
      quick ? std::vector<double>{5, 25} : std::vector<double>{2, 5, 10, 15, 20, 25, 30, 35};
  const std::vector<double> step_alphas_deg = {5, 25};  // slender and stocky
  const std::vector<double> feeds_hz = {200, 100, 50, 20, 10};
  // Pulses at 0.01 %, 0.1 % and 1 % of the reference's own overturning boundary, either side.
  const std::vector<double> pulse_factors = {0.99, 0.999, 0.9999, 1.0001, 1.001, 1.01};
  const std::vector<double> pulse_wps = {2.0, 4.0};
  auto is_step_alpha = [&](double a_deg) {
    return std::any_of(step_alphas_deg.begin(), step_alphas_deg.end(),
                       [&](double x) { return std::abs(x - a_deg) < 1e-9; });
  };

  std::vector<MapBody> bodies;
  for (double feed : feeds_hz) {
    for (double a : alphas_deg) {
      if (feed != 200.0 && !is_step_alpha(a)) continue;  // other alphas: analytic map at 200 Hz
      for (double p : ps) {
        MapBody b;
        b.p = p;
        b.alpha = rb::deg(a);
        b.dt = 1.0 / feed;
        const double t_free = std::min(200.0, 1.2 * accumulation_time(p, b.alpha, 0.5) + 2.0 / p);
        b.free = rb::zeros(b.dt, t_free);
        for (double wp : pulse_wps) {
          const double w = wp * p;
          if (2.0 * kPi / w < 8.0 * b.dt) continue;  // the pulse would not be resolved by the input
          b.pulse_wps.push_back(wp);
        }
        bodies.push_back(std::move(b));
      }
    }
  }
  rocking_monitor::tools::ProgressMeter reference_progress("references", quiet);
  parallel_for(bodies.size(), jobs, [&](std::size_t i) {
    MapBody& b = bodies[i];
    const BodyParameters body = rb::rectangle_with(b.p, b.alpha);
    b.ref_free = reference_run(body, ModelKind::Nonlinear, b.free, 0.5 * b.alpha);
    for (double wp : b.pulse_wps) {
      // The reference's overturning amplitude near the linearized closed form, by bisection (the
      // boundary is not monotonic in general: this finds one sign change of "overturned").
      const double w = wp * b.p, t_end = 2.0 * kPi / w + 20.0 / b.p;
      auto pulse = [&](double ap) { return rb::one_sine_pulse(ap, w, b.dt, t_end); };
      auto overturns = [&](double ap) {
        return reference_run(body, ModelKind::Nonlinear, pulse(ap), 0.0).outcome.overturned;
      };
      const double a_lin = rb::pulse_min_amplitude_ratio(wp) * b.alpha * kGravity;
      double lo = 0.3 * a_lin, hi = 3.0 * a_lin;
      if (overturns(lo) || !overturns(hi)) continue;
      for (int it = 0; it < 30; ++it) {
        const double mid = 0.5 * (lo + hi);
        (overturns(mid) ? hi : lo) = mid;
      }
      const double a_star = 0.5 * (lo + hi);
      b.boundary.push_back(a_star);
      for (double f : pulse_factors) {
        b.pulses.push_back(pulse(f * a_star));
        b.ref_pulses.push_back(reference_run(body, ModelKind::Nonlinear, b.pulses.back(), 0.0));
      }
    }
  }, &reference_progress);
  std::fprintf(stderr, "stability: %zu references done\n", bodies.size());

  std::vector<MapCell> cells;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const MapBody& b = bodies[i];
    const double a = b.alpha * 180.0 / kPi;
    const double feed = 1.0 / b.dt;
    if (is_step_alpha(a)) {
      // rk4: at 200 Hz with 1..32 sub-steps, and one step per sample at the coarser feeds.
      if (std::abs(feed - 200.0) < 1e-6) {
        for (int n : {1, 2, 4, 8, 16, 32}) cells.push_back({rb::rk4_setting(n, ModelKind::Nonlinear), i});
      } else {
        cells.push_back({rb::rk4_setting(1, ModelKind::Nonlinear), i});
      }
      // dopri5: tolerances at 200 Hz (steps capped by the samples) and 20 Hz (tolerance-limited).
      if (std::abs(feed - 200.0) < 1e-6 || std::abs(feed - 20.0) < 1e-6)
        for (double tol : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10})
          cells.push_back({rb::dopri5_setting(tol, ModelKind::Nonlinear), i});
    }
    if (std::abs(feed - 200.0) < 1e-6) cells.push_back({rb::analytic_setting(), i});
  }

  std::vector<std::string> rows(cells.size());
  rocking_monitor::tools::ProgressMeter progress("cells", quiet);
  parallel_for(cells.size(), jobs, [&](std::size_t i) {
    const MapCell& c = cells[i];
    const MapBody& b = bodies[c.body];
    const BodyParameters body = rb::rectangle_with(b.p, b.alpha);
    const Run r = run_once(body, c.ms.settings, b.free, 0.5 * b.alpha);
    int wrong = 0, total = 0, max_steps = r.max_steps, max_impacts = r.max_impacts;
    double max_ratio_err = 0.0;
    for (std::size_t k = 0; k < b.pulses.size(); ++k) {
      const Run pm = run_once(body, c.ms.settings, b.pulses[k], 0.0);
      const Run& pr = b.ref_pulses[k];
      ++total;
      wrong += pm.outcome.overturned != pr.outcome.overturned;
      if (!pm.outcome.overturned && !pr.outcome.overturned)
        max_ratio_err = std::max(max_ratio_err, std::abs(pm.outcome.max_rotation_ratio -
                                                         pr.outcome.max_rotation_ratio));
      max_steps = std::max(max_steps, pm.max_steps);
      max_impacts = std::max(max_impacts, pm.max_impacts);
    }
    // Where the method puts the overturning boundary, relative to the reference's: bisection
    // inside +-5 % of the reference amplitude (0.05 = off by 5 % or more).
    double boundary_shift = b.boundary.empty() ? kNaN : 0.0;
    for (std::size_t j = 0; j < b.boundary.size(); ++j) {
      const double w = b.pulse_wps[j] * b.p, t_end = 2.0 * kPi / w + 20.0 / b.p;
      auto overturns = [&](double ap) {
        return run_once(body, c.ms.settings, rb::one_sine_pulse(ap, w, b.dt, t_end), 0.0)
            .outcome.overturned;
      };
      const double a_ref = b.boundary[j];
      double lo = 0.95 * a_ref, hi = 1.05 * a_ref;
      if (overturns(lo) || !overturns(hi)) {
        boundary_shift = std::max(boundary_shift, 0.05);
        continue;
      }
      for (int it = 0; it < 25; ++it) {
        const double mid = 0.5 * (lo + hi);
        (overturns(mid) ? hi : lo) = mid;
      }
      boundary_shift = std::max(boundary_shift, std::abs(0.5 * (lo + hi) - a_ref) / a_ref);
    }
    const Run& ref = b.ref_free;
    const double h = c.ms.method == "rk4" ? b.dt / c.ms.param : b.dt;
    std::ostringstream os;
    os << c.ms.method << ',' << c.ms.label << ',' << fmt(c.ms.param) << ','
       << to_string(c.ms.settings.model) << ",nonlinear," << fmt(1.0 / b.dt) << ',' << fmt(h) << ','
       << fmt(b.p) << ',' << fmt(b.alpha * 180.0 / kPi) << ',' << fmt(b.p * h) << ','
       << r.outcome.impacts << ',' << ref.outcome.impacts << ',' << fmt(impact_time_error(r, ref))
       << ',' << fmt(energy_gain(r)) << ',' << fmt(energy_gain(ref)) << ',' << fmt(r.rest_time)
       << ',' << fmt(ref.rest_time) << ',' << r.outcome.rest_captures << ','
       << r.outcome.forced_rest_captures << ',' << r.outcome.overturned << ','
       << fmt(peak_error(r, ref)) << ',' << wrong << ',' << total << ',' << fmt(boundary_shift)
       << ',' << fmt(max_ratio_err)
       << ',' << max_impacts << ',' << ref.max_impacts << ',' << max_steps << ','
       << fmt(b.free.dt * static_cast<double>(b.free.size() - 1)) << '\n';
    rows[i] = os.str();
  }, &progress);
  std::ofstream os(out_dir + "/stability_map.csv");
  os << "method,label,param,model,ref_model,feed_hz,h,p,alpha_deg,p_h,impacts,ref_impacts,"
        "err_impact_s,energy_gain,ref_energy_gain,rest_time,ref_rest_time,rest_captures,"
        "forced_rest,free_overturned,free_err_peak,pulse_wrong,pulse_total,boundary_shift,pulse_err_ratio,"
        "max_impacts_per_sample,ref_max_impacts_per_sample,max_steps_per_sample,free_duration_s\n";
  for (const std::string& r : rows) os << r;
}

}  // namespace rocking_monitor::bench::accuracy
