#include "rocking_monitor/study/shaking_table_experiments.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include "rocking_monitor/constants.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/criteria.hpp"

namespace rocking_monitor::core {
namespace {

// Lines of a text file, gzipped or not (gzopen reads plain files transparently).
std::vector<std::string> read_lines(const std::string& path) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error(path + ": cannot open");
  std::vector<std::string> lines;
  std::string line;
  char buf[4096];
  while (gzgets(f, buf, sizeof buf)) {
    line += buf;
    if (!line.empty() && line.back() == '\n') {
      while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
      lines.push_back(line);
      line.clear();
    }
  }
  int err = 0;
  const char* msg = gzerror(f, &err);
  const bool failed = err != Z_OK && err != Z_STREAM_END;
  const std::string what = failed ? msg : "";
  gzclose(f);
  if (failed) throw std::runtime_error(path + ": read failed (" + what + ")");
  if (!line.empty()) lines.push_back(line);
  return lines;
}

double parse_number(const std::string& text, const std::string& where) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw std::runtime_error(where + ": not a finite number: '" + text + "'");
  return v;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out(1);
  for (char c : line) {
    if (c == ',') out.emplace_back();
    else if (!std::isspace(static_cast<unsigned char>(c))) out.back() += c;
  }
  return out;
}

int test_number(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const std::string name = path.substr(slash == std::string::npos ? 0 : slash + 1);
  const auto pos = name.find("Test");
  if (pos == std::string::npos) return 0;
  return std::atoi(name.c_str() + pos + 4);
}

}  // namespace

TableTest read_table_test(const std::string& path) {
  const auto lines = read_lines(path);
  if (lines.empty() || lines[0].rfind("time_s,table_accel_g", 0) != 0)
    throw std::runtime_error(path + ":1: expected the header 'time_s,table_accel_g'");
  TableTest t;
  t.number = test_number(path);
  t.file = path;
  std::vector<double> times;
  times.reserve(lines.size());
  t.accel_mps2.reserve(lines.size());
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const std::string where = path + ":" + std::to_string(i + 1);
    const auto cells = split(lines[i]);
    if (cells.size() != 2) throw std::runtime_error(where + ": expected 2 columns, got " +
                                                    std::to_string(cells.size()));
    times.push_back(parse_number(cells[0], where));
    t.accel_mps2.push_back(parse_number(cells[1], where) * kGravity);
  }
  if (times.size() < 2) throw std::runtime_error(path + ": fewer than 2 samples");
  // The time column is printed to 6 significant digits (0.0001 s after 10 s): each time is checked
  // against the uniform grid of the first step within twice that rounding.
  const double step0 = times[1] - times[0];
  if (!(step0 > 0.0)) throw std::runtime_error(path + ":3: time does not increase");
  for (std::size_t i = 2; i < times.size(); ++i) {
    const double grid = times[0] + static_cast<double>(i) * step0;
    if (std::abs(times[i] - grid) > 1e-5 * std::abs(times[i]) + 1e-6)
      throw std::runtime_error(path + ":" + std::to_string(i + 2) + ": time " +
                               std::to_string(times[i]) + " s is off the uniform grid of step " +
                               std::to_string(step0) + " s (uniform sampling expected)");
  }
  t.dt = (times.back() - times.front()) / static_cast<double>(times.size() - 1);
  // Offset: the table starts and ends at rest, so the true acceleration integrates to zero over the
  // record (no net velocity change); the record's mean is therefore the instrument's offset.
  double sum = 0.0;
  for (double a : t.accel_mps2) sum += a;
  t.offset_mps2 = sum / static_cast<double>(t.accel_mps2.size());
  for (double& a : t.accel_mps2) {
    a -= t.offset_mps2;
    t.peak_mps2 = std::max(t.peak_mps2, std::abs(a));
    t.peak_positive_mps2 = std::max(t.peak_positive_mps2, a);
    t.peak_negative_mps2 = std::max(t.peak_negative_mps2, -a);
  }
  return t;
}

