#pragma once

// Two-plane items in the study (issue 11): an item with a depth rocks in its x-z plane (width,
// eccentricity) and in its y-z plane (depth, eccentricity_y), each plane a planar body of the paper
// run by the study's pure-rocking case runner (run_case), without coupling between the planes
// (physics/principal_planes.hpp). Items run on station pairs: both horizontals of a station rotated
// to each requested azimuth (motion/station.hpp rotate()), x along the azimuth, y 90 deg
// counter-clockwise of it seen from above (REP 103: x forward, y left, z up), with the station's
// vertical. The item's verdict is combine() of the plane verdicts (physics/item_verdict.hpp).
//
// Azimuths are in degrees clockwise from north (a user-facing exception to SI: that is how
// components are labelled).
//
// Item case numbering: for each item, for each station pair in load order, for each azimuth in the
// given order, polarity +1 then -1 (both horizontals flipped together; the vertical never is).
// case = item * inputs_per_item + input.
//
// An item with a 3-D description (StudyItem::solid) also runs the 3-D model on the same inputs
// (both horizontals and the vertical at once, polarity flipping both horizontals): its outcome
// goes beside the planes' (columns solid_*), the planes' verdict is unchanged.

#include <array>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "rocking_monitor/integrate/solver_settings.hpp"
#include "rocking_monitor/model/rocking_3d_model.hpp"
#include "rocking_monitor/physics/item_verdict.hpp"
#include "rocking_monitor/physics/principal_planes.hpp"
#include "rocking_monitor/study/study_bodies.hpp"
#include "rocking_monitor/study/study_records.hpp"
#include "rocking_monitor/study/study_runner.hpp"

namespace rocking_monitor::core::study {

/// A station's two horizontals, checked so that they can be rotated together.
struct StationPair {
  std::string event, station;
  std::size_t first = 0, second = 0;  ///< indices into the records, in load order
  double azimuth_first = 0.0, azimuth_second = 0.0;  ///< deg clockwise from north, from the labels
  /// Samples after pairing: the longer of the two lengths (the shorter is zero-padded, as the
  /// study pads a short vertical; a note says so).
  std::size_t samples = 0;
};

/// Station pairs of a record list, with what could not be paired (never dropped silently).
struct StationPairs {
  std::vector<StationPair> pairs;
  long single_horizontal = 0;   ///< stations with one horizontal (only single-plane bodies run them)
  long different_dt = 0;        ///< horizontals with different sample intervals: skipped
  long no_azimuth = 0;          ///< a label carries no direction: skipped
  long not_resolvable = 0;      ///< different start times, nearly parallel sensors, > 2 horizontals
  long zero_padded = 0;         ///< lengths differed: the shorter zero-padded (the pair is used)
  std::vector<std::string> notes;  ///< one line per skipped or padded station
};

/// Groups the records by (event, station) in load order. A component's direction comes from its
/// file header's label when that carries one (the header wins, as for record_to_bag), else from
/// the manifest / file-name label.
StationPairs pair_stations(const std::vector<StudyRecord>& records);

/// The inputs of a two-plane item on one station pair: the ground acceleration along the azimuth
/// (x) and 90 deg counter-clockwise of it (y), on the pair's grid, and the station's vertical
/// (empty without one).
struct PlaneInputs {
  double dt = 0.0, t0 = 0.0;
  std::vector<double> x, y, vertical;
};
/// Throws StudyError naming the station when rotate() refuses the pair.
PlaneInputs plane_inputs(const StationPair& pair, const std::vector<StudyRecord>& records,
                         double azimuth_deg);

/// One plane's levels (combine()'s input) from its outcome.
LevelTimes level_times(const RockingOutcome& outcome);

/// What one item case produced.
struct ItemCaseResult {
  std::size_t index = 0;  ///< global item case index
  std::size_t item = 0;   ///< index into the items
  std::size_t pair = 0;   ///< index into the station pairs
  double azimuth_deg = 0.0;
  int polarity = 1;
  bool vertical = false;
  std::array<CaseResult, kPlaneCount> planes;  ///< [x, y], each as run_case() returns it
  std::array<double, kPlaneCount> pga{};       ///< max |input| of each plane, m/s^2
  ItemVerdict verdict;                         ///< combine(x, y)
  bool solid_run = false;                      ///< the item has a 3-D description: solid is set
  RockingOutcome solid;                        ///< the 3-D model's outcome (levels, impacts)
  Rocking3DOutcome solid_3d;                   ///< its 3-D counts (max tilt, corner wobble)
};

/// Runs one item case: both planes with run_case() on `inputs` (psv not computed: the screening
/// criteria are a single-plane table's).
ItemCaseResult run_item_case(const StudyItem& item, const PlaneInputs& inputs, int polarity,
                             bool vertical, const SolverSettings& settings);

struct ItemStudyOptions {
  SolverSettings settings;
  std::vector<double> azimuths{0.0, 90.0};  ///< deg clockwise from north
  bool both_polarities = true;
  bool verticals = true;  ///< apply the station's vertical when it has one
  int threads = 0;        ///< 0 = all cores
  std::function<void(std::size_t, std::size_t)> progress;  ///< (cases done, cases), calling thread
};

std::size_t item_case_count(std::size_t items, std::size_t pairs, const ItemStudyOptions& options);

/// Runs every item on every station pair, azimuth and polarity; results in case order,
/// bit-identical for any thread count (work is handed out per (item, pair)).
std::vector<ItemCaseResult> run_item_study(const std::vector<StudyItem>& items,
                                           const std::vector<StudyRecord>& records,
                                           const StationPairs& pairs, const ItemStudyOptions& options);

/// item_cases.csv (columns in docs/study.md): header and one row per item case.
const std::vector<std::string>& item_case_csv_columns();
void write_item_cases_csv(std::ostream& out, const std::vector<ItemCaseResult>& results,
                          const std::vector<StudyItem>& items, const std::vector<StudyRecord>& records,
                          const StationPairs& pairs);

/// Counts over the item cases (summary.json "two_plane_items").
struct ItemTally {
  long cases = 0, overturned = 0, committed = 0, beyond_tipping = 0;
  long overturned_decided_by_y = 0;      ///< the y plane overturned first (a tie names x)
  long overturned_x_only = 0, overturned_y_only = 0, overturned_both = 0;
  /// Cases the 3-D model ran; of them overturned by it; its overturn decision differing from the
  /// planar pair's (overturned by one model, not the other).
  long solid_cases = 0, solid_overturned = 0, solid_differs = 0;
  void add(const ItemCaseResult& c);
};
struct ItemSummary {
  std::size_t items = 0, pairs = 0;
  std::vector<double> azimuths;
  ItemTally all;
  std::vector<ItemTally> by_azimuth;            ///< same order as azimuths
  std::vector<std::string> item_names;
  std::vector<ItemTally> by_item;
  StationPairs skipped;                         ///< the pairing counts and notes (pairs cleared)
};
ItemSummary summarize_items(const std::vector<ItemCaseResult>& results, const std::vector<StudyItem>& items,
                            const StationPairs& pairs, const std::vector<double>& azimuths);

/// Parses "0,90" / "45" into azimuths (deg); throws StudyError naming the text for a bad or
/// non-finite number.
std::vector<double> parse_azimuths(const std::vector<std::string>& texts);

}  // namespace rocking_monitor::core::study
