// Convergence of the live ensemble's probabilities (issue 13): P(level) from N = 32, 128 and 512
// Latin-hypercube members against a 2,500-member reference on 20 real record / body cases (issue 42:
// 10,000 took 100 s of CPU, the longest test in CI; ROCKING_ENSEMBLE_REFERENCE=10000 runs that one). The
// reference is drawn with another seed (so it shares no member with the small ensembles); a small
// ensemble "covers" when the reference lies inside its 95 % Wilson interval.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "rocking_monitor/monitoring/item_ensemble.hpp"
#include "rocking_monitor/monitoring/uncertain_item.hpp"
#include "rocking_monitor/motion/record_reader.hpp"
#include "test_helpers.hpp"

namespace rocking_monitor::core {
namespace {

struct Case {
  std::string record;
  UncertainItemSpec item;
};

UncertainItemSpec body(const std::string& id, double width, double cg_height) {
  UncertainItemSpec u;
  u.nominal.id = id;
  u.nominal.sensor = "floor";
  u.nominal.frame = id;
  u.nominal.body.width = width;
  u.nominal.body.cg_height = cg_height;
  u.nominal.body.nu1 = 0.425;
  // Catalogue-like uncertainty: base +-25 %, height 5 %, the centre of mass somewhere off the middle.
  u.law(UncertainField::Width) = Distribution::uniform(0.75 * width, 1.25 * width, valid_range(UncertainField::Width));
  u.law(UncertainField::CgHeight) =
      Distribution::normal(cg_height, 0.05 * cg_height, valid_range(UncertainField::CgHeight));
  u.law(UncertainField::Eccentricity) = Distribution::uniform(0.35, 0.5, valid_range(UncertainField::Eccentricity));
  return u;
}

// P(level) of n members through the record (pure rocking: the paper's model, the cheapest).
std::array<long, kLevelCount> reached(const UncertainItemSpec& spec, int n, std::uint64_t seed, const Component& c) {
  ItemMonitor::Options o;
  o.fidelity = Fidelity::Rocking;
  ItemEnsemble e(draw_members(spec, n, seed), o);
  e.start(0.0, c.accel[0], 0.0, 0.0, c.dt);
  for (std::size_t i = 1; i < c.accel.size(); ++i) e.step(c.accel[i], 0.0, 0.0, c.dt);
  std::array<long, kLevelCount> k{};
  for (int l = 0; l < kLevelCount; ++l) k[static_cast<std::size_t>(l)] = e.reached(static_cast<Level>(l));
  return k;
}

TEST(EnsembleConvergence, SmallEnsemblesCoverALargeReference) {
  const std::string dir = ROCKING_RECORDS_DIR;
  const std::vector<std::string> records{"kobe_1995/RSN1120_KOBE_TAK090.AT2", "kobe_1995/NIS090.AT2",
                                         "northridge_1994/RSN1044_NORTHR_NWH360.AT2",
                                         "northridge_1994/RSN960_NORTHR_LOS270.AT2",
                                         "northridge_1994/RSN1045_NORTHR_WPI046.AT2"};
  const std::vector<UncertainItemSpec> bodies{body("vase", 0.15, 0.35), body("cabinet", 0.30, 0.80),
                                              body("shelf", 0.35, 1.00), body("rack", 0.60, 1.00)};
  std::vector<Component> motions;
  for (const std::string& r : records) motions.push_back(read_record(dir + "/" + r).front());
  constexpr std::array<int, 3> kSizes{32, 128, 512};
  // A 2,500-member reference: its own sampling error, <= 0.01, stays well inside the 512-member
  // interval (+-0.043 at P = 0.5). ROCKING_ENSEMBLE_REFERENCE sets another size (docs/monitor.md: 10,000).
  const char* env = std::getenv("ROCKING_ENSEMBLE_REFERENCE");
  const int kReference = env ? std::atoi(env) : 2500;
  ASSERT_GE(kReference, 2500) << "ROCKING_ENSEMBLE_REFERENCE: a smaller reference proves little";
  const std::size_t cases = records.size() * bodies.size();
  ASSERT_EQ(cases, 20u);
  // Per case: the reference counts and each small ensemble's counts.
  std::vector<std::array<long, kLevelCount>> ref(cases);
  std::vector<std::array<std::array<long, kLevelCount>, kSizes.size()>> small(cases);
  std::atomic<std::size_t> next{0};
  std::array<std::string, 2> errors;
  auto worker = [&](std::string& error) {
    try {
      for (std::size_t k; (k = next++) < cases;) {
        const Component& c = motions[k / bodies.size()];
        const UncertainItemSpec& b = bodies[k % bodies.size()];
        ref[k] = reached(b, kReference, 987654321, c);
        for (std::size_t s = 0; s < kSizes.size(); ++s) small[k][s] = reached(b, kSizes[s], 1, c);
      }
    } catch (const std::exception& e) {
      error = e.what();
      next = cases;
    }
  };
  std::thread helper(worker, std::ref(errors[1]));
  worker(errors[0]);
  helper.join();
  for (const std::string& e : errors) ASSERT_EQ(e, "");

  int intermediate = 0;  // cases with 0 < P_ref(overturned) < 1: where a probability says more than a verdict
  for (std::size_t k = 0; k < cases; ++k) {
    const double p = static_cast<double>(ref[k][static_cast<int>(Level::Overturned)]) / kReference;
    intermediate += p > 0.0 && p < 1.0;
  }
  EXPECT_GE(intermediate, 5) << "the cases must include uncertain outcomes, or coverage proves little";
  for (std::size_t s = 0; s < kSizes.size(); ++s) {
    int covered = 0, total = 0;
    double abs_error = 0.0;
    for (std::size_t k = 0; k < cases; ++k) {
      for (int l = 0; l < kLevelCount; ++l) {
        const double p_ref = static_cast<double>(ref[k][static_cast<std::size_t>(l)]) / kReference;
        const long hits = small[k][s][static_cast<std::size_t>(l)];
        const WilsonInterval w = wilson_interval(hits, kSizes[s]);
        covered += p_ref >= w.lower && p_ref <= w.upper;
        ++total;
        abs_error += std::abs(static_cast<double>(hits) / kSizes[s] - p_ref);
      }
    }
    const double coverage = static_cast<double>(covered) / total;
    std::printf("[ measured ] N = %3d: the %d-member P inside the 95 %% Wilson interval in %d of %d "
                "(case, level) pairs (%.1f %%); mean |P_N - P_ref| = %.4f; %d of 20 cases with 0 < P_ref < 1\n",
                kSizes[s], kReference, covered, total, 100.0 * coverage, abs_error / total, intermediate);
    // Latin hypercube: at least as tight as independent draws, so the binomial interval should cover
    // about 95 % or more; 90 % leaves room for 60 pairs of chance.
    EXPECT_GE(coverage, 0.90) << "N = " << kSizes[s];
    if (s + 1 == kSizes.size()) EXPECT_LT(abs_error / total, 0.03) << "512 members must be within a few per cent";
  }
}

}  // namespace
}  // namespace rocking_monitor::core
