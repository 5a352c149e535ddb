// rocking_accuracy policy: the accuracy policy of fast paths (issue 28).

#include "accuracy_common.hpp"
#include "accuracy_parts.hpp"

namespace rocking_monitor::bench::accuracy {

namespace rb = rocking_monitor::bench;
using namespace rocking_monitor::core;  // NOLINT(google-build-using-namespace): as in every bench file

namespace {

// ------------------------------------------------------------------ accuracy policy (issue 28)
// What a fast path (here: the batch engine with vector sin/cos, BatchTrig::Fast) must get right:
// the decisions (uplift, beyond tipping, committed, overturned, final mode) and their event times
// (within kPolicyTimeTol), against a converged reference, wherever today's scalar run (dopri5,
// tol 1e-8, the monitor's default) gets them right. Bit-for-bit equality is kept for the exact
// path only (work-precision; test_batch_rocking).
//
// Converged reference per case: two tight, different integrations of the same piecewise-linear
// input, both on the input re-sampled kRefUpsample x finer: dopri5 at tol 1e-12 (the accuracy
// tables' reference) and RK4 with 16 fixed sub-steps per fine sample (another method, fixed steps,
// its own event location). A case where these two disagree on any decision or time is chaotic:
// no integrator can be judged on it; it is listed, and not counted.

constexpr double kPolicyTimeTol = 1e-6;  // s
constexpr int kPolicyRk4Substeps = 16;

struct Decisions {
  bool uplift = false, beyond = false, committed = false, overturned = false;
  Mode final_mode = Mode::Rest;
  double uplift_time = kNaN, beyond_time = kNaN, committed_time = kNaN, overturn_time = kNaN;  // s
};

Decisions decisions(const RockingOutcome& o, Mode final_mode) {
  Decisions d;
  d.uplift = !std::isnan(o.uplift_time);
  d.beyond = o.beyond_tipping;
  d.committed = o.committed;
  d.overturned = o.overturned;
  d.final_mode = final_mode;
  d.uplift_time = o.uplift_time;
  d.beyond_time = o.beyond_tipping_time;
  d.committed_time = o.committed_time;
  d.overturn_time = o.overturn_time;
  return d;
}

constexpr int kPolicyItems = 9;
constexpr const char* kPolicyItemNames[kPolicyItems] = {
    "uplift", "beyond tipping", "committed", "overturned", "final mode",
    "uplift time", "beyond-tipping time", "committed time", "overturn time"};

bool same_time(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  return std::abs(a - b) <= kPolicyTimeTol;
}

/// Whether item i (kPolicyItemNames) of a agrees with b.
bool agrees(const Decisions& a, const Decisions& b, int i) {
  switch (i) {
    case 0: return a.uplift == b.uplift;
    case 1: return a.beyond == b.beyond;
    case 2: return a.committed == b.committed;
    case 3: return a.overturned == b.overturned;
    case 4: return a.final_mode == b.final_mode;
    case 5: return same_time(a.uplift_time, b.uplift_time);
    case 6: return same_time(a.beyond_time, b.beyond_time);
    case 7: return same_time(a.committed_time, b.committed_time);
    default: return same_time(a.overturn_time, b.overturn_time);
  }
}

/// One body over the whole input (no stop at an overturn: the final mode is a decision too).
Decisions run_decisions(const BodyParameters& body, const SolverSettings& s, const GroundMotion& g) {
  RockingModel m(body, s);
  m.reset(g.t0, g.horizontal[0], g.ay(0));
  for (std::size_t i = 1; i < g.size(); ++i) m.step(g.horizontal[i], g.ay(i), g.dt);
  return decisions(m.outcome(), m.mode());
}

struct PolicyCase {
  std::string name;  // input and body
  Decisions ref, ref_check, scalar, fast, exact;
};

struct PolicyCounts {
  long scalar_ok[kPolicyItems] = {}, fast_ok[kPolicyItems] = {}, exact_ok[kPolicyItems] = {};
  long fast_fail[kPolicyItems] = {}, exact_fail[kPolicyItems] = {};  // wrong where the scalar run is right
};

/// Every body of `bodies` on input g: the two references and the scalar run per body, and the batch
/// engine (all bodies as its lanes, one batch per input as in a catalogue), fast and exact trig.
std::vector<PolicyCase> policy_cases(const std::string& input, const GroundMotion& g,
                                     const std::vector<BodyParameters>& bodies, const std::vector<std::string>& names) {
  std::vector<PolicyCase> out(bodies.size());
  const GroundMotion fine = upsample(g, kRefUpsample);
  SolverSettings ref, check, scalar;
  ref.tol = kRefTol;
  check.method = Method::Rk4;
  check.substeps = kPolicyRk4Substeps;
  scalar.tol = 1e-8;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    out[b].name = input + " " + names[b];
    out[b].ref = run_decisions(bodies[b], ref, fine);
    out[b].ref_check = run_decisions(bodies[b], check, fine);
    out[b].scalar = run_decisions(bodies[b], scalar, g);
  }
  for (BatchTrig trig : {BatchTrig::Fast, BatchTrig::Exact}) {
    BatchRocking batch(bodies, scalar, trig);
    batch.reset(g.t0, g.horizontal[0], g.ay(0));
    for (std::size_t i = 1; i < g.size(); ++i) batch.step_all(g.horizontal[i], g.ay(i), g.dt);
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const RockingModel& m = std::as_const(batch).model(b);
      (trig == BatchTrig::Fast ? out[b].fast : out[b].exact) = decisions(m.outcome(), m.mode());
    }
  }
  return out;
}

}  // namespace

