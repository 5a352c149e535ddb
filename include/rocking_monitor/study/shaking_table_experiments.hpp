#pragma once
// Real shaking-table experiments (issue 20): the table's measured acceleration of each test, the
// measured outcome per specimen, and the engine's prediction of it. See docs/validation.md.
#include <map>
#include <string>
#include <vector>

#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/physics/base_body.hpp"
#include "rocking_monitor/physics/body.hpp"

namespace rocking_monitor::core {

/// One test's table acceleration (a `time_s,table_accel_g` CSV, gzipped or not).
struct TableTest {
  int number = 0;            ///< from the file name TestNNN
  std::string file;
  double dt = 0.0;           ///< s, the sampling interval (uniform; checked)
  double offset_mps2 = 0.0;  ///< removed instrument offset, m/s^2 (the record's mean, see .cpp)
  double peak_mps2 = 0.0;    ///< max |a| after the offset is removed, m/s^2
  double peak_positive_mps2 = 0.0;  ///< max a (toward +x), m/s^2
  double peak_negative_mps2 = 0.0;  ///< max -a (toward -x), m/s^2
  std::vector<double> accel_mps2;   ///< offset removed, m/s^2, positive along the shaking axis +x
};

/// Reads a test. Throws std::runtime_error "<file>:<line>: <problem>" (bad header or number,
/// non-uniform or non-increasing time, fewer than 2 samples).
TableTest read_table_test(const std::string& path);

/// outcomes.csv: `test,<specimen>_overturned,...` (1 = overturned, 0 = not); the specimen names are
/// the header's column prefixes upper-cased (sp1_overturned -> SP1). Throws "<file>:<line>: ...".
struct MeasuredOutcomes {
  std::vector<std::string> specimens;
  std::map<int, std::vector<int>> by_test;  ///< test -> one 0/1 per specimen
};
MeasuredOutcomes read_outcomes(const std::string& path);

struct ExperimentSettings {
  AdaptiveSettings adaptive{};  ///< default fidelity (adaptive)
  /// s of table at rest appended after the record: a body still rocking when the recording stops
  /// settles or falls (the experiments' outcome is the final state).
  double tail_s = 5.0;
  /// +1: table acceleration positive toward +x (pivot 2 side), as recorded; -1: reversed.
  int direction = 1;
  /// 3-D model only: the table's axis turned by this angle from the floor frame's x towards y, rad
  /// (how the specimen stood on the table is itself uncertain).
  double table_azimuth = 0.0;
  /// Dimensionless, > 0: the table acceleration is multiplied by it (a catalogue item's input_gain,
  /// or the scale searched by table_test_margin).
  double input_gain = 1.0;
};

struct TestPrediction {
  int test = 0;
  std::string specimen;
  bool predicted = false;     ///< the engine's overturn
  int measured = -1;          ///< 1 overturned, 0 not, -1 no outcome for this test
  bool uplift = false;        ///< rocking started
  double max_rotation_ratio = 0.0;  ///< max |theta| / alpha of the pivot
  double overturn_time = 0.0;       ///< s, NaN when not overturned
  long impacts = 0;
  bool exceeds_static_uplift = false;  ///< the table reached g tan(alpha) toward some pivot
  int final_face = 0;         ///< 3-D with a hull: the hull face it ends on (0: its base)
  long rests_off_base = 0;    ///< 3-D with a hull: rests on another hull face during the test
};

/// One sample of a test's rotation history (predict_table_test with a history): the state after the
/// table sample at time t. (Not core::HistorySample of monitoring/simulation.hpp: one name for two
/// structs in one namespace is an ODR violation, which AddressSanitizer caught.)
struct TableHistorySample {
  double t = 0.0;                 ///< s from the record's first sample
  double table_accel_mps2 = 0.0;  ///< table acceleration fed to the model (offset removed, direction applied), m/s^2
  double theta = 0.0;             ///< rad, > 0 rocking on pivot 1 (corner 1, -x)
  double omega = 0.0;             ///< rad/s
  double rotation_ratio = 0.0;    ///< |theta| / alpha of the pivot it rocks on (0 at rest)
  /// the outcome's max |theta| / alpha so far (includes peaks between samples: the table's column
  /// at the last sample)
  double max_rotation_ratio = 0.0;
  const char* mode = "";          ///< the active model's mode name (REST, ROCKING, SLIDE, ...)
};

/// Static uplift (eq. 19): the table acceleration toward +x lifts pivot 1 (corner 1, -x side)...
/// returns true when the record reaches g tan(alpha) of the pivot it would lift in either direction.
bool exceeds_static_uplift(const Body& body, const TableTest& test, int direction = 1);

/// Runs one specimen (its x-z plane) through one test. With `history`, it is cleared and gets one
/// sample at the start (at rest) and one per table sample stepped (record, then the tail at rest),
/// up to the overturn.
TestPrediction predict_table_test(const BodyParameters& body, const std::string& specimen,
                                  const TableTest& test, const ExperimentSettings& settings = {},
                                  std::vector<TableHistorySample>* history = nullptr);

/// The same with the 3-D model (model/rocking_3d_model.hpp) on the specimen's base polygon: the
/// table moves along the floor frame's x. History samples carry the tilt of the base as theta
/// (signed by the side of the centre of mass the active contact lies on: > 0 on -x, as the planar
/// pivot 1) and the 3-D rotation ratio.
TestPrediction predict_table_test_3d(const BaseBodyParameters& body, const std::string& specimen,
                                     const TableTest& test, const ExperimentSettings& settings = {},
                                     std::vector<TableHistorySample>* history = nullptr);

/// Confusion matrix of predicted vs measured overturning (tests without an outcome not counted).
struct Confusion {
  long tp = 0, fp = 0, tn = 0, fn = 0;
  void add(bool predicted, bool measured);
  long total() const { return tp + fp + tn + fn; }
  double accuracy() const;
  double precision() const;  ///< NaN when nothing predicted overturned
  double recall() const;     ///< NaN when nothing overturned
  double f1() const;
};

}  // namespace rocking_monitor::core
