#pragma once

#include <string>

#include "rocking_monitor/physics/dynamics.hpp"

namespace rocking_monitor::core {

/// Integration method (see README, "Integrators").
enum class Method {
  Dopri5,    ///< adaptive Dormand-Prince 5(4), dense output, located events (reference)
  Rk4,       ///< fixed-step RK4, `substeps` per input sample, events by Hermite interpolation
  Analytic,  ///< exact closed form of the linearized equation (linearized model only)
};

struct SolverSettings {
  Method method = Method::Dopri5;
  ModelKind model = ModelKind::Nonlinear;
  /// dopri5: relative tolerance; absolute tolerances are tol*alpha (theta) and tol*p*alpha (omega).
  double tol = 1e-8;
  /// rk4: sub-steps per input sample.
  int substeps = 4;
  /// Rest capture (Zeno rule): after an impact, the body returns to REST when its angular
  /// velocity is below rest_capture_ratio * p * alpha of the new pivot, i.e. when its kinetic
  /// energy is below rest_capture_ratio^2 of the energy needed to reach the tipping angle.
  double rest_capture_ratio = 1e-3;
  /// Bound on impacts + uplifts in one input sample; beyond it the body is put to REST for the
  /// rest of the sample (counted as a forced rest capture). Keeps the work per sample bounded.
  int max_events_per_sample = 1000;
};

/// Empty when valid, else one line naming the field and the value.
std::string validate(const SolverSettings& settings);

const char* to_string(Method method);
const char* to_string(ModelKind model);
/// Parse "dopri5" | "rk4" | "analytic"; returns false on an unknown name.
bool parse_method(const std::string& text, Method& method);
/// Parse "nonlinear" | "linearized"; returns false on an unknown name.
bool parse_model(const std::string& text, ModelKind& model);

}  // namespace rocking_monitor::core
