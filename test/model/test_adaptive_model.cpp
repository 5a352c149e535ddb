// AdaptiveModel (issue 7, part 2): fidelity selection between RockingModel and ContactModel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "rocking_monitor/motion/synthetic_motion.hpp"
#include "test_helpers.hpp"

#include <nlohmann/json.hpp>

namespace rm = rocking_monitor::core;
using rm::AdaptiveModel;
using rm::AdaptiveSettings;
using rm::Fidelity;

namespace {

constexpr double kStandardG = 9.80665;
// Located alarm times (beyond tipping, overturn) of the two models may differ by the integrators'
// error (RockingModel dopri5 tol 1e-8 vs ContactModel RK4 16 sub-steps per sample); committed is
// evaluated at sample ends in both. Measured differences are printed by the tests.
constexpr double kTimeTol = 1e-4;

struct Input {
  std::string name;
  double dt = 0.005;
  std::vector<double> ax, ay;
};

struct RunResult {
  rm::AdaptiveOutcome o;
  rm::ContactMode final_mode = rm::ContactMode::Rest;
  std::vector<rm::SwitchRecord> switches;
  std::vector<double> theta;
  int max_steps_per_sample = 0;
  int max_rocking_samples = 0, max_contact_samples = 0, max_recomputed = 0;  // per sample
  int max_rocking_steps = 0, max_contact_steps = 0;                          // per sample
  bool steps_add_up = true;  // integrator_steps == rocking_steps + contact_steps every sample
  int revised_alarms = 0;    // samples in which an already latched alarm changed
};

bool same_time(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

// Counts latched alarms (flag set, or time known) that a later sample changed.
int revisions(const rm::AdaptiveOutcome& before, const rm::AdaptiveOutcome& now) {
  int n = 0;
  if (before.beyond_tipping && (!now.beyond_tipping ||
                                !same_time(before.beyond_tipping_time, now.beyond_tipping_time)))
    ++n;
  if (before.committed && (!now.committed || !same_time(before.committed_time, now.committed_time)))
    ++n;
  if (before.overturned && (!now.overturned || !same_time(before.overturn_time, now.overturn_time)))
    ++n;
  if (!std::isnan(before.uplift_time) && !same_time(before.uplift_time, now.uplift_time)) ++n;
  if (!std::isnan(before.first_slip_time) && !same_time(before.first_slip_time, now.first_slip_time))
    ++n;
  if (!std::isnan(before.first_flight_time) &&
      !same_time(before.first_flight_time, now.first_flight_time))
    ++n;
  if (now.max_rotation_ratio < before.max_rotation_ratio || now.impacts < before.impacts) ++n;
  return n;
}

RunResult run(const rm::BodyParameters& body, Fidelity f, const Input& in, AdaptiveSettings s = {}) {
  s.fidelity = f;
  AdaptiveModel m(body, s);
  m.reset(0.0, in.ax[0], in.ay.empty() ? 0.0 : in.ay[0]);
  RunResult r;
  r.theta.reserve(in.ax.size());
  for (std::size_t i = 1; i < in.ax.size(); ++i) {
    const rm::AdaptiveOutcome before = m.outcome();
    const rm::AdaptiveReport& rep = m.step(in.ax[i], in.ay.empty() ? 0.0 : in.ay[i], in.dt);
    r.max_steps_per_sample = std::max(r.max_steps_per_sample, rep.integrator_steps);
    r.max_rocking_samples = std::max(r.max_rocking_samples, rep.rocking_samples);
    r.max_contact_samples = std::max(r.max_contact_samples, rep.contact_samples);
    r.max_recomputed = std::max(r.max_recomputed, rep.recomputed_samples);
    r.max_rocking_steps = std::max(r.max_rocking_steps, rep.rocking_steps);
    r.max_contact_steps = std::max(r.max_contact_steps, rep.contact_steps);
    r.steps_add_up &= rep.integrator_steps == rep.rocking_steps + rep.contact_steps;
    r.revised_alarms += revisions(before, m.outcome());
    r.theta.push_back(m.theta());
  }
  r.o = m.outcome();
  r.final_mode = m.mode();
  r.switches = m.switches();
  return r;
}

double time_diff(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return 0.0;
  if (std::isnan(a) || std::isnan(b)) return 1e9;
  return std::abs(a - b);
}

// Same alarms as the richest model: flags equal, times within kTimeTol, same final mode.
// Returns the largest time difference.
double expect_same_alarms(const RunResult& a, const RunResult& c, const std::string& what) {
  EXPECT_EQ(a.o.beyond_tipping, c.o.beyond_tipping) << what;
  EXPECT_EQ(a.o.committed, c.o.committed) << what;
  EXPECT_EQ(a.o.overturned, c.o.overturned) << what;
  EXPECT_EQ(a.final_mode, c.final_mode) << what << ": " << rm::to_string(a.final_mode) << " vs "
                                        << rm::to_string(c.final_mode);
  double worst = 0.0;
  for (auto [x, y] : {std::pair{a.o.beyond_tipping_time, c.o.beyond_tipping_time},
                      std::pair{a.o.committed_time, c.o.committed_time},
                      std::pair{a.o.overturn_time, c.o.overturn_time}}) {
    const double d = time_diff(x, y);
    EXPECT_LE(d, kTimeTol) << what << ": " << x << " vs " << y;
    worst = std::max(worst, d);
  }
  return worst;
}

rm::BodyParameters box(double b, double h, double nu1, double mu_s, double mu_k = NAN) {
  rm::BodyParameters p;
  p.width = b;
  p.cg_height = h;
  p.nu1 = nu1;
  p.mu_s = mu_s;
  p.mu_k = mu_k;
  return p;
}

// config/catalogue_example.yaml, items in file order.
std::vector<std::pair<std::string, rm::BodyParameters>> catalogue() {
  std::vector<std::pair<std::string, rm::BodyParameters>> c;
  c.push_back({"medicine_cabinet", box(0.50, 0.90, 0.40, 0.6)});
  c.push_back({"monitor_cart", box(0.55, 0.75, 0.50, 0.3)});
  c.push_back({"shelving_unit", box(0.30, 0.90, 0.30, 0.6)});
  auto inc = box(0.60, 0.70, 0.50, 0.5);
  inc.restitution = 0.92;
  c.push_back({"incubator", inc});
  auto rack = box(0.60, 0.95, 0.45, 0.5);
  rack.radius_of_gyration = 0.60;
  c.push_back({"server_rack", rack});
  auto vase = box(0.15, 0.35, 0.5, 0.6);  // shape: cylinder (as src/ros/catalogue.cpp)
  vase.radius_of_gyration = std::sqrt(0.15 * 0.15 / 16.0 + 0.35 * 0.35 / 3.0);
  c.push_back({"museum_vase", vase});
  return c;
}

Input one_sine_pulse_csv() {
  Input in{"one_sine_pulse.csv"};
  std::ifstream f(std::string(ROCKING_SOURCE_DIR) + "/bags/one_sine_pulse.csv");
  EXPECT_TRUE(f.good());
  std::string line;
  double t_prev = NAN;
  while (std::getline(f, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    double t, a;
    if (std::sscanf(line.c_str(), "%lf,%lf", &t, &a) != 2) continue;
    if (!std::isnan(t_prev)) in.dt = t - t_prev;
    t_prev = t;
    in.ax.push_back(a);
  }
  in.dt = 0.005;
  return in;
}

Input ricker_input(double peak = 3.0) {
  Input in{"ricker"};
  const std::size_t n = rm::synthetic_sample_count(10.0, 0.005);
  for (std::size_t i = 0; i < n; ++i) in.ax.push_back(rm::ricker(0.005 * i, peak, 1.5, 2.0));
  return in;
}

Input quiet_noise(double seconds = 30.0) {
  Input in{"quiet_noise"};
  rm::GaussianNoise nx(0.005, 1), nz(0.005, 3);
  const std::size_t n = rm::synthetic_sample_count(seconds, 0.005);
  for (std::size_t i = 0; i < n; ++i) {
    in.ax.push_back(nx.next());
    in.ay.push_back(nz.next());
  }
  return in;
}

Input sine_pulse_input(double amp, double period, double start, double seconds, double vamp = 0.0) {
  Input in{"sine_pulse"};
  const std::size_t n = rm::synthetic_sample_count(seconds, 0.005);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 0.005 * i;
    in.ax.push_back(rm::sine_pulse(t, amp, period, start, 1.0));
    in.ay.push_back(rm::sine_pulse(t, vamp, period / 2.0, start, 1.0));
  }
  return in;
}

}  // namespace

// (a) mu_s = inf: sliding is ruled out statically. Where the RockingModel never sees free flight
// the adaptive run never switches and is the RockingModel bit for bit; where it does (the slender
// vase near overturning: R_y < 0), the only switch reason is free flight (or its early form,
// R_y < lift_off_margin g at a sample end).
TEST(AdaptiveModel, InfiniteFrictionNeverSwitchesAndEqualsRockingModelBitForBit) {
  int identical = 0, flight = 0;
  for (const Input& in : {one_sine_pulse_csv(), ricker_input(), quiet_noise(10.0)}) {
    for (auto [b, h] : {std::pair{0.15, 0.35}, std::pair{0.3, 0.9}, std::pair{0.5, 0.9},
                        std::pair{0.6, 0.95}}) {
      const rm::BodyParameters body = box(b, h, 0.5, INFINITY);
      const RunResult a = run(body, Fidelity::Adaptive, in);
      EXPECT_TRUE(a.o.sliding_ruled_out);
      rm::RockingModel ref(body, rm::SolverSettings{});
      ref.reset(0.0, in.ax[0], in.ay.empty() ? 0.0 : in.ay[0]);
      bool ref_flight = false;
      std::vector<double> theta;
      for (std::size_t i = 1; i < in.ax.size(); ++i) {
        const rm::StepReport& r = ref.step(in.ax[i], in.ay.empty() ? 0.0 : in.ay[i], in.dt);
        ref_flight |= (r.violation_onsets & (1u << int(rm::Criterion::FreeFlight))) != 0;
        theta.push_back(ref.theta());
      }
      // No friction given: pure rocking, unchanged (issue 11), also where the rocking model flags a
      // free-flight onset (the contact model is not asked to resolve flight for such a body).
      flight += ref_flight;
      ++identical;
      ASSERT_EQ(a.o.model_switches, 0) << in.name << " B " << b << " h " << h;
      EXPECT_EQ(0, std::memcmp(theta.data(), a.theta.data(), theta.size() * sizeof(double)));
      const rm::RockingOutcome& o = ref.outcome();
      EXPECT_EQ(a.o.samples_contact_model, 0);
      EXPECT_EQ(a.o.samples_rocking_model, static_cast<long>(in.ax.size() - 1));
      EXPECT_EQ(a.o.overturned, o.overturned);
      EXPECT_EQ(a.o.committed, o.committed);
      EXPECT_EQ(a.o.beyond_tipping, o.beyond_tipping);
      EXPECT_EQ(0, std::memcmp(&a.o.overturn_time, &o.overturn_time, sizeof(double)));
      EXPECT_EQ(0, std::memcmp(&a.o.committed_time, &o.committed_time, sizeof(double)));
      EXPECT_EQ(0, std::memcmp(&a.o.beyond_tipping_time, &o.beyond_tipping_time, sizeof(double)));
      EXPECT_EQ(0, std::memcmp(&a.o.max_rotation_ratio, &o.max_rotation_ratio, sizeof(double)));
      EXPECT_EQ(a.o.impacts, o.impacts);
      EXPECT_EQ(a.o.rocking_steps, o.integrator_steps);
    }
  }
  std::printf("[ measured ] %d runs bit-identical to RockingModel, %d of them with a flagged free-flight onset\n",
              identical, flight);
  EXPECT_EQ(identical, 12);
  EXPECT_GE(flight, 1) << "the inputs must include a free-flight onset, or the rule is untested";
}

TEST(AdaptiveModel, SlidingAndFlightScenesGiveTheContactModelAlarms) {
  struct Case {
    std::string name;
    rm::BodyParameters body;
    Input in;
    bool expect_switch;
  };
  std::vector<Case> cases = {
      // squat block, mu 0.2: slides from rest under the one-sine pulse
      {"slide_from_rest", box(0.8, 0.4, 0.5, 0.2), one_sine_pulse_csv(), true},
      // slender block, tan(alpha) = 0.333 < mu 0.36: rocks, then the pivot slips while rocking
      {"slide_while_rocking", box(0.3, 0.45, 0.5, 0.36), sine_pulse_input(5.0, 0.5, 0.5, 6.0), true},
      // overturning with low friction
      {"overturn_low_friction", box(0.15, 0.35, 0.5, 0.25), sine_pulse_input(8.0, 0.6, 0.5, 6.0), true},
      // vertical pulse below -g: free flight
      {"free_flight", box(0.3, 0.6, 0.5, 0.6), sine_pulse_input(1.0, 0.5, 0.5, 4.0, 14.0), true},
  };
  for (const Case& c : cases) {
    const RunResult a = run(c.body, Fidelity::Adaptive, c.in);
    const RunResult ct = run(c.body, Fidelity::Contact, c.in);
    const double worst = expect_same_alarms(a, ct, c.name);
    EXPECT_EQ(a.revised_alarms, 0) << c.name;
    EXPECT_LE(a.max_contact_samples, 1) << c.name;
    EXPECT_LE(a.max_rocking_samples, 1) << c.name;
    if (c.expect_switch) {
      EXPECT_GE(a.o.model_switches, 1) << c.name;
    }
    std::printf("[ measured ] %-22s switches %ld (first: %s), overturned %d, max alarm dt %.3g s, "
                "contact slips %ld flights %ld\n",
                c.name.c_str(), a.o.model_switches,
                a.switches.empty() ? "-" : rm::to_string(a.switches.front().reason), a.o.overturned,
                worst, ct.o.slip_episodes, ct.o.flight_episodes);
  }
}

TEST(AdaptiveModel, CatalogueOverSyntheticInputsMatchesTheRichestModel) {
  std::vector<Input> inputs = {one_sine_pulse_csv(), ricker_input(), quiet_noise()};
  for (const Input& in : inputs) {
    for (const auto& [id, body] : catalogue()) {
      const RunResult a = run(body, Fidelity::Adaptive, in);
      const RunResult c = run(body, Fidelity::Contact, in);
      const double worst = expect_same_alarms(a, c, id + " / " + in.name);
      EXPECT_EQ(a.revised_alarms, 0) << id << " / " << in.name;
      EXPECT_LE(a.max_contact_samples, 1) << id << " / " << in.name;
      std::printf("[ measured ] %-16s %-18s adaptive: rock %ld / contact %ld samples, %ld switches, "
                  "steps %ld+%ld; contact-only steps %ld; tipping %d committed %d overturned %d, "
                  "max alarm dt %.3g s\n",
                  id.c_str(), in.name.c_str(), a.o.samples_rocking_model, a.o.samples_contact_model,
                  a.o.model_switches, a.o.rocking_steps, a.o.contact_steps, c.o.contact_steps,
                  c.o.beyond_tipping, c.o.committed, c.o.overturned, worst);
    }
  }
}

// Work per sample: at most one RockingModel sample plus one ContactModel sample (the up switch
// recomputes only its own sample), each bounded by its own settings; the report's step counts add
// up; latched alarms are never revised.
TEST(AdaptiveModel, BoundedWorkOneRockingPlusOneContactSampleAndNoRevisedAlarm) {
  AdaptiveSettings s;
  s.max_switch_records = 8;
  s.hold_time_s = 0.0;
  Input alternating{"alternating"};
  for (int i = 0; i < 2000; ++i) {
    alternating.ax.push_back((i % 2 ? 3.0 : -3.0) * kStandardG * (i % 7 == 0 ? 0.1 : 1.0));
    alternating.ay.push_back((i % 5 == 0) ? -2.0 * kStandardG : (i % 3 == 0 ? kStandardG : 0.0));
  }
  // ContactModel: <= substeps sub-steps per stretch between events, <= max_events + 1 stretches.
  const int contact_bound = s.contact.substeps * (s.contact.max_events_per_sample + 1);
  long recomputed = 0, up_switches = 0;
  int worst_contact = 0, worst_rocking = 0;
  for (const Input& in : {alternating, one_sine_pulse_csv(), ricker_input(4.0)}) {
    for (AdaptiveSettings st : {s, AdaptiveSettings{}}) {
      for (const auto& [id, body] : catalogue()) {
        const RunResult a = run(body, Fidelity::Adaptive, in, st);
        const std::string what = id + " / " + in.name;
        EXPECT_LE(a.max_rocking_samples, 1) << what;
        EXPECT_LE(a.max_contact_samples, 1) << what;
        EXPECT_LE(a.max_recomputed, 1) << what;
        EXPECT_TRUE(a.steps_add_up) << what;
        EXPECT_LE(a.max_contact_steps, contact_bound) << what;
        EXPECT_LE(a.max_steps_per_sample, a.max_rocking_steps + a.max_contact_steps) << what;
        EXPECT_EQ(a.revised_alarms, 0) << what;
        EXPECT_LE(a.switches.size(), static_cast<std::size_t>(st.max_switch_records)) << what;
        EXPECT_TRUE(std::isfinite(a.theta.back())) << what;
        // every up switch recomputes exactly one sample; the work counters agree
        long ups = 0;
        for (const auto& sw : a.switches) ups += sw.to == rm::ActiveModel::Contact;
        if (a.o.model_switches <= st.max_switch_records) EXPECT_EQ(a.o.recomputed_samples, ups) << what;
        EXPECT_EQ(a.o.samples_rocking_model + a.o.samples_contact_model - a.o.recomputed_samples,
                  a.o.samples)
            << what;
        recomputed += a.o.recomputed_samples;
        up_switches += ups;
        worst_contact = std::max(worst_contact, a.max_contact_steps);
        worst_rocking = std::max(worst_rocking, a.max_rocking_steps);
      }
    }
  }
  EXPECT_GT(recomputed, 0);
  std::printf("[ measured ] %ld samples recomputed at up switches (%ld up switches in the kept switch records); "
              "worst per sample: rocking %d steps, contact %d sub-steps (bound %d)\n",
              recomputed, up_switches, worst_rocking, worst_contact, contact_bound);
  AdaptiveModel m(box(0.3, 0.6, 0.5, 0.5));
  EXPECT_THROW(m.step(0.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(m.step(NAN, 0.0, 0.005), std::invalid_argument);
  AdaptiveSettings bad;
  bad.friction_safety = 0.0;
  EXPECT_THROW(AdaptiveModel(box(0.3, 0.6, 0.5, 0.5), bad), std::invalid_argument);
}

// The hand-back to the rocking model happens only from the contact model at REST or in pure ROCK, also
// with hold_time_s = 0: there the hold test alone once passed in SLIDE-ROCK, and a body 1.27 rad over
// (about to fall) restarted upright at rest. A 0.194 x 0.456 m box (mu_s 0.68, nu1 0.49) under Kobe
// Takatori 090 slides and rocks over: the contact model alone overturns it, and so must the adaptive
// model whatever the hold time (with 0 it came back to rest).
TEST(AdaptiveModel, HandsBackOnlyFromRestOrRockEvenWithoutAHoldTime) {
  const rm::Component c = rm::read_record(std::string(ROCKING_RECORDS_DIR) + "/kobe_1995/RSN1120_KOBE_TAK090.AT2").front();
  Input in{"Takatori 090"};
  in.dt = c.dt;
  in.ax = c.accel;
  const rm::BodyParameters body = box(0.194, 0.228, 0.49, 0.68);
  const RunResult contact = run(body, Fidelity::Contact, in);
  ASSERT_TRUE(contact.o.overturned);
  for (const double hold : {0.1, 0.02, 0.0}) {
    AdaptiveSettings s;
    s.hold_time_s = hold;
    const RunResult a = run(body, Fidelity::Adaptive, in, s);
    EXPECT_TRUE(a.o.overturned) << "hold " << hold << " s";
    // No down switch moves the body: theta right after one is within a sample's motion of before.
    for (std::size_t k = 1; k < a.theta.size(); ++k)
      EXPECT_LT(std::abs(a.theta[k] - a.theta[k - 1]), 0.5) << "hold " << hold << " s, sample " << k;
  }
}

TEST(AdaptiveModel, CostsLessThanAlwaysContactOnAMostlyQuietInput) {
  // 30 s of quiet noise with one moderate Ricker burst at 10 s: tall items rock, nothing slides.
  Input in = quiet_noise(30.0);
  for (std::size_t i = 0; i < in.ax.size(); ++i) in.ax[i] += rm::ricker(0.005 * i, 2.5, 1.5, 10.0);
  long adaptive = 0, contact = 0;
  for (const auto& [id, body] : catalogue()) {
    const RunResult a = run(body, Fidelity::Adaptive, in);
    const RunResult c = run(body, Fidelity::Contact, in);
    expect_same_alarms(a, c, id + " / quiet+burst");
    adaptive += a.o.rocking_steps + a.o.contact_steps;
    contact += c.o.contact_steps;
    std::printf("[ measured ] %-16s adaptive steps %ld (rock %ld, contact %ld, %ld switches), "
                "contact-only %ld\n",
                id.c_str(), a.o.rocking_steps + a.o.contact_steps, a.o.rocking_steps,
                a.o.contact_steps, a.o.model_switches, c.o.contact_steps);
  }
  std::printf("[ measured ] total integrator steps: adaptive %ld, contact-only %ld (%.3f)\n", adaptive,
              contact, contact > 0 ? double(adaptive) / double(contact) : 0.0);
  EXPECT_LT(adaptive, contact);
}

TEST(AdaptiveModel, ImpactFrictionDemandAndReasons) {
  AdaptiveModel m(box(0.3, 0.6, 0.5, 0.5));
  // symmetric slender box: equal demand both ways, about h (1 - e) / (B (e/2 + 1/2))
  EXPECT_NEAR(m.impact_friction_demand(1), m.impact_friction_demand(-1), 1e-15);
  EXPECT_GT(m.impact_friction_demand(1), 0.0);
  EXPECT_EQ(m.initial_reason(), rm::SwitchReason::PureRockingValid);
  AdaptiveModel inf(box(0.3, 0.6, 0.5, INFINITY));
  EXPECT_EQ(inf.initial_reason(), rm::SwitchReason::FrictionRulesOutSliding);
  rm::Fidelity f;
  EXPECT_TRUE(rm::parse_fidelity("contact", f));
  EXPECT_EQ(f, Fidelity::Contact);
  EXPECT_FALSE(rm::parse_fidelity("best", f));
}

// rocking_sim --fidelity: default adaptive (= --fidelity adaptive), rocking keeps the pure-rocking
// keys and never switches, contact / adaptive agree.
TEST(RockingSimFidelity, DefaultIsAdaptiveAndAdaptiveMatchesContact) {
  const std::string base = std::string(ROCKING_SIM_EXE) + " --record " + ROCKING_SOURCE_DIR +
                           "/bags/one_sine_pulse.csv --width 0.15 --cg-height 0.35 --json";
  const auto plain = rm::testing::run_command(base);
  const auto explicit_adaptive = rm::testing::run_command(base + " --fidelity adaptive");
  const auto rocking = rm::testing::run_command(base + " --fidelity rocking");
  ASSERT_EQ(plain.status, 0);
  ASSERT_EQ(rocking.status, 0);
  auto jp = nlohmann::json::parse(plain.out), je = nlohmann::json::parse(explicit_adaptive.out),
       jr = nlohmann::json::parse(rocking.out);
  EXPECT_EQ(jp["fidelity"], "adaptive");
  for (auto* j : {&jp, &je})
    for (const char* k : {"cpu_time_s", "planes"}) j->erase(k);  // timings (planes.x repeats the top level)
  EXPECT_EQ(jp, je);
  EXPECT_EQ(jr["fidelity"], "rocking");
  EXPECT_EQ(jr["model_switches"], 0);
  EXPECT_EQ(jr["samples_contact_model"], 0);
  EXPECT_TRUE(jr.contains("violations") && jr.contains("rest_captures") && jr.contains("body"));
  const auto adaptive = rm::testing::run_command(base + " --mu-s 0.6 --mu-k 0.5 --fidelity adaptive");
  const auto contact = rm::testing::run_command(base + " --mu-s 0.6 --mu-k 0.5 --fidelity contact");
  ASSERT_EQ(adaptive.status, 0);
  ASSERT_EQ(contact.status, 0);
  auto ja = nlohmann::json::parse(adaptive.out), jc = nlohmann::json::parse(contact.out);
  EXPECT_EQ(ja["fidelity"], "adaptive");
  EXPECT_GE(ja["model_switches"].get<int>(), 1);
  EXPECT_EQ(ja["switch_reasons"][0]["to"], "contact_model");
  EXPECT_TRUE(ja["switch_reasons"][0].contains("reason"));
  EXPECT_GT(ja["samples_rocking_model"].get<long>(), 0);
  EXPECT_EQ(jc["samples_rocking_model"], 0);
  for (const char* k : {"overturned", "committed", "beyond_tipping", "final_mode"})
    EXPECT_EQ(ja[k], jc[k]) << k;
  for (const char* k : {"overturn_time_s", "committed_time_s", "beyond_tipping_time_s"})
    EXPECT_NEAR(ja[k].get<double>(), jc[k].get<double>(), kTimeTol) << k;
  EXPECT_NE(rm::testing::run_command(base + " --fidelity best 2>&1").status, 0);
}

TEST(RockingSimFidelity, SceneEnvelopeAndLinearizedOptions) {
  const std::string base = std::string(ROCKING_SIM_EXE) + " --record " + ROCKING_SOURCE_DIR +
                           "/bags/one_sine_pulse.csv --width 0.50 --cg-height 0.90 --eccentricity 0.4"
                           " --mu-s 0.6 --fidelity adaptive --json";
  // auto: the record's own peak (4.0 m/s^2, no vertical) -> the same bound as given explicitly.
  const auto autoj = rm::testing::run_command(base);
  const auto given = rm::testing::run_command(base + " --scene 4.0,0");
  const auto unknown = rm::testing::run_command(base + " --scene unknown");
  ASSERT_EQ(autoj.status, 0);
  ASSERT_EQ(given.status, 0);
  ASSERT_EQ(unknown.status, 0);
  const auto ja = nlohmann::json::parse(autoj.out), jg = nlohmann::json::parse(given.out),
             ju = nlohmann::json::parse(unknown.out);
  EXPECT_NEAR(ja["scene"]["horizontal_mps2"].get<double>(), 4.0, 1e-6);
  EXPECT_EQ(ja["scene"]["vertical_mps2"].get<double>(), 0.0);
  EXPECT_NEAR(ja["scene"]["required_mu"].get<double>(), jg["scene"]["required_mu"].get<double>(), 1e-6);
  EXPECT_LT(ja["scene"]["required_mu"].get<double>(), 0.6);
  EXPECT_TRUE(ja["sliding_ruled_out"].get<bool>());
  EXPECT_EQ(ja["samples_contact_model"], 0);
  EXPECT_EQ(ja["initial_model_reason"],
            "friction rules out sliding, slip at impact and flight in the scene envelope");
  EXPECT_TRUE(ju["scene"]["required_mu"].is_null());
  EXPECT_EQ(ju["initial_model_reason"], "pure rocking valid");
  for (const char* k : {"overturned", "committed", "beyond_tipping", "final_mode"})
    EXPECT_EQ(ja[k], ju[k]) << k;
  EXPECT_EQ(ja["samples_linearized_model"], 0);  // tier off by default
  for (const char* bad : {" --scene 1,x", " --scene -1,0", " --scene 3", " --linearized-max-alpha -1"}) {
    const auto r = rm::testing::run_command(base + bad + " 2>&1");
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_NE(r.out.find(std::string(bad).substr(3, 5)), std::string::npos) << bad << ": " << r.out;
  }
}
