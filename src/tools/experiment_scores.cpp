// rocking_experiments' scores: adding a prediction and printing the tables.
#include "experiment_scores.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rocking_monitor::tools::experiments {

namespace {

void print_confusion(const std::string& name, const core::Confusion& c) {
  std::printf("%-8s tests %4ld  TP %3ld FP %3ld TN %3ld FN %3ld  accuracy %.3f precision %.3f "
              "recall %.3f F1 %.3f\n", name.c_str(), c.total(), c.tp, c.fp, c.tn, c.fn,
              c.accuracy(), c.precision(), c.recall(), c.f1());
}

void print_reliability(const std::string& id, const Reliability& r) {
  std::printf("%-8s Brier %.4f  reliability (P bin: n, mean P, observed):", id.c_str(),
              r.n ? r.brier / static_cast<double>(r.n) : std::nan(""));
  for (int b = 0; b < 5; ++b)
    if (r.bin_n[b])
      std::printf("  [%.1f,%.1f%c: %ld, %.2f, %.2f", b * 0.2, (b + 1) * 0.2, b == 4 ? ']' : ')', r.bin_n[b],
                  r.bin_p[b] / static_cast<double>(r.bin_n[b]),
                  static_cast<double>(r.bin_y[b]) / static_cast<double>(r.bin_n[b]));
  std::printf("\n");
}

}  // namespace

void Reliability::add(double p, int y) {
  brier += (p - y) * (p - y);
  ++n;
  const int b = std::min(4, static_cast<int>(p * 5.0));
  ++bin_n[b];
  bin_p[b] += p;
  bin_y[b] += y;
}

void Scores::add(const std::string& specimen, double probability, bool predicted, int measured) {
  if (measured < 0) {
    ++without_outcome;
    return;
  }
  per[specimen].add(predicted, measured == 1);
  all.add(predicted, measured == 1);
  reliability[specimen].add(probability, measured);
  reliability["all"].add(probability, measured);
}

void print_scores(const Scores& scores, bool reliability) {
  for (const auto& [id, c] : scores.per) print_confusion(id, c);
  print_confusion("all", scores.all);
  if (!reliability) return;
  for (const auto& [id, r] : scores.reliability) print_reliability(id, r);
}

}  // namespace rocking_monitor::tools::experiments