/// Prints the policy table; returns 1 when a fast path decides a converged case wrongly where the
/// scalar tol-1e-8 run decides it right (or the exact batch differs from the scalar run at all).
int accuracy_policy(const std::string& out_dir, const std::string& records, int jobs, bool quick, bool quiet) {
  struct Job {
    std::string file;
    double scale;
    bool random_bodies;
  };
  std::vector<Job> jobs_list;
  std::vector<std::string> files = rb::at2_files(records);
  if (files.empty()) {
    std::fprintf(stderr, "rocking_accuracy: no .AT2 records under %s: policy not checked\n", records.c_str());
    return 1;
  }
  if (quick && files.size() > 30) files.resize(30);
  // The accuracy suite's records (1x and 2x, the study's four bodies) ...
  for (const std::string& f : files)
    for (double s : {1.0, 2.0}) jobs_list.push_back({f, s, false});
  // ... and 150 random catalogue bodies on both Lucerne (Landers 1992) components at 1x and 2x.
  for (const std::string& f : files)
    if (f.find("LANDERS_LCN") != std::string::npos)
      for (double s : {1.0, 2.0}) jobs_list.push_back({f, s, true});
  const std::vector<NamedBody> study = study_bodies();
  const std::vector<BodyParameters> random = rb::catalogue(quick ? 40 : 150, 28);
  std::vector<std::vector<PolicyCase>> results(jobs_list.size());
  rocking_monitor::tools::ProgressMeter progress("inputs", quiet);
  parallel_for(jobs_list.size(), jobs, [&](std::size_t i) {
    const Job& j = jobs_list[i];
    try {
      const GroundMotion g = rb::load_record(j.file, j.scale);
      std::vector<BodyParameters> bodies;
      std::vector<std::string> names;
      if (j.random_bodies) {
        bodies = random;
        for (std::size_t b = 0; b < random.size(); ++b) names.push_back("random#" + std::to_string(b));
      } else {
        for (const NamedBody& nb : study) {
          bodies.push_back(nb.body);
          names.push_back(nb.name);
        }
      }
      char scale[32];
      std::snprintf(scale, sizeof scale, " x%g", j.scale);
      results[i] = policy_cases(std::filesystem::relative(j.file, records).string() + scale, g, bodies, names);
    } catch (const std::exception& e) {
      if (std::string(e.what()).find("no horizontal component") == std::string::npos)
        std::fprintf(stderr, "rocking_accuracy: skipping %s: %s\n", j.file.c_str(), e.what());
    }
  }, &progress);
  PolicyCounts c;
  long cases = 0, converged = 0;
  std::vector<std::string> chaotic, failures;
  std::ofstream csv(out_dir + "/accuracy_policy.csv");
  csv << "case,converged,scalar_agrees,fast_agrees,exact_agrees\n";  // bitmasks over kPolicyItemNames
  for (const std::vector<PolicyCase>& rs : results) {
    for (const PolicyCase& r : rs) {
      ++cases;
      bool conv = true;
      for (int i = 0; i < kPolicyItems; ++i) conv = conv && agrees(r.ref, r.ref_check, i);
      int ms = 0, mf = 0, me = 0;
      for (int i = 0; i < kPolicyItems; ++i) {
        ms |= agrees(r.scalar, r.ref, i) << i;
        mf |= agrees(r.fast, r.ref, i) << i;
        me |= agrees(r.exact, r.scalar, i) << i;  // the exact path: the scalar run's decisions
      }
      csv << '"' << r.name << "\"," << conv << ',' << ms << ',' << mf << ',' << me << '\n';
      if (!conv) {
        std::string what;
        for (int i = 0; i < kPolicyItems; ++i)
          if (!agrees(r.ref, r.ref_check, i)) what += std::string(what.empty() ? "" : ", ") + kPolicyItemNames[i];
        chaotic.push_back(r.name + " (references differ in: " + what + ")");
        continue;
      }
      ++converged;
      for (int i = 0; i < kPolicyItems; ++i) {
        const bool s = ms >> i & 1, f = mf >> i & 1, e = me >> i & 1;
        c.scalar_ok[i] += s;
        c.fast_ok[i] += f;
        c.exact_ok[i] += e;
        c.exact_fail[i] += !e;
        if (s && !f) {
          ++c.fast_fail[i];
          failures.push_back(r.name + ": " + kPolicyItemNames[i]);
        }
      }
    }
  }
  std::printf("Accuracy policy (issue 28): %ld cases, %ld converged (dopri5 1e-12 and rk4 x%d on the input x%d finer "
              "agree), %zu chaotic\n",
              cases, converged, kPolicyRk4Substeps, kRefUpsample, chaotic.size());
  std::printf("%-22s %14s %16s %14s %16s\n", "decision / time", "scalar 1e-8 ok", "batch fast-trig ok",
              "fast wrong*", "exact == scalar");
  for (int i = 0; i < kPolicyItems; ++i)
    std::printf("%-22s %14ld %16ld %14ld %16ld\n", kPolicyItemNames[i], c.scalar_ok[i], c.fast_ok[i], c.fast_fail[i],
                c.exact_ok[i]);
  std::printf("* wrong against the reference where the scalar tol-1e-8 run is right (the policy: must be 0); "
              "times within %g s\n", kPolicyTimeTol);
  for (const std::string& s : chaotic) std::printf("chaotic: %s\n", s.c_str());
  for (const std::string& s : failures) std::printf("FAIL: %s\n", s.c_str());
  long exact_fail = 0;
  for (int i = 0; i < kPolicyItems; ++i) exact_fail += c.exact_fail[i];
  if (exact_fail > 0) std::printf("FAIL: the exact-trig batch differs from the scalar run in %ld decisions\n", exact_fail);
  return failures.empty() && exact_fail == 0 && converged > 0 ? 0 : 1;
}

}  // namespace rocking_monitor::bench::accuracy
