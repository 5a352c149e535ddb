#pragma once

// Moved to rocking_monitor/physics/item_verdict.hpp: combine() is a pure rule over plane verdicts,
// and the study, which may not include monitoring/, needs it too. This header stays so that code
// written against the old path (rocking_sim's second plane, on its own branch) still builds; new
// code includes the physics header.
#include "rocking_monitor/physics/item_verdict.hpp"
