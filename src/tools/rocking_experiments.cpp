// rocking_experiments: predicts the real shaking-table experiments of a data set (issue 20):
// every tests/TestNNN.csv(.gz) for every specimen of a catalogue (rocking_geometry's output),
// predicted overturn vs outcomes.csv; a CSV table and accuracy, precision, recall, F1. Items with
// distributions (a calibrated input_gain, issue 41) run as the node's ensemble; --margins writes each
// test's margin (the smallest scale of its table motion that overturns the model) instead.
// Thin command-line layer: all physics lives in the core (study/shaking_table_experiments).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_line.hpp"
#include "rocking_monitor/monitoring/catalogue_file.hpp"
#include "rocking_monitor/monitoring/uncertain_item.hpp"
#include "rocking_monitor/study/shaking_table_experiments.hpp"
#include "rocking_monitor/study/table_test_margin.hpp"

namespace rm = rocking_monitor::core;
namespace fs = std::filesystem;

namespace {

void print_scores(const std::string& name, const rm::Confusion& c) {
  std::printf("%-8s tests %4ld  TP %3ld FP %3ld TN %3ld FN %3ld  accuracy %.3f precision %.3f "
              "recall %.3f F1 %.3f\n", name.c_str(), c.total(), c.tp, c.fp, c.tn, c.fn,
              c.accuracy(), c.precision(), c.recall(), c.f1());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Predicts real shaking-table tests: each specimen of the catalogue through each "
               "tests/TestNNN.csv.gz of DIR, compared with DIR/outcomes.csv (docs/validation.md)"};
  std::string dir, catalogue, out;
  double restitution = std::nan("");
  double mu_s = std::nan("");
  int direction = 1, max_tests = 0;
  double tail_s = 5.0;
  app.add_option("dir", dir, "data set: tests/ and outcomes.csv")->required();
  app.add_option("--catalogue", catalogue, "specimens (YAML items: from rocking_geometry.py); "
                 "item ids are the outcome columns (SP1, SP2)")->required();
  app.add_option("--out", out, "write the per-test table here (CSV)");
  app.add_option("--restitution", restitution, "override eq. 34 (both pivots), in [0, 1]");
  app.add_option("--mu-s", mu_s, "static friction (default: the catalogue's; none = not checked)");
  app.add_option("--direction", direction, "+1: table acceleration as recorded; -1 reversed")
      ->check(CLI::IsMember({-1, 1}));
  app.add_option("--tail", tail_s, "s of table at rest after each record (default 5)");
  app.add_option("--max-tests", max_tests, "only the first N tests (0 = all)");
  std::string model_name = "auto";
  double restitution_factor = std::nan("");
  app.add_option("--model", model_name, "planar: each specimen's x-z plane (pivots on a line across "
                 "the shaking); 3d: the rigid body on its base polygon (needs the catalogue's 3-D keys: "
                 "base_polygon, centre_of_mass, central_inertia, mass); auto (default): 3d for a "
                 "catalogue whose items all have them, else planar")
      ->check(CLI::IsMember({"planar", "3d", "auto"}));
  double azimuth_deg = 0.0;
  app.add_option("--table-azimuth", azimuth_deg, "3d: the table's axis turned from the catalogue's x "
                 "towards y by this angle, deg (the specimen's placement on the table is uncertain)");
  app.add_option("--restitution-factor", restitution_factor, "3d: multiplies the angular velocity "
                 "after each impact of the 3-D law, in [0, 1] (default: the catalogue's, else 1)");
  std::string histories, history_tests = "misses";
  int history_every = 1;
  app.add_option("--histories", histories, "write rotation histories here: one CSV per chosen test "
                 "and specimen (TestNNN_SP1.csv; the first member's geometry)");
  app.add_option("--history-tests", history_tests, "which tests get a history: 'misses' (the wrong "
                 "predictions, default), 'all', or test numbers '12,40,41'");
  app.add_option("--history-every", history_every, "keep every Nth sample in a history (the last "
                 "one always; default 1)")->check(CLI::PositiveNumber);
  // An item with distributions (e.g. a calibrated lognormal input_gain, docs/validation.md section 0)
  // runs as the node runs it: the same Latin hypercube members for the same size and seed.
  int samples = 32;
  long seed = 1;
  app.add_option("--samples", samples, "members of an item with distributions when its catalogue gives no "
                 "ensemble_size (default 32: the node's ~ensemble_size)")->check(CLI::Range(1, 100000));
  app.add_option("--seed", seed, "global seed of those members (default 1: the node's ~ensemble_seed)");
  std::string margins;
  rm::MarginSearch search;
  app.add_option("--margins", margins, "instead of predicting: write each test's margin per specimen "
                 "member (CSV): the smallest scale of the table motion that overturns the model, searched on "
                 "--margin-grid scales from --margin-range LO HI, then bisected (issue 41); an item with distributions "
                 "at its nominal values (its input_gain's nominal included)");
  std::vector<double> margin_range{search.lo, search.hi};
  app.add_option("--margin-range", margin_range, "the scales searched, dimensionless (default 0.25 4)")->expected(2);
  app.add_option("--margin-grid", search.grid, "scales run on the grid, log-spaced (default 9: steps of sqrt 2)");
  app.add_option("--margin-bisections", search.bisections, "halvings of ln s inside the grid step where it "
                 "first overturns (default 5)");
  if (auto status = rocking_monitor::tools::parse_command_line(app, argc, argv, "rocking_experiments"))
    return *status;
  try {
    const auto outcomes = rm::read_outcomes((fs::path(dir) / "outcomes.csv").string());
    const auto items = rm::load_catalogue_items_file(catalogue);
    // Items "SP1#3" are members of SP1's ensemble (rocking_geometry.py --ensemble): P(overturn) is
    // the fraction of members that overturn, the prediction P >= 0.5.
    bool solid = model_name == "3d";
    if (model_name == "auto")
      solid = !items.empty() && std::all_of(items.begin(), items.end(), [](const auto& i) { return i.spec.solid.has_value(); });
    // A member's table azimuth (rad): --table-azimuth minus the item's own yaw on the table (its
    // catalogue pose), the same rotation the node applies to a sensor's input through tf.
    search.lo = margin_range[0];
    search.hi = margin_range[1];
    if (!margins.empty()) rm::validate(search);
    struct Member { rm::BodyParameters planar; rm::BaseBodyParameters solid; double azimuth; double gain; };
    struct Specimen { std::string id; std::vector<Member> members; int column; };
    std::vector<Specimen> specimens;
    for (const auto& item : items) {
      const std::string name = item.spec.id.substr(0, item.spec.id.find('#'));
      const auto it = std::find(outcomes.specimens.begin(), outcomes.specimens.end(), name);
      if (it == outcomes.specimens.end())
        throw std::runtime_error(catalogue + ": item '" + item.spec.id + "': no column " + name +
                                 "_overturned in outcomes.csv");
      // The item's members as the node draws them (ItemEnsemble: each member's input_gain scales its
      // input); a deterministic item is its one member. For --margins the nominal item alone: the
      // margin is the geometry's, the fragility's spread is what the script fits.
      std::vector<rm::ItemSpec> specs{item.spec};
      if (item.uncertain.uncertain() && margins.empty())
        specs = rm::draw_members(item.uncertain, item.ensemble_size > 0 ? item.ensemble_size : samples,
                                 static_cast<std::uint64_t>(seed));
      for (const rm::ItemSpec& spec : specs) {
      rm::BodyParameters b = spec.body;
      if (!std::isnan(restitution)) b.restitution = restitution;
      if (!std::isnan(mu_s)) b.mu_s = mu_s;
      const std::string problem = rm::validate(b);
      if (!problem.empty()) throw std::runtime_error("item '" + item.spec.id + "': " + problem);
      Member member{b, {}, azimuth_deg * M_PI / 180.0, spec.input_gain};
      if (item.pose.given) {
        if (item.pose.roll != 0.0 || item.pose.pitch != 0.0)
          throw std::runtime_error(catalogue + ": item '" + item.spec.id + "': pose: a specimen stands on the "
                                   "table: only its yaw is used, roll and pitch must be 0");
        if (item.pose.yaw != 0.0 && !solid)
          throw std::runtime_error(catalogue + ": item '" + item.spec.id + "': pose.yaw needs the 3-D model "
                                   "(--model 3d): a planar plane has one axis");
        member.azimuth -= item.pose.yaw;
      }
      if (solid) {
        if (!spec.solid)
          throw std::runtime_error(catalogue + ": item '" + item.spec.id + "': --model 3d needs its 3-D "
                                   "description (base_polygon, centre_of_mass, central_inertia, mass: "
                                   "scripts/rocking_geometry.py writes them)");
        member.solid = *spec.solid;
        if (!std::isnan(restitution_factor)) member.solid.restitution_factor = restitution_factor;
        if (!std::isnan(mu_s)) member.solid.mu_s = mu_s;
        const std::string p3 = rm::validate(member.solid);
        if (!p3.empty()) throw std::runtime_error("item '" + item.spec.id + "': " + p3);
      }
      auto group = std::find_if(specimens.begin(), specimens.end(),
                                [&](const Specimen& sp) { return sp.id == name; });
      if (group != specimens.end()) {
        group->members.push_back(member);
        continue;
      }
      if (item.uncertain.uncertain() && margins.empty())
        std::printf("%s: %zu members (seed %ld; input_gain %.4f..%.4f)\n", item.spec.id.c_str(), specs.size(), seed,
                    std::min_element(specs.begin(), specs.end(), [](const auto& x, const auto& y) { return x.input_gain < y.input_gain; })->input_gain,
                    std::max_element(specs.begin(), specs.end(), [](const auto& x, const auto& y) { return x.input_gain < y.input_gain; })->input_gain);
      specimens.push_back({name, {member}, static_cast<int>(it - outcomes.specimens.begin())});
      const rm::Body body(b);
      for (int side : {1, -1}) {
        const auto& p = body.pivot(side);
        std::printf("%s pivot %d: alpha %.3f deg, R %.4f m, p %.3f rad/s, uplift at %.3f g, "
                    "restitution %.4f\n", item.spec.id.c_str(), side > 0 ? 1 : 2,
                    p.alpha * 180.0 / M_PI, p.radius, p.p, p.tan_alpha, p.restitution);
      }
      if (solid) {
        const rm::BaseBody body3(member.solid);
        for (int k = 0; k < body3.vertex_count(); ++k) {
          const auto& e = body3.edge(k);
          // only the edges the table (along x) can tip it over
          if (std::abs(e.normal.x()) < 0.2) continue;
          std::printf("%s edge %d (normal %+.2f, %+.2f): alpha %.3f deg, R %.4f m, uplift at %.3f g "
                      "along the normal\n", item.spec.id.c_str(), k + 1, e.normal.x(), e.normal.y(),
                      e.pivot.alpha * 180.0 / M_PI, e.pivot.radius, e.pivot.tan_alpha);
        }
      }
      }
    }
    std::vector<std::string> files;
    for (const auto& e : fs::directory_iterator(fs::path(dir) / "tests")) {
      const std::string name = e.path().filename().string();
      if (name.rfind("Test", 0) == 0 && (name.size() > 4 && (name.find(".csv") != std::string::npos)))
        files.push_back(e.path().string());
    }
    std::sort(files.begin(), files.end());
    if (max_tests > 0 && static_cast<int>(files.size()) > max_tests) files.resize(max_tests);
    if (files.empty()) throw std::runtime_error(dir + "/tests: no TestNNN.csv(.gz) files");

    // Tests named for a history: each must be among the tests run (checked after the run).
    std::set<int> history_numbers;
    const bool history_misses = history_tests == "misses", history_all = history_tests == "all";
    if (!histories.empty()) {
      if (!history_misses && !history_all) {
        std::stringstream list(history_tests);
        std::string cell;
        while (std::getline(list, cell, ',')) {
          char* end = nullptr;
          const long n = std::strtol(cell.c_str(), &end, 10);
          if (cell.empty() || *end != '\0' || n <= 0)
            throw std::runtime_error("--history-tests: '" + cell + "' is not a test number (or use misses, all)");
          history_numbers.insert(static_cast<int>(n));
        }
      }
      fs::create_directories(histories);
    }
    std::set<int> history_done;
    long histories_written = 0;
    std::vector<rm::TableHistorySample> history;
    rm::ExperimentSettings settings;
    settings.direction = direction;
    settings.tail_s = tail_s;
    if (!solid && azimuth_deg != 0.0)
      throw std::runtime_error("--table-azimuth needs the 3-D model (--model 3d): a planar plane has one axis");
    auto predict = [&](const Member& m, const std::string& id, const rm::TableTest& test,
                       std::vector<rm::TableHistorySample>* h) {
      rm::ExperimentSettings member_settings = settings;
      member_settings.table_azimuth = m.azimuth;
      member_settings.input_gain = m.gain;
      return solid ? rm::predict_table_test_3d(m.solid, id, test, member_settings, h)
                   : rm::predict_table_test(m.planar, id, test, settings, h);
    };
    if (!margins.empty()) {
      // Each test's margin per specimen member (issue 41): the table motion scaled until the model
      // overturns. A run that overturns stops there, so most of the cost is in the scales that stand.
      std::ofstream mf(margins);
      if (!mf) throw std::runtime_error(margins + ": cannot open for writing");
      mf << "test,specimen,member,measured_overturned,peak_table_accel_mps2,margin_scale,censored,chaotic,"
            "grid_outcomes,bracket_lo,bracket_hi,runs\n";
      long chaotic = 0, below = 0, above = 0, count = 0;
      for (const auto& file : files) {
        const auto test = rm::read_table_test(file);
        const auto row = outcomes.by_test.find(test.number);
        for (const auto& sp : specimens) {
          const int measured = row == outcomes.by_test.end() ? -1 : row->second[sp.column];
          for (std::size_t k = 0; k < sp.members.size(); ++k) {
            Member m = sp.members[k];
            const double gain = m.gain;
            const auto margin = rm::table_test_margin([&](double scale) {
              m.gain = gain * scale;
              return predict(m, sp.id, test, nullptr).predicted;
            }, search);
            chaotic += margin.chaotic;
            below += margin.censored < 0;
            above += margin.censored > 0;
            ++count;
            char line[512];
            std::snprintf(line, sizeof line, "%d,%s,%zu,%s,%.6g,%.6g,%d,%d,%s,%.6g,%.6g,%d\n", test.number,
                          sp.id.c_str(), k, measured < 0 ? "" : std::to_string(measured).c_str(), test.peak_mps2,
                          margin.scale, margin.censored, margin.chaotic, margin.pattern.c_str(), margin.bracket_lo,
                          margin.bracket_hi, margin.runs);
            mf << line;
          }
        }
      }
      if (!mf.flush()) throw std::runtime_error(margins + ": write failed");
      std::printf("rocking_experiments: %ld margins (%zu tests) written to %s: %ld chaotic (not monotone on the "
                  "grid), %ld overturn at %g already, %ld stand at %g\n", count, files.size(), margins.c_str(),
                  chaotic, below, search.lo, above, search.hi);
      return 0;
    }
    std::ofstream table;
    if (!out.empty()) {
      table.open(out);
      if (!table) throw std::runtime_error(out + ": cannot open for writing");
      table << "test,specimen,peak_table_accel_mps2,offset_mps2,exceeds_static_uplift,uplift,"
               "max_rotation_ratio,impacts,overturn_time_s,predicted_overturned,measured_overturned,"
               "members,p_overturn,final_face,rests_off_base\n";
    }
    std::map<std::string, rm::Confusion> per;
    rm::Confusion all;
    long without_outcome = 0;
    // Brier score and a 5-bin reliability diagram of P(overturn), per specimen and overall.
    struct Reliability { double brier = 0.0; long n = 0; long bin_n[5] = {}; double bin_p[5] = {};
                         long bin_y[5] = {}; };
    std::map<std::string, Reliability> rel;
    auto add_rel = [](Reliability& r, double p, int y) {
      r.brier += (p - y) * (p - y);
      ++r.n;
      const int b = std::min(4, static_cast<int>(p * 5.0));
      ++r.bin_n[b];
      r.bin_p[b] += p;
      r.bin_y[b] += y;
    };
    for (const auto& file : files) {
      const auto test = rm::read_table_test(file);
      const auto row = outcomes.by_test.find(test.number);
      for (const auto& s : specimens) {
        // the first member (the nominal geometry) gives the row's details, the members P(overturn)
        auto p = predict(s.members.front(), s.id, test, nullptr);
        long over = p.predicted;
        for (std::size_t k = 1; k < s.members.size(); ++k)
          over += predict(s.members[k], s.id, test, nullptr).predicted;
        const double prob = static_cast<double>(over) / static_cast<double>(s.members.size());
        const bool predicted = prob >= 0.5;
        if (row != outcomes.by_test.end()) p.measured = row->second[s.column];
        if (p.measured < 0) ++without_outcome;
        else {
          per[s.id].add(predicted, p.measured == 1);
          all.add(predicted, p.measured == 1);
          add_rel(rel[s.id], prob, p.measured);
          add_rel(rel["all"], prob, p.measured);
        }
        const bool wrong = p.measured >= 0 && predicted != (p.measured == 1);
        if (!histories.empty() && (history_all || (history_misses && wrong) ||
                                   history_numbers.count(test.number))) {
          predict(s.members.front(), s.id, test, &history);
          char name[64];
          std::snprintf(name, sizeof name, "Test%03d_%s.csv", test.number, s.id.c_str());
          const std::string path = (fs::path(histories) / name).string();
          std::ofstream h(path);
          if (!h) throw std::runtime_error(path + ": cannot open for writing");
          h << "t_s,table_accel_mps2,theta_rad,omega_radps,rotation_ratio,max_rotation_ratio,mode\n";
          char line[256];
          for (std::size_t k = 0; k < history.size(); ++k) {
            if (k % static_cast<std::size_t>(history_every) != 0 && k + 1 != history.size()) continue;
            const auto& r = history[k];
            std::snprintf(line, sizeof line, "%.6f,%.6g,%.8g,%.8g,%.8g,%.8g,%s\n", r.t,
                          r.table_accel_mps2, r.theta, r.omega, r.rotation_ratio,
                          r.max_rotation_ratio, r.mode);
            h << line;
          }
          if (!h.flush()) throw std::runtime_error(path + ": write failed");
          ++histories_written;
          history_done.insert(test.number);
        }
        if (table) {
          char line[512];
          std::snprintf(line, sizeof line, "%d,%s,%.6g,%.6g,%d,%d,%.6g,%ld,%.4f,%d,%s,%zu,%.4f,%d,%ld\n",
                        p.test, s.id.c_str(), test.peak_mps2, test.offset_mps2,
                        p.exceeds_static_uplift, p.uplift, p.max_rotation_ratio, p.impacts,
                        p.overturn_time, predicted,
                        p.measured < 0 ? "" : std::to_string(p.measured).c_str(),
                        s.members.size(), prob, p.final_face, p.rests_off_base);
          table << line;
        }
      }
    }
    std::printf("rocking_experiments: %zu tests x %zu specimens, direction %+d, model %s, restitution %s\n",
                files.size(), specimens.size(), direction, solid ? "3d" : "planar",
                solid ? (std::isnan(restitution_factor) ? "3-D law x the catalogue's factor"
                                                        : ("3-D law x " + std::to_string(restitution_factor)).c_str())
                      : (std::isnan(restitution) ? "eq. 34" : std::to_string(restitution).c_str()));
    for (const auto& [id, c] : per) print_scores(id, c);
    print_scores("all", all);
    if (std::any_of(specimens.begin(), specimens.end(), [](const Specimen& sp) { return sp.members.size() > 1; })) {
      for (const auto& [id, r] : rel) {
        std::printf("%-8s Brier %.4f  reliability (P bin: n, mean P, observed):", id.c_str(),
                    r.n ? r.brier / static_cast<double>(r.n) : std::nan(""));
        for (int b = 0; b < 5; ++b)
          if (r.bin_n[b])
            std::printf("  [%.1f,%.1f%c: %ld, %.2f, %.2f", b * 0.2, (b + 1) * 0.2, b == 4 ? ']' : ')',
                        r.bin_n[b], r.bin_p[b] / static_cast<double>(r.bin_n[b]),
                        static_cast<double>(r.bin_y[b]) / static_cast<double>(r.bin_n[b]));
        std::printf("\n");
      }
    }
    for (int n : history_numbers)
      if (!history_done.count(n))
        throw std::runtime_error("--history-tests: test " + std::to_string(n) + " is not among the tests run");
    if (!histories.empty())
      std::printf("rocking_experiments: %ld histories written to %s (%s)\n", histories_written,
                  histories.c_str(), history_tests.c_str());
    if (without_outcome)
      std::printf("rocking_experiments: %ld predictions without a measured outcome (not scored)\n",
                  without_outcome);
    if (table && !table.flush()) throw std::runtime_error(out + ": write failed");
  } catch (const std::exception& e) {
    std::cerr << "rocking_experiments: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
