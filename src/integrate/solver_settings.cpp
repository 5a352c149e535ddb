#include "rocking_monitor/integrate/solver_settings.hpp"

#include <cmath>
#include <sstream>

namespace rocking_monitor::core {

std::string validate(const SolverSettings& s) {
  std::ostringstream os;
  if (s.method == Method::Analytic && s.model != ModelKind::Linearized) {
    return "invalid solver: method 'analytic' is exact only for the linearized model "
           "(use --model linearized, or another method)";
  }
  if (!(std::isfinite(s.tol) && s.tol > 0.0 && s.tol <= 1e-2)) {
    os << "invalid solver: tol = " << s.tol << " (must lie in (0, 1e-2])";
    return os.str();
  }
  if (s.substeps < 1 || s.substeps > 100000) {
    os << "invalid solver: substeps = " << s.substeps << " (must lie in [1, 100000])";
    return os.str();
  }
  if (!(std::isfinite(s.rest_capture_ratio) && s.rest_capture_ratio >= 0.0 &&
        s.rest_capture_ratio < 1.0)) {
    os << "invalid solver: rest_capture_ratio = " << s.rest_capture_ratio << " (must lie in [0, 1))";
    return os.str();
  }
  if (s.max_events_per_sample < 1) {
    os << "invalid solver: max_events_per_sample = " << s.max_events_per_sample << " (must be >= 1)";
    return os.str();
  }
  return {};
}

const char* to_string(Method method) {
  switch (method) {
    case Method::Dopri5: return "dopri5";
    case Method::Rk4: return "rk4";
    case Method::Analytic: return "analytic";
  }
  return "unknown";
}

const char* to_string(ModelKind model) {
  return model == ModelKind::Linearized ? "linearized" : "nonlinear";
}

bool parse_method(const std::string& text, Method& method) {
  if (text == "dopri5") method = Method::Dopri5;
  else if (text == "rk4") method = Method::Rk4;
  else if (text == "analytic") method = Method::Analytic;
  else return false;
  return true;
}

bool parse_model(const std::string& text, ModelKind& model) {
  if (text == "nonlinear") model = ModelKind::Nonlinear;
  else if (text == "linearized") model = ModelKind::Linearized;
  else return false;
  return true;
}

}  // namespace rocking_monitor::core
