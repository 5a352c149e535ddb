#pragma once
// Private to src/model/contact_*.cpp (ContactModel's state machine, phase equations and
// transitions): what more than one of those files uses and the public header does not show.

namespace rocking_monitor::core {

// Which REST exit conditions fired (find_rest_exit -> leave_rest), as bits.
inline constexpr unsigned kFiredFlight = 1u, kFiredSlide = 2u, kFiredUplift = 4u;

}  // namespace rocking_monitor::core
