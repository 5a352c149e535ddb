#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/motion/streaming_intensity.hpp"

namespace rocking_monitor::core {

/// One catalogue entry: a free-standing item, the sensor that feeds it and its frame.
struct ItemSpec {
  std::string id;           ///< unique name
  std::string description;  ///< free text for people
  std::string sensor;       ///< name of the sensor whose acceleration drives it
  std::string frame;        ///< tf frame: x across the base width (rocking direction), z up
  BodyParameters body;
};

/// Empty if valid, else "item '<id>': <field>: <problem>" (for start-up errors).
std::string validate(const ItemSpec& spec);

/// Live state codes (the values of RockingState.msg's constants).
enum class ItemMode : std::uint8_t { Rest = 0, Rocking = 1, BeyondTipping = 2, Committed = 3, Overturned = 4 };
const char* to_string(ItemMode mode);

/// Criterion codes (the values of CriterionExceedance.msg's constants).
enum class CriterionId : std::uint8_t {
  Housner = 0, Ishiyama = 1, IshiyamaEquivalent = 2, Proposed = 3,
  FreeFlight = 4, SlideFromRest = 5, SlideAtUplift = 6, SlideWhileRocking = 7,
};
inline constexpr int kCriterionIdCount = 8;
inline constexpr int kScreeningCount = 4;
const char* to_string(CriterionId id);

/// A criterion changed state at the end of a sample. Exceeded means value > threshold (and, for the
/// Ishiyama-type criteria, also second_value >= second_threshold).
struct CriterionChange {
  CriterionId id = CriterionId::Housner;
  bool exceeded = false;
  double value = 0.0, threshold = 0.0;               ///< SI (m/s, m/s^2 or a ratio)
  double second_value = 0.0, second_threshold = 0.0; ///< Ishiyama-type: PGA and its threshold, m/s^2
};

/// An overturning level reached during a sample.
struct AlarmEvent {
  ItemMode level = ItemMode::BeyondTipping;  ///< BeyondTipping, Committed or Overturned
  double time = 0.0;                         ///< s, when it was reached (inside the sample)
  double rotation_ratio = 0.0;
};

/// What one step produced. Fixed capacity: no allocation in the sample loop.
struct ItemEvents {
  int change_count = 0;
  std::array<CriterionChange, kCriterionIdCount> changes;
  int alarm_count = 0;
  std::array<AlarmEvent, 3> alarms;
};

/// One item of the live monitor: the rocking model plus its running screening criteria (Housner from
/// the running 5 %-damped pseudo-velocity at housner_period(), Ishiyama and variants from running PGA
/// and high-pass PGV of the item's own horizontal input) and the model-validity criteria.
/// ROS-free, so the node and an offline replay produce the same numbers.
class ItemMonitor {
 public:
  struct Options {
    SolverSettings solver;
    double velocity_highpass_hz = 0.05;  ///< PGV high-pass corner, Hz (see StreamingIntensity)
    /// Rocking: pure rocking, violations flagged (default). Adaptive / Contact: sliding and free
    /// flight modelled (AdaptiveModel, docs/fidelity.md); the validity criteria are then not flagged.
    Fidelity fidelity = Fidelity::Rocking;
    /// Adaptive: scene envelope of the static pre-check (AdaptiveSettings::scene; inf = unknown).
    SceneEnvelope scene{};
    /// Adaptive: linearized tier for slender items (AdaptiveSettings::linearized_max_alpha, rad; 0 = off).
    double linearized_max_alpha = 0.0;
  };

  /// Throws std::invalid_argument (message from validate()) for a bad spec.
  ItemMonitor(const ItemSpec& spec, const Options& options);

  /// (Re)starts at time t (s) at rest with the first sample (m/s^2); dt_nominal (s) sizes the
  /// running spectrum. Allocates (once); not for the per-sample path.
  void start(double t, double ax, double ay, double dt_nominal);
  bool started() const { return started_; }

  /// One sample: horizontal ax along the item's x and vertical ay (m/s^2), dt seconds after the
  /// previous one. No allocation.
  const ItemEvents& step(double ax, double ay, double dt);

  /// Events of the last step().
  const ItemEvents& events() const { return events_; }
  ItemMode mode() const;
  /// The pure-rocking model (the one that runs with Fidelity::Rocking).
  const RockingModel& model() const { return model_; }
  /// Present with Fidelity::Adaptive or Contact.
  const AdaptiveModel* adaptive() const { return adaptive_.get(); }
  // The state of whichever model runs:
  int side() const;
  double theta() const;                ///< rad
  double omega() const;                ///< rad/s
  double rotation_ratio() const;       ///< |theta| / alpha of the active pivot
  OverturnMargin margin() const;
  long impacts() const;
  double slip() const;                 ///< m, base displacement relative to the floor
  ContactMode contact_mode() const;    ///< REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT, OVERTURNED
  const char* active_model() const;    ///< "rocking" or "contact"
  const Body& body() const { return model_.body(); }
  const ItemSpec& spec() const { return spec_; }
  const ScreeningThresholds& thresholds() const { return thresholds_; }
  /// Screening criteria exceeded so far (they are running maxima, so they stay exceeded).
  bool screening_exceeded(CriterionId id) const { return exceeded_[static_cast<int>(id)]; }
  std::uint8_t violations() const;  ///< RockingState VIOLATION_* bitmask
  double pga() const { return intensity_ ? intensity_->pga() : 0.0; }
  double pgv() const { return intensity_ ? intensity_->pgv() : 0.0; }
  double housner_demand() const { return intensity_ ? intensity_->psv()[0] : 0.0; }

 private:
  void evaluate_criteria(double ax, double ay);
  void report_switch(SwitchReason reason, bool to_contact);
  void record_change(CriterionId id, bool exceeded, double value, double threshold,
                     double second_value = 0.0, double second_threshold = 0.0);

  ItemSpec spec_;
  Options options_;
  RockingModel model_;
  std::unique_ptr<AdaptiveModel> adaptive_;
  ScreeningThresholds thresholds_;
  std::unique_ptr<StreamingIntensity> intensity_;
  bool started_ = false;
  bool slid_at_uplift_ = false;  // latched from the onset until the body is back at rest
  CriterionId last_switch_criterion_ = CriterionId::SlideFromRest;  // adaptive: why it went up
  std::array<bool, kCriterionIdCount> exceeded_{};
  ItemEvents events_;
};

}  // namespace rocking_monitor::core