MeasuredOutcomes read_outcomes(const std::string& path) {
  const auto lines = read_lines(path);
  if (lines.empty()) throw std::runtime_error(path + ": empty");
  const auto header = split(lines[0]);
  if (header.size() < 2 || header[0] != "test")
    throw std::runtime_error(path + ":1: expected 'test,<specimen>_overturned,...'");
  MeasuredOutcomes m;
  for (std::size_t c = 1; c < header.size(); ++c) {
    const auto pos = header[c].find("_overturned");
    if (pos == std::string::npos || pos == 0)
      throw std::runtime_error(path + ":1: column '" + header[c] + "' is not <specimen>_overturned");
    std::string name = header[c].substr(0, pos);
    for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    m.specimens.push_back(name);
  }
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const std::string where = path + ":" + std::to_string(i + 1);
    const auto cells = split(lines[i]);
    if (cells.size() != header.size())
      throw std::runtime_error(where + ": expected " + std::to_string(header.size()) + " columns");
    const int test = static_cast<int>(parse_number(cells[0], where));
    std::vector<int> row;
    for (std::size_t c = 1; c < cells.size(); ++c) {
      if (cells[c] != "0" && cells[c] != "1")
        throw std::runtime_error(where + ": outcome must be 0 or 1, got '" + cells[c] + "'");
      row.push_back(cells[c] == "1");
    }
    if (!m.by_test.emplace(test, row).second)
      throw std::runtime_error(where + ": test " + std::to_string(test) + " listed twice");
  }
  return m;
}

bool exceeds_static_uplift(const Body& body, const TableTest& test, int direction) {
  for (double a : test.accel_mps2)
    if (uplift_side(body, direction * a, 0.0) != 0) return true;
  return false;
}

namespace {

// One test through a model, the same for the planar and the 3-D model: reset with the first sample,
// each record sample (the table acceleration a, direction applied), then the tail at rest, up to an
// overturn. Model: reset(a), step(a), overturned(); record(t, a) keeps a history sample (or not).
template <class Reset, class Step, class Over, class Record>
void run_test(const TableTest& test, double s, long tail, bool history, Reset&& reset, Step&& step,
              Over&& overturned, Record&& record) {
  long sample = 0;
  auto keep = [&](double a) {
    if (history) record(static_cast<double>(sample) * test.dt, a);
  };
  reset(s * test.accel_mps2.front());
  keep(s * test.accel_mps2.front());
  for (std::size_t i = 1; i < test.accel_mps2.size(); ++i) {
    step(s * test.accel_mps2[i]);
    ++sample;
    keep(s * test.accel_mps2[i]);
    if (overturned()) break;
  }
  for (long i = 0; i < tail && !overturned(); ++i) {
    step(0.0);
    ++sample;
    keep(0.0);
  }
}

template <class Outcome>
void fill_outcome(TestPrediction& p, const Outcome& o) {
  p.predicted = o.overturned;
  p.uplift = !std::isnan(o.uplift_time);
  p.max_rotation_ratio = o.max_rotation_ratio;
  p.overturn_time = o.overturned ? o.overturn_time : std::numeric_limits<double>::quiet_NaN();
  p.impacts = o.impacts;
}

}  // namespace

TestPrediction predict_table_test(const BodyParameters& parameters, const std::string& specimen,
                                  const TableTest& test, const ExperimentSettings& settings,
                                  std::vector<TableHistorySample>* history) {
  const Body body(parameters);
  TestPrediction p;
  p.test = test.number;
  p.specimen = specimen;
  p.exceeds_static_uplift = exceeds_static_uplift(body, test, settings.direction);
  AdaptiveModel model(body, settings.adaptive);
  const double s = (settings.direction >= 0 ? 1.0 : -1.0) * settings.input_gain;
  const long tail = static_cast<long>(std::ceil(settings.tail_s / test.dt));
  if (history) {
    history->clear();
    history->reserve(test.accel_mps2.size() + static_cast<std::size_t>(tail));
  }
  run_test(
      test, s, tail, history != nullptr, [&](double a) { model.reset(0.0, a, 0.0); },
      [&](double a) { model.step(a, 0.0, test.dt); }, [&] { return model.outcome().overturned; },
      [&](double t, double a) {
        TableHistorySample h;
        h.t = t;
        h.table_accel_mps2 = a;
        h.theta = model.theta();
        h.omega = model.omega();
        h.rotation_ratio = h.theta == 0.0 ? 0.0 : std::abs(h.theta) / body.pivot(h.theta > 0.0 ? 1 : -1).alpha;
        h.max_rotation_ratio = model.outcome().max_rotation_ratio;
        h.mode = model.mode_name();
        history->push_back(h);
      });
  fill_outcome(p, model.outcome());
  return p;
}

