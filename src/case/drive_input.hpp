// Reading [hammer], [drive] and [[layer]] into a case (case.cpp calls these
// while it reads the line). Internal to src/case/.
#pragma once

#include "barimpact/case/case.hpp"
#include "reader.hpp"

namespace barimpact::detail {

/// [hammer]'s own bodies, added above the case's before its joints are
/// read: a model's helmet (and anvil) and ram, a diesel hammer's anvil and ram.
void add_hammer_bodies(Reader& r, Case& c, BodyIndex& index);

/// [hammer]: a model from a table adds the helmet, the capblock and the ram
/// above the pile head (and the pile cushion, if any); by hand it names the
/// ram. Either way the ram starts at impact, moving down at
/// sqrt(2 g stroke efficiency). Call after the joints and [load], before [blow].
void read_hammer(Reader& r, Case& c, BodyIndex& index);

/// [drive] and [[layer]]: reads and checks them, then gives the pile the
/// profile's shaft and toe at the depth a run analyses (drive.depth, else
/// the deepest of drive.depths).
void read_drive(Reader& r, Case& c, const BodyIndex& index);

}  // namespace barimpact::detail
