// rocking_accuracy work-precision: cost against error of every method setting (work_precision.csv).

#include "accuracy_common.hpp"
#include "accuracy_parts.hpp"

namespace rocking_monitor::bench::accuracy {

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::core;  // NOLINT(google-build-using-namespace): as in every bench file

namespace {

// ------------------------------------------------------------------ work-precision
struct Case {
  std::string kind;  // free | pulse | record
  std::string name;
  BodyParameters body;
  GroundMotion motion;
  double theta0 = 0.0;
};

std::vector<Case> work_precision_cases(const std::string& records, bool quick) {
  std::vector<Case> cases;
  for (double rate : {200.0, 50.0}) {
    const double dt = 1.0 / rate;
    const std::string tag = "@" + std::to_string(static_cast<int>(rate)) + "Hz";
    // Free rocking: the NOTES.md block (p = 2, alpha = 15 deg) from alpha/2 until rest, and a
    // small stiff item (p = 8 rad/s, alpha = 10 deg) from 0.7 alpha.
    cases.push_back({"free", "p2_a15" + tag, rb::rectangle_with(2.0, rb::deg(15)), rb::zeros(dt, 11.0),
                     0.5 * rb::deg(15)});
    cases.push_back({"free", "p8_a10" + tag, rb::rectangle_with(8.0, rb::deg(10)), rb::zeros(dt, 4.0),
                     0.7 * rb::deg(10)});
    // One-sine pulses just below/above the closed-form boundary (p = 2.5, alpha = 12 deg).
    for (double wp : {2.0, 4.0}) {
      for (double f : {0.997, 1.003}) {
        const double p = 2.5, alpha = rb::deg(12), w = wp * p;
        char nm[64];
        std::snprintf(nm, sizeof nm, "wp%g_a%.3f%s", wp, f, tag.c_str());
        cases.push_back({"pulse", nm, rb::rectangle_with(p, alpha),
                         rb::one_sine_pulse(f * rb::pulse_min_amplitude_ratio(wp) * alpha * kGravity, w,
                                            dt, 2.0 * kPi / w + 8.0)});
      }
    }
  }
  // Real records at their own sampling rate (100-250 Hz), a 0.4 x 1.2 m cabinet and a small
  // vase-like item (0.12 x 0.3 m).
  if (rb::records_available(records)) {
    const std::vector<std::pair<std::string, std::string>> recs = {
        {"rinaldi228", "northridge_1994/Rinaldi228.AT2"},
        {"lucerne345", "landers_1992/RSN879_LANDERS_LCN345.AT2"},
        {"elcentro5", "imperial_valley_1979/RSN180_IMPVALL.H_H-E05140.AT2"},
        {"takatori090", "kobe_1995/RSN1120_KOBE_TAK090.AT2"},
    };
    BodyParameters cabinet, vase;
    cabinet.width = 0.4;
    cabinet.cg_height = 0.6;
    vase.width = 0.12;
    vase.cg_height = 0.15;
    for (const auto& [nm, file] : recs) {
      try {
        const GroundMotion g = rb::load_record(records + "/" + file);
        cases.push_back({"record", nm + "_cabinet", cabinet, g});
        if (!quick) cases.push_back({"record", nm + "_vase", vase, g});
      } catch (const std::exception& e) {
        std::fprintf(stderr, "rocking_accuracy: skipping %s: %s\n", file.c_str(), e.what());
      }
    }
  } else {
    std::fprintf(stderr, "rocking_accuracy: records folder %s not found: record cases skipped\n",
                 records.c_str());
  }
  return cases;
}

}  // namespace

/// Returns the number of exact-trig batch runs that are not the scalar dopri5 run bit for bit
/// (0 expected: BatchTrig::Exact is documented bit-identical).
int work_precision(const std::string& out_dir, const std::string& records, bool quick,
                   std::size_t batch_lanes) {
  const std::vector<Case> cases = work_precision_cases(records, quick);
  std::ofstream os(out_dir + "/work_precision.csv");
  os << "model,input,case,sample_rate_hz,method,label,param,ns_per_sim_s,ns_per_item_step,"
        "steps_per_sample,err_peak,err_impact_s,err_overturn_s,overturned,ref_overturned,impacts,"
        "ref_impacts,max_ratio,ref_max_ratio,lanes\n";
  std::fprintf(stderr, "work-precision: batch engine with %zu identical lanes, SIMD target %s\n",
               batch_lanes, BatchRocking::simd_target());
  int mismatches = 0;
  for (ModelKind model : {ModelKind::Nonlinear, ModelKind::Linearized}) {
    const std::vector<rb::MethodSetting> settings = rb::all_settings(model, !quick);
    for (const Case& c : cases) {
      const Run ref = reference_run(c.body, model, c.motion, c.theta0);
      const double samples = static_cast<double>(c.motion.size() - 1);
      auto write_row = [&](const std::string& method, const std::string& label, double param,
                           const Run& r, std::size_t lanes) {
        const double e_over = r.outcome.overturned && ref.outcome.overturned
                                  ? std::abs(r.outcome.overturn_time - ref.outcome.overturn_time)
                                  : kNaN;
        os << to_string(model) << ',' << c.kind << ',' << c.name << ',' << fmt(1.0 / c.motion.dt)
           << ',' << method << ',' << label << ',' << fmt(param) << ','
           << fmt(1e9 * r.seconds / r.duration) << ',' << fmt(1e9 * r.seconds / samples) << ','
           << fmt(static_cast<double>(r.outcome.integrator_steps) / samples) << ','
           << fmt(peak_error(r, ref)) << ',' << fmt(impact_time_error(r, ref)) << ','
           << fmt(e_over) << ',' << r.outcome.overturned << ',' << ref.outcome.overturned << ','
           << r.outcome.impacts << ',' << ref.outcome.impacts << ','
           << fmt(r.outcome.max_rotation_ratio) << ',' << fmt(ref.outcome.max_rotation_ratio) << ','
           << lanes << '\n';
      };
      for (const rb::MethodSetting& ms : settings) {
        const Run r = run_timed(c.body, ms.settings, c.motion, c.theta0);
        write_row(ms.method, ms.label, ms.param, r, 1);
        // The batch engine vectorizes nonlinear dopri5 only (other settings: RockingModel::step).
        if (model != ModelKind::Nonlinear || ms.method != "dopri5") continue;
        for (BatchTrig trig : {BatchTrig::Exact, BatchTrig::Fast}) {
          const bool exact = trig == BatchTrig::Exact;
          long lanes_differing = 0;
          const Run b = run_batch_timed(c.body, ms.settings, c.motion, c.theta0, trig, batch_lanes,
                                        lanes_differing);
          char tol[16];
          std::snprintf(tol, sizeof tol, "%.0e", ms.param);
          write_row(exact ? "batch_exact" : "batch_fast",
                    std::string("batch dopri5 (") + (exact ? "exact" : "fast") + " trig) tol=" + tol,
                    ms.param, b, batch_lanes);
          if (!exact) continue;
          std::string d = bitwise_difference(b, r);
          if (lanes_differing != 0) {
            d += (d.empty() ? "" : ", ") + std::to_string(lanes_differing) +
                 " lanes differ from lane 0";
          }
          if (!d.empty()) {
            ++mismatches;
            std::fprintf(stderr,
                         "rocking_accuracy: error: batch dopri5 (exact trig) is not bit-identical to "
                         "scalar dopri5 on %s, tol %s: %s\n",
                         c.name.c_str(), tol, d.c_str());
          }
        }
      }
      std::fprintf(stderr, "work-precision: %s %s %s done\n", to_string(model), c.kind.c_str(),
                   c.name.c_str());
    }
  }
  if (mismatches == 0)
    std::fprintf(stderr, "work-precision: batch dopri5 (exact trig) bit-identical to scalar dopri5 "
                         "in every nonlinear case and tolerance\n");
  return mismatches;
}

}  // namespace rocking_monitor::bench::accuracy
