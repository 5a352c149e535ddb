// SEED channel codes (SEED manual, appendix A): band, instrument and orientation letters. Only
// accelerometer channels become ground-acceleration components; anything else is refused by name,
// because a velocity channel divided by an acceleration gain would be silently wrong.
#include "record_reader_internal.hpp"

namespace rocking_monitor::core::record_io {

SeedChannel classify_seed_channel(const std::string& channel, const std::string& where) {
  const std::string c = upper(trim(channel));
  if (c.size() != 3) fail(where, 0, "channel code " + in_quotes(channel) + " is not a 3-character SEED code");
  // N: accelerometer. L and G: older strong-motion networks (e.g. SCSN HL?, HG?) used them for
  // accelerometers; the gain given must then be counts per m/s^2 like any other.
  const char instrument = c[1];
  if (instrument != 'N' && instrument != 'L' && instrument != 'G') {
    fail(where, 0,
         "channel " + c + " is not an accelerometer (instrument code " + std::string(1, instrument) +
             "; expected N, or L/G as some strong-motion networks use): select the accelerometer channels");
  }
  SeedChannel out;
  switch (c[2]) {
    case 'Z':
    case '3':
      out.vertical = true;
      break;
    case 'N':
      out.geographic = true;
      out.horizontal_index = 0;
      break;
    case 'E':
      out.geographic = true;
      out.horizontal_index = 1;
      break;
    case '1':
      out.horizontal_index = 0;
      break;
    case '2':
      out.horizontal_index = 1;
      break;
    default:
      fail(where, 0,
           "channel " + c + ": orientation code " + std::string(1, c[2]) +
               " is not one of Z, N, E, 1, 2, 3 (the reader maps only these to components)");
  }
  return out;
}

}  // namespace rocking_monitor::core::record_io
