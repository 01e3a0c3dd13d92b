// Reading [hammer], [drive] and [[layer]] into a case (case.cpp calls these
// while it reads the line). Internal to src/case/.
#pragma once

#include "barimpact/case/case.hpp"
#include "reader.hpp"

namespace barimpact::detail {

/// [hammer]: a model from a table adds the helmet, the capblock and the ram
/// above the pile head (and the pile cushion, if any); by hand it names the
/// ram. Either way the ram starts at impact, moving down at
/// sqrt(2 g stroke efficiency). Call before [blow] and the gauges are checked.
void read_hammer(Reader& r, Case& c, BodyIndex& index);

/// [drive] and [[layer]]: reads and checks them, then gives the pile the
/// profile's shaft and toe at the depth a run analyses (drive.depth, else
/// the deepest of drive.depths).
void read_drive(Reader& r, Case& c, const BodyIndex& index);

}  // namespace barimpact::detail
