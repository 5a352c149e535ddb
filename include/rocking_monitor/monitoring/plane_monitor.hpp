#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "rocking_monitor/model/adaptive_model.hpp"
#include "rocking_monitor/monitoring/item_modes.hpp"
#include "rocking_monitor/physics/criteria.hpp"
#include "rocking_monitor/model/rocking_model.hpp"
#include "rocking_monitor/motion/streaming_intensity.hpp"

namespace rocking_monitor::core {

/// Planar: the planar pair always; Solid: the 3-D model always; Auto: the 3-D model when the base is
/// not an axis-aligned rectangle (oblique or irregular) or the shaking is bidirectional, else the
/// planar pair (the cheaper model where it is exact: a rectangle under one component along a side).
enum class SolidChoice : std::uint8_t { Planar, Solid, Auto };
const char* to_string(SolidChoice choice);
/// "planar" | "3d" | "auto"; false for an unknown name.
bool parse_solid_choice(const std::string& text, SolidChoice& choice);

/// One rocking plane of a live item: the planar rocking model plus its running screening criteria
/// (Housner from the running 5 %-damped pseudo-velocity at housner_period(), Ishiyama and variants from
/// running PGA and high-pass PGV of the plane's own horizontal input) and the model-validity criteria.
/// ItemMonitor holds one per plane. ROS-free, so the node and an offline replay give the same numbers.
class PlaneMonitor {
 public:
  struct Options {
    SolverSettings solver;
    double velocity_highpass_hz = 0.05;  ///< PGV high-pass corner, Hz (see StreamingIntensity)
    /// Adaptive (default): pure rocking while valid, sliding and free flight modelled when needed
    /// (AdaptiveModel, docs/fidelity.md); the validity criteria are then reported as model switches.
    /// Rocking: pure rocking only, violations flagged (the speed option). Contact: always the contact model.
    Fidelity fidelity = Fidelity::Adaptive;
    /// Adaptive: scene envelope of the static pre-check (AdaptiveSettings::scene; inf = unknown).
    SceneEnvelope scene{};
    /// Adaptive: linearized tier for slender items (AdaptiveSettings::linearized_max_alpha, rad; 0 = off).
    double linearized_max_alpha = 0.0;
    /// ItemMonitor, items with a 3-D description (ItemSpec::solid): which model decides the item's
    /// state and alarms (model/rocking_3d_model.hpp, docs/fidelity.md).
    SolidChoice solid = SolidChoice::Auto;
    /// SolidChoice::Auto: the 3-D model takes over (at rest) once the weaker horizontal component's
    /// running peak reaches this fraction of the stronger one's (bidirectional shaking).
    double bidirectional_ratio = 0.3;
  };

  /// Throws BodyError (naming the field) for a bad body.
  PlaneMonitor(const BodyParameters& body, const Options& options);

  /// (Re)starts at time t (s) at rest with the first sample (m/s^2); dt_nominal (s) sizes the
  /// running spectrum. Allocates (once); not for the per-sample path.
  void start(double t, double ax, double ay, double dt_nominal);
  bool started() const { return started_; }
  /// The running spectrum's sample interval given to start(), s (0 before).
  double dt_nominal() const { return intensity_ ? intensity_->config().dt : 0.0; }

  /// One sample: horizontal ax along the item's x and vertical ay (m/s^2), dt seconds after the
  /// previous one. No allocation.
  const PlaneEvents& step(double ax, double ay, double dt);
  /// The rest of step() once the adaptive model's sample is applied already (MonitorBatch: a rocking
  /// sample its vector kernel found clean, with nothing the model reports but its state, in which a
  /// running PGA, PGV or PSV grows): the running intensity and the screening criteria. Such a sample
  /// brings no alarm and no model switch (the same conditions as a deferred one).
  const PlaneEvents& step_after_model(double ax, double ay);

  /// Everything one sample carries to the next (state snapshots, issue 29): restored into a plane
  /// monitor of the same body and options it continues bit for bit. The last sample's events are
  /// not in it (a restored monitor has none until it steps).
  struct Saved {
    bool started = false;
    double dt_nominal = 0.0;  ///< s, sizes the running spectrum
    bool has_adaptive = false;
    RockingModel::Saved model;    ///< without the adaptive model (which has its own)
    AdaptiveModel::Saved adaptive;
    StreamingIntensity::Saved intensity;
    bool slid_at_uplift = false;
    CriterionId last_switch_criterion = CriterionId::SlideFromRest;
    std::array<bool, kCriterionIdCount> exceeded{};
  };
  /// Reuses out's storage.
  void save(Saved& out) const;
  /// std::invalid_argument when in was saved by a plane monitor of other options (adaptive or not).
  /// Allocates (the running spectrum), as start() does.
  void restore(const Saved& in);

  /// Events of the last step().
  const PlaneEvents& events() const { return events_; }
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
  /// Whether this plane models friction (the adaptive model with a finite mu_s): the pair may share it.
  bool models_friction() const { return adaptive_ && !std::isinf(model_.body().mu_s()); }
  /// The pair's share of mu_s from the next step on (friction_share.hpp); no effect without friction.
  void set_friction_share(double share) { if (models_friction()) adaptive_->set_friction_share(share); }
  ContactMode contact_mode() const;    ///< REST, SLIDE, ROCK, SLIDE_ROCK, FLIGHT, OVERTURNED
  const char* active_model() const;    ///< "rocking" or "contact"
  const Body& body() const { return model_.body(); }
  const ScreeningThresholds& thresholds() const { return thresholds_; }
  /// Screening criteria exceeded so far (they are running maxima, so they stay exceeded).
  bool screening_exceeded(CriterionId id) const { return exceeded_[static_cast<int>(id)]; }
  std::uint8_t violations() const;  ///< RockingState VIOLATION_* bitmask
  double pga() const { return intensity_ ? intensity_->pga() : 0.0; }
  double pgv() const { return intensity_ ? intensity_->pgv() : 0.0; }
  double housner_demand() const { return intensity_ ? intensity_->psv()[0] : 0.0; }

 private:
  friend class MonitorBatch;  // defers quiet samples of many planes (monitoring/monitor_batch.hpp)
  void make_intensity(double dt_nominal);
  void evaluate_criteria(double ax, double ay);
  void report_switch(SwitchReason reason, bool to_contact);
  void record_change(CriterionId id, bool exceeded, double value, double threshold,
                     double second_value = 0.0, double second_threshold = 0.0);

  Options options_;
  RockingModel model_;
  std::unique_ptr<AdaptiveModel> adaptive_;
  ScreeningThresholds thresholds_;
  std::unique_ptr<StreamingIntensity> intensity_;
  bool started_ = false;
  bool slid_at_uplift_ = false;  // latched from the onset until the body is back at rest
  CriterionId last_switch_criterion_ = CriterionId::SlideFromRest;  // adaptive: why it went up
  std::array<bool, kCriterionIdCount> exceeded_{};
  PlaneEvents events_;
};

}  // namespace rocking_monitor::core
