// From the case's bodies, joints, ends and gauges to the line the schemes
// step (model/line.hpp): bodies become node ranges (a mass is one node), a
// welded joint shares its node, a spring joint is a bond, a unilateral
// joint or end law is a link.
#pragma once

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"

namespace barimpact {

/// The line of `c` (validated). A single-bar case gives one uniform bar.
[[nodiscard]] Line build_line(const Case& c);

/// The restitution a rigid link uses: its own if given, else time.restitution.
[[nodiscard]] double rigid_restitution(const Case& c, const LawData& law);

}  // namespace barimpact
