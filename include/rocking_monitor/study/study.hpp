#pragma once

// The paper's parametric study (Boroschek & Romo, "Overturning criteria for non-anchored
// non-symmetric rigid bodies", sections "Overturning criteria validation for symmetric bodies" and
// "... for non-symmetric bodies"): every body of a grid against every horizontal record component,
// in both polarities, with and without the vertical component of the same station, compared with
// the screening criteria (Housner eq. 1, Ishiyama eq. 2, Ishiyama with B' = 2 nu B, the 0.2 rule).
//
// ROS-free and free of I/O libraries: the YAML body files and the JSON summary live in
// rocking_monitor/study/study_io.hpp (built with the tool, not into the core library); rocking_study
// is the command line over both. Everything is in namespace rocking_monitor::core::study.
//
// Case numbering (stable, documented in docs/study.md): the inputs of one body are, for each record
// component r in load order, polarity +1 then -1, and for each polarity "vertical off" then
// (when the station has a vertical) "vertical on". case = body * inputs_per_body + input. Results
// are stored by case index, so the output does not depend on the number of threads, and a shard
// k/n is the contiguous index range [floor((k-1) N / n), floor(k N / n)).

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rocking_monitor/physics/body.hpp"
#include "rocking_monitor/motion/component.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/integrate/solver_settings.hpp"

namespace rocking_monitor::core::study {

/// Thrown for a bad study input (records directory, manifest, shard, case file); what() is one line
/// naming the file (and line or item) and the problem.
class StudyError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ------------------------------------------------------------------ bodies

struct StudyBody {
  std::string name;           ///< unique label, e.g. "h0.630_B0.252_nu0.30"
  BodyParameters parameters;  ///< radius_of_gyration always set explicitly (finite)
};

/// The paper's grid (section "Overturning criteria validation for symmetric bodies"): `heights`
/// centre-of-mass heights log-spaced over [min_height, max_height]; for each, `widths` base widths
/// geometrically spaced over [max(min_width, min_width_ratio h), min(max_width, max_width_ratio h)];
/// homogeneous rectangles B x 2h; each eccentricity nu (CoM at nu B from corner 1) keeps the radius
/// of gyration of its symmetric twin (the paper: "the same moment of inertia").
struct StudyGrid {
  int heights = 4;
  double min_height = 0.25, max_height = 4.0;  ///< m
  int widths = 12;
  double min_width = 0.08, max_width = 3.5;    ///< m
  double min_width_ratio = 0.16, max_width_ratio = 1.2;  ///< B / h limits
  std::vector<double> eccentricities{0.5, 0.4, 0.3, 0.2};
};

/// Bodies of the grid, ordered eccentricity-major, then height, then width. Throws StudyError for an
/// empty or inconsistent grid (counts < 1, limits not positive, empty width range, nu outside (0, 1)).
std::vector<StudyBody> grid_bodies(const StudyGrid& grid = {});

/// n values from lo to hi inclusive with constant ratio (n == 1 gives {lo}).
std::vector<double> geometric_spacing(double lo, double hi, int n);

/// Eccentricity class of a body: min(nu1, 1 - nu1) (a body with nu1 = 0.7 is the mirror image of
/// nu1 = 0.3; both polarities of every record are run, so the two give the same set of cases).
double eccentricity_of(const BodyParameters& body);

// ------------------------------------------------------------------ records

/// One horizontal record component with the vertical of the same station, ready to run.
struct StudyRecord {
  std::string event;       ///< event slug (manifest) or directory name
  std::string station;     ///< station name
  std::string component;   ///< horizontal label, e.g. "228", "N-S"
  std::string file;        ///< path relative to the records directory
  std::string vertical_component;  ///< empty: the station has no vertical
  std::string vertical_file;
  double dt = 0.0;                 ///< s
  double t0 = 0.0;                 ///< s
  std::vector<double> horizontal;  ///< as recorded, m/s^2 (the rocking input, like rocking_sim)
  std::vector<double> vertical;    ///< on the horizontal's grid (zero-padded / cut), m/s^2, up
  std::vector<double> corrected;   ///< baseline-corrected horizontal (for the PSV), m/s^2
  double pga = 0.0;           ///< max |a_h| as recorded, m/s^2
  double pgv = 0.0;           ///< max |v_h| after baseline correction (peak_ground_motion), m/s
  double pga_vertical = 0.0;  ///< max |a_v|, m/s^2 (0 without a vertical)