TestPrediction predict_table_test_3d(const BaseBodyParameters& parameters, const std::string& specimen,
                                     const TableTest& test, const ExperimentSettings& settings,
                                     std::vector<TableHistorySample>* history) {
  const BaseBody body(parameters);
  SolverSettings solver = settings.adaptive.rocking;
  solver.method = Method::Dopri5;
  solver.model = ModelKind::Nonlinear;
  Rocking3DModel model(body, solver);
  TestPrediction p;
  p.test = test.number;
  p.specimen = specimen;
  // The gain multiplies the input in the item's frame, as ItemEnsemble scales a member's input
  // (gain * (a * axis), not (gain * a) * axis: live and offline to the bit).
  const double s = settings.direction >= 0 ? 1.0 : -1.0, gain = settings.input_gain;
  const Eigen::Vector3d axis(std::cos(settings.table_azimuth), std::sin(settings.table_azimuth), 0.0);
  // Static uplift in 3-D: some hull edge's moment lifts it at some sample.
  for (double a : test.accel_mps2) {
    for (int k = 0; k < body.vertex_count() && !p.exceeds_static_uplift; ++k) {
      const BaseEdge& e = body.edge(k);
      const double a_n = -(gain * (s * a)) * e.normal.dot(axis);
      p.exceeds_static_uplift = uplift_function(e.pivot, 1, ModelKind::Nonlinear, a_n, 0.0) > 0.0;
    }
    if (p.exceeds_static_uplift) break;
  }
  const long tail = static_cast<long>(std::ceil(settings.tail_s / test.dt));
  const Eigen::Vector3d centre = body.centre_of_mass();
  if (history) {
    history->clear();
    history->reserve(test.accel_mps2.size() + static_cast<std::size_t>(tail));
  }
  run_test(
      test, s, tail, history != nullptr, [&](double a) { model.reset(0.0, gain * (a * axis)); },
      [&](double a) { model.step(gain * (a * axis), test.dt); }, [&] { return model.outcome().overturned; },
      [&](double t, double a) {
        TableHistorySample h;
        h.t = t;
        h.table_accel_mps2 = gain * a;
        // Tilt signed by where the contact lies: on the -x side of the centre of mass > 0.
        double side = 1.0;
        if (model.contact() >= 0) side = model.contact_point().x() <= centre.x() ? 1.0 : -1.0;
        h.theta = side * model.tilt();
        h.omega = model.angular_velocity().norm();
        h.rotation_ratio = model.rotation_ratio();
        h.max_rotation_ratio = model.outcome().max_rotation_ratio;
        h.mode = to_string(model.mode());
        history->push_back(h);
      });
  fill_outcome(p, model.outcome());
  p.final_face = model.face();
  p.rests_off_base = model.outcome_3d().rests_off_base;
  return p;
}

void Confusion::add(bool predicted, bool measured) {
  if (predicted && measured) ++tp;
  else if (predicted) ++fp;
  else if (measured) ++fn;
  else ++tn;
}

double Confusion::accuracy() const {
  return total() ? static_cast<double>(tp + tn) / static_cast<double>(total())
                 : std::numeric_limits<double>::quiet_NaN();
}
double Confusion::precision() const {
  return tp + fp ? static_cast<double>(tp) / static_cast<double>(tp + fp)
                 : std::numeric_limits<double>::quiet_NaN();
}
double Confusion::recall() const {
  return tp + fn ? static_cast<double>(tp) / static_cast<double>(tp + fn)
                 : std::numeric_limits<double>::quiet_NaN();
}
double Confusion::f1() const {
  const double p = precision(), r = recall();
  return (p + r > 0.0) ? 2.0 * p * r / (p + r) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace rocking_monitor::core
