#include "rocking_monitor/motion/ground_motion.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rocking_monitor::core {

GroundMotion make_ground_motion(const Component& h, const Component* v, double scale,
                                std::string* notice) {
  if (!std::isfinite(scale)) throw std::invalid_argument("scale must be finite");
  if (h.accel.size() < 2) throw std::invalid_argument(h.file + ": fewer than 2 samples");
  if (!(h.dt > 0.0) || !std::isfinite(h.dt))
    throw std::invalid_argument(h.file + ": sample interval must be > 0");
  GroundMotion g;
  g.t0 = h.t0;
  g.dt = h.dt;
  g.description = h.file + (h.label.empty() ? "" : " [" + h.label + "]");
  g.horizontal.reserve(h.accel.size());
  for (double a : h.accel) g.horizontal.push_back(a * scale);
  if (v != nullptr) {
    if (std::abs(v->dt - h.dt) > 1e-6 * h.dt) {
      std::ostringstream os;
      os << v->file << ": vertical dt = " << v->dt << " s differs from the horizontal's " << h.dt
         << " s (" << h.file << ")";
      throw std::invalid_argument(os.str());
    }
    g.vertical.assign(h.accel.size(), 0.0);
    const std::size_t n = std::min(v->accel.size(), h.accel.size());
    for (std::size_t i = 0; i < n; ++i) g.vertical[i] = v->accel[i] * scale;
    g.description += " + vertical " + v->file + (v->label.empty() ? "" : " [" + v->label + "]");
    if (notice != nullptr && v->accel.size() != h.accel.size()) {
      std::ostringstream os;
      os << "vertical " << v->file << " has " << v->accel.size() << " samples, horizontal "
         << h.accel.size() << ": "
         << (v->accel.size() < h.accel.size() ? "padded with zeros after its end"
                                               : "samples beyond the horizontal's end not used");
      *notice = os.str();
    }
  }
  return g;
}

}  // namespace rocking_monitor::core
