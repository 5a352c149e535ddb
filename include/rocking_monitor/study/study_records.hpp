#pragma once

// The records of the study: every horizontal component of a records directory with the vertical of
// its station (MANIFEST.csv or a directory scan).

#include <string>
#include <vector>

#include "rocking_monitor/motion/component.hpp"
#include "rocking_monitor/study/study_error.hpp"

namespace rocking_monitor::core::study {

/// One horizontal record component with the vertical of the same station, ready to run.
struct StudyRecord {
  std::string event;       ///< event slug (manifest) or directory name
  std::string station;     ///< station name
  std::string component;   ///< horizontal label, e.g. "228", "N-S"
  std::string header_label;  ///< the label in the file's header (may differ from `component`)
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

}  // namespace rocking_monitor::core::study