  bool has_vertical() const { return !vertical.empty(); }
};

/// Builds a StudyRecord from read components (PGA, PGV and the corrected series computed here).
/// A vertical with a different dt is not paired (the reason goes to *notice); a shorter one is
/// zero-padded, a longer one cut (also noted).
StudyRecord make_study_record(const Component& horizontal, const Component* vertical,
                              std::string event, std::string station, std::string component,
                              std::string file, std::string* notice = nullptr);

struct RecordSelection {
  /// Keep only components whose relative file path, event or station contains one of these
  /// (case-sensitive); empty = keep all.
  std::vector<std::string> only;
  /// Drop components whose relative file path contains one of these.
  std::vector<std::string> exclude;
};

struct StudyRecords {
  std::string root;
  bool from_manifest = false;      ///< MANIFEST.csv was used (else a directory scan)
  std::vector<StudyRecord> records;
  std::vector<std::string> notes;  ///< pairing notices, skipped files
};

/// Loads every horizontal component of a records directory. With a MANIFEST.csv (format of
/// ../shared/records/README.md: columns event, station, component "H:<label>"/"V:<label>", file)
/// rows are taken in manifest order and verticals paired by (event, station). Without one, every
/// file below `dir` whose format is recognised (AT2, BBP, SMC, CSV; sorted by path) is read and its
/// components grouped by (directory, station name from the header, else the file name); a
/// 3-column CSV is one station with its vertical. Throws StudyError / RecordError naming the file.
StudyRecords load_study_records(const std::string& dir, const RecordSelection& selection = {});

// ------------------------------------------------------------------ cases

/// One excitation of a body: record component, polarity (+1 as recorded, -1 reversed; the vertical
/// is never reversed), vertical on or off.
struct StudyInput {
  std::size_t record = 0;
  int polarity = 1;
  bool vertical = false;
};

struct StudyPlanOptions {
  bool both_polarities = true;  ///< false: polarity +1 only
  bool verticals = true;        ///< false: never run the "vertical on" cases
};

/// The inputs of one body, in case order (see the file comment).
std::vector<StudyInput> study_inputs(const std::vector<StudyRecord>& records,
                                     const StudyPlanOptions& options = {});

/// Contiguous case range.
struct CaseRange {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};

/// Shard k of n (1 <= k <= n) of `total` cases: [floor((k-1) total / n), floor(k total / n)).
/// Throws StudyError for k or n out of range.
CaseRange shard_range(std::size_t total, int k, int n);
/// Parses "k/n" (e.g. "2/8"); throws StudyError naming the text.
std::pair<int, int> parse_shard(const std::string& text);

/// What one case produced.
struct CaseResult {
  std::size_t index = 0;   ///< global case index
  std::size_t body = 0;    ///< index into the bodies
  std::size_t record = 0;  ///< index into the records
  int polarity = 1;
  bool vertical = false;
  RockingOutcome outcome;
  Mode final_mode = Mode::Rest;
  double max_theta = 0.0;         ///< max |theta| reached, rad (= max_rotation_ratio * alpha of that pivot)
  std::uint8_t violations = 0;    ///< bit (1 << Criterion): the onset happened at least once
  double first_violation_time = std::numeric_limits<double>::quiet_NaN();  ///< s, first onset (NaN: none)
  double housner_period = 0.0;    ///< s, housner_period(body)
  double housner_psv = 0.0;       ///< 5 %-damped PSV of the corrected horizontal at that period, m/s
  ScreeningThresholds thresholds;
  ScreeningPrediction prediction;
};

/// 5 %-damped pseudo-velocity of `accel` at `period` (Nigam-Jennings, maxima over the samples), m/s.
double pseudo_velocity_at(const std::vector<double>& accel, double dt, double period,
                          double damping = 0.05);

/// Runs one case. `psv` is the record's PSV at housner_period(body) (pass NaN to compute it here).
CaseResult run_case(const Body& body, const StudyRecord& record, int polarity, bool vertical,
                    const SolverSettings& settings, double psv);

struct StudyOptions {
  SolverSettings settings;
  StudyPlanOptions plan;
  int threads = 0;  ///< 0 = std::thread::hardware_concurrency()
  /// Cases to run (global indices); the default (end = SIZE_MAX) means all.
  CaseRange range{0, std::numeric_limits<std::size_t>::max()};
  /// Called from the calling thread about every progress_interval_s seconds and once at the end,
  /// with (cases done, cases in range).
  std::function<void(std::size_t, std::size_t)> progress;
  double progress_interval_s = 0.5;
};

/// Total number of cases for these bodies and records.
std::size_t study_case_count(std::size_t bodies, const std::vector<StudyRecord>& records,
                             const StudyPlanOptions& plan = {});

/// Runs the cases of options.range on options.threads threads. Work is handed out per
/// (body, record) so the PSV is computed once for its 2-4 cases; results are returned in case order
/// and are bit-identical for any thread count. Throws the first error a worker met.
std::vector<CaseResult> run_study(const std::vector<StudyBody>& bodies,
                                  const std::vector<StudyRecord>& records, const StudyOptions& options);

// ------------------------------------------------------------------ per-case CSV

/// Column names of cases.csv, in order (documented in docs/study.md).
const std::vector<std::string>& case_csv_columns();
void write_case_csv_header(std::ostream& out);
/// One line per case (no header), fields as named by case_csv_columns().
void write_case_csv_rows(std::ostream& out, const std::vector<CaseResult>& results,
                         const std::vector<StudyBody>& bodies, const std::vector<StudyRecord>& records);

/// bodies.csv: one row per body with its derived geometry and screening thresholds.
void write_bodies_csv(std::ostream& out, const std::vector<StudyBody>& bodies);
/// records.csv: one row per record component (index, event, station, component, file, vertical,
/// dt, samples, PGA, PGV, vertical PGA).
void write_records_csv(std::ostream& out, const std::vector<StudyRecord>& records);

// ------------------------------------------------------------------ summary

/// The screening criteria compared (ScreeningPrediction fields), in this order.
enum class Screening : int { Housner = 0, Ishiyama = 1, IshiyamaEquivalent = 2, Proposed = 3 };
inline constexpr int kScreeningCount = 4;
const char* to_string(Screening criterion);

/// What the summary needs of a case (from a CaseResult or from a cases.csv row).
struct CaseRow {
  std::size_t index = 0, body = 0, record = 0;
  double width = 0.0, cg_height = 0.0, nu1 = 0.5;
  double pgv = 0.0;  ///< m/s, of the record component
  int polarity = 1;
  bool vertical = false;
  bool overturned = false, committed = false, beyond_tipping = false;
  std::array<bool, kScreeningCount> predicted{};
};
CaseRow to_case_row(const CaseResult& result, const std::vector<StudyBody>& bodies,
                    const std::vector<StudyRecord>& records);

/// Counts over a group of cases. For each criterion: predicted = it predicts overturning;
/// missed = overturned although it predicted safety (the criterion is "not satisfied");
/// false_alarm = predicted overturning, the body stayed.
struct Tally {
  long cases = 0, overturned = 0, committed = 0, beyond_tipping = 0;
  std::array<long, kScreeningCount> predicted{}, missed{}, false_alarms{};
  void add(const CaseRow& row);
  double overturned_percent() const { return cases ? 100.0 * overturned / cases : 0.0; }
  /// Share (%) of cases where the criterion is satisfied: no overturn where it predicts safety.
  double consistent_percent(Screening c) const {
    return cases ? 100.0 * (cases - missed[static_cast<int>(c)]) / cases : 0.0;
  }
};

/// Upper edges of the PGV bands of SetSummary::by_eccentricity_pgv, m/s (the last band is open).
inline const std::vector<double>& pgv_band_edges() {
  static const std::vector<double> edges{0.1, 0.3, 1.0};
  return edges;
}
/// Band of a PGV (0 .. pgv_band_edges().size()).
std::size_t pgv_band(double pgv);

/// Tallies of one set of cases, by eccentricity (descending: 0.5 first), centre-of-mass height
/// (ascending) and PGV band.
struct SetSummary {
  std::string name;
  std::vector<double> eccentricities;
  std::vector<double> heights;
  std::vector<Tally> by_eccentricity;
  std::vector<std::vector<Tally>> by_eccentricity_height;  ///< [eccentricity][height]
  std::vector<std::vector<Tally>> by_eccentricity_pgv;     ///< [eccentricity][pgv band]
  Tally all;
  /// Index of eccentricity 0.5 (symmetric) or -1.
  int symmetric_index() const;
  /// Overturned share at eccentricity e / overturned share at 0.5 (Figure 8), over all cases of that
  /// eccentricity (height < 0) or of one height; equal to the ratio of counts when every
  /// eccentricity has the same cases (the grid). NaN without symmetric overturns.
  double overturn_ratio(std::size_t eccentricity, int height = -1) const;
  /// The same restricted to one PGV band.
  double overturn_ratio_pgv(std::size_t eccentricity, std::size_t band) const;
};

/// The effect of the vertical component: cases that have a vertical, paired on (body, record,
/// polarity), by eccentricity.
struct VerticalEffect {
  std::vector<double> eccentricities;
  std::vector<long> pairs, overturned_without, overturned_with, only_with, only_without;
};

struct StudySummary {
  std::size_t cases = 0, bodies = 0, records = 0, records_with_vertical = 0;
  SetSummary horizontal;               ///< every record, vertical off (the paper's setting)
  SetSummary subset_without_vertical;  ///< records that have a vertical, vertical off
  SetSummary with_vertical;            ///< the same records, vertical on
  VerticalEffect vertical_effect;
};

/// Summary of any set of cases (rows in any order).
StudySummary summarize(const std::vector<CaseRow>& rows);

/// Human-readable table (what rocking_study prints).
std::string format_summary(const StudySummary& summary);

/// Reads the rows of one or more cases.csv files (header required; columns found by name), for
/// merging shards. Throws StudyError "<file>:<line>: ..." (malformed CSV included, csv layer).
struct CaseFile {
  std::vector<CaseRow> rows;
  std::vector<std::string> lines;  ///< the data rows as written (csv::Row::text), same order as rows
  std::string header;              ///< the header row as written
};
CaseFile read_case_csv(const std::string& path);

}  // namespace rocking_monitor::core::study
