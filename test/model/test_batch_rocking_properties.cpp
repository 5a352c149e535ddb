// BatchRocking (model/batch_rocking.hpp) against the scalar RockingModel, its oracle, on randomized
// bodies, other solver settings, ten thousand lanes and every SIMD target (bit-identical with
// BatchTrig::Exact), and the fast trig path against the accuracy policy.
#include <gtest/gtest.h>
#include <hwy/targets.h>

#include "batch_rocking_fixtures.hpp"

namespace rocking_monitor::core {
namespace {

using testing::deg;
using testing::rectangle_with;

// ---------------------------------------------------------------- randomized property test
std::vector<BodyParameters> random_bodies(std::size_t n, std::uint64_t seed) {
  std::uint64_t s = seed;
  auto next = [&]() {
    std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  auto uni = [&](double a, double b) { return a + (b - a) * (next() >> 11) * 0x1.0p-53; };
  std::vector<BodyParameters> out(n);
  for (BodyParameters& b : out) {
    b.width = uni(0.1, 1.0);
    b.cg_height = uni(0.2, 1.5);
    b.nu1 = uni(0.25, 0.75);
  }
  return out;
}

std::vector<Input> property_inputs() {
  std::vector<Input> out{pulse_csv()};
  for (const char* file : {"northridge_1994/Rinaldi228.AT2", "landers_1992/RSN879_LANDERS_LCN345.AT2"}) {
    GroundMotion g;
    if (!testing::first_horizontal(file, g)) continue;
    Input in{file};
    in.dt = g.dt;
    in.ax = g.horizontal;
    out.push_back(in);
  }
  return out;
}

// The property test: 10,000 random bodies x 3 inputs (about 20 s in Release); under the
// sanitizers 2,000 of the same bodies.
constexpr int kPropertyBodies = testing::kUnderSanitizers ? 2000 : 10000;

TEST(BatchRocking, RandomBodiesTimesThreeInputsSameDecisions) {
  const std::vector<BodyParameters> bodies = random_bodies(kPropertyBodies, 2024);
  const double n = kPropertyBodies;
  for (const Input& in : property_inputs()) {
    // Looked at every 37th sample: lanes at rest stay deferred in between.
    const Compare c = run_compare(bodies, in, BatchTrig::Exact, {}, SolverSettings{}, 37);
    std::printf("[ batch  ] %s: %d bodies, exact trig: %ld lanes differ, %ld lane-samples not bitwise; "
                "per lane-sample rest_fast %.3f rocking_fast %.3f scalar %.3f (rocking fallback %.4f)\n",
                in.name.c_str(), kPropertyBodies, c.lanes_off, c.samples_not_bitwise,
                double(c.totals.rest_fast) / (n * (in.ax.size() - 1)),
                double(c.totals.rocking_fast) / (n * (in.ax.size() - 1)),
                double(c.totals.scalar) / (n * (in.ax.size() - 1)),
                double(c.totals.rocking_fallback) / (n * (in.ax.size() - 1)));
    expect_exact(c);
  }
}

TEST(BatchRocking, OtherSettingsAreSteppedByTheScalarModel) {
  // rk4, analytic and the linearized model have no vector path for rocking lanes; their rest lanes
  // still use the (model-specific) uplift test and deferral.
  const Input in = pulse_csv();
  SolverSettings lin;
  lin.model = ModelKind::Linearized;
  SolverSettings rk4;
  rk4.method = Method::Rk4;
  SolverSettings ana;
  ana.method = Method::Analytic;
  ana.model = ModelKind::Linearized;
  for (const SolverSettings& s : {lin, rk4, ana}) {
    SCOPED_TRACE(to_string(s.method) + std::string(" ") + to_string(s.model));
    const Compare c = run_compare(varied_bodies(23), in, BatchTrig::Exact, {}, s, 7);
    expect_exact(c);
    EXPECT_GT(c.totals.rest_fast, 0u);
    EXPECT_EQ(c.totals.rocking_fast, 0u);
  }
}

TEST(BatchRocking, TenThousandLanesOnTheBundledPulse) {
  const Compare c = run_compare(random_bodies(10000, 99), pulse_csv(), BatchTrig::Exact, {},
                                SolverSettings{}, 61);
  expect_exact(c);
  EXPECT_GT(c.totals.rocking_fast, 0u);
}

// Every SIMD target compiled in (AVX-512, AVX2, SSE4, ..., and the emulated 128-bit / scalar
// fallback) gives the scalar model's bits with exact trig: the portable path answers the same.
TEST(BatchRocking, EverySimdTargetGivesTheSameBits) {
  const std::vector<BodyParameters> bodies = random_bodies(300, 77);
  std::vector<Input> inputs = property_inputs();
  inputs.resize(std::min<std::size_t>(inputs.size(), 2));
  int targets = 0;
  for (const std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    hwy::SetSupportedTargetsForTest(target);
    std::printf("[ batch  ] SIMD target %s (batch reports %s)\n", hwy::TargetName(target),
                BatchRocking::simd_target());
    EXPECT_STREQ(BatchRocking::simd_target(), hwy::TargetName(target));
    for (const Input& in : inputs) {
      SCOPED_TRACE(std::string(hwy::TargetName(target)) + " " + in.name);
      expect_exact(run_compare(bodies, in, BatchTrig::Exact, {}, SolverSettings{}, 13));
    }
    ++targets;
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the machine's own
  EXPECT_GE(targets, 2);
}

// The accuracy policy's judgement of one body (docs/performance.md, rocking_accuracy policy): its
// decisions and event times from a run over the input.
struct Judged {
  bool beyond = false, committed = false, overturned = false;
  Mode mode = Mode::Rest;
  double uplift = NAN, beyond_t = NAN, committed_t = NAN, overturn_t = NAN;  // s
  bool operator==(const Judged& o) const {
    auto near = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= 1e-6; };
    return beyond == o.beyond && committed == o.committed && overturned == o.overturned && mode == o.mode &&
           near(uplift, o.uplift) && near(beyond_t, o.beyond_t) && near(committed_t, o.committed_t) &&
           near(overturn_t, o.overturn_t);
  }
};

Judged judge(const RockingModel& m) {
  const RockingOutcome& o = m.outcome();
  return {o.beyond_tipping, o.committed, o.overturned, m.mode(), o.uplift_time, o.beyond_tipping_time,
          o.committed_time, o.overturn_time};
}

// One body over the input made `fine` times finer (the same piecewise-linear signal).
Judged judge_run(const BodyParameters& body, const SolverSettings& s, const Input& in, int fine) {
  RockingModel m(body, s);
  m.reset(0.0, in.ax[0], in.ay_at(0));
  for (std::size_t i = 1; i < in.ax.size(); ++i)
    for (int j = 1; j <= fine; ++j) {
      const double f = static_cast<double>(j) / fine;
      m.step(in.ax[i - 1] + f * (in.ax[i] - in.ax[i - 1]), in.ay_at(i - 1) + f * (in.ay_at(i) - in.ay_at(i - 1)),
             in.dt / fine);
    }
  return judge(m);
}

// The fast trigonometry (Highway Sin/Cos, the batch's default) is not bit-identical. Under the
// accuracy policy a lane whose decisions or event times (1e-6 s) differ from the scalar tol-1e-8
// run's is judged against a converged reference (dopri5 1e-12 and rk4 x16, both on the input 8x
// finer, agreeing): it fails when the scalar run is right and the fast lane is not. Cases where
// the two references disagree are chaotic (counted, printed, not judged).
constexpr int kPolicyBodies = testing::kUnderSanitizers ? 400 : 2000;  // the first 400 of the same bodies

TEST(BatchRocking, FastTrigMeetsTheAccuracyPolicy) {
  const std::vector<BodyParameters> bodies = random_bodies(kPolicyBodies, 2024);
  SolverSettings ref, check;
  ref.tol = 1e-12;
  check.method = Method::Rk4;
  check.substeps = 16;
  long differing = 0, chaotic = 0, judged_right = 0;
  for (const Input& in : property_inputs()) {
    const Compare c = run_compare(bodies, in, BatchTrig::Fast);
    BatchRocking fast(bodies, SolverSettings{}, BatchTrig::Fast);
    fast.reset(0.0, in.ax[0], in.ay_at(0));
    for (std::size_t i = 1; i < in.ax.size(); ++i) fast.step_all(in.ax[i], in.ay_at(i), in.dt);
    for (std::size_t k : c.lanes_decision_off) {
      ++differing;
      const Judged r = judge_run(bodies[k], ref, in, 8);
      if (!(r == judge_run(bodies[k], check, in, 8))) {
        ++chaotic;
        continue;
      }
      const bool scalar_right = judge_run(bodies[k], SolverSettings{}, in, 1) == r;
      const bool fast_right = judge(fast.model(k)) == r;
      EXPECT_TRUE(fast_right || !scalar_right) << in.name << " lane " << k << ": the fast lane is wrong where the "
                                               << "scalar run is right";
      judged_right += fast_right;
    }
    std::printf("[ batch  ] %s: %d bodies, fast trig: %ld lanes differ in beyond_tipping / "
                "committed / overturned / final mode, %ld lanes in any outcome field (impacts, "
                "event times > 1e-9 s), %ld lane-samples with |theta diff| > 1e-9 or another "
                "mode, %ld step reports differ\n",
                in.name.c_str(), kPolicyBodies, c.lanes_flags_off, c.lanes_off, c.samples_theta_off, c.report_off);
    for (const std::string& n : c.notes) std::printf("[ batch  ]   %s\n", n.c_str());
    EXPECT_EQ(c.allocations, 0);
  }
  std::printf("[ batch  ] policy: %ld lanes decided differently from the scalar run: %ld chaotic, %ld with the fast "
              "lane right\n", differing, chaotic, judged_right);
}

}  // namespace
}  // namespace rocking_monitor::core
