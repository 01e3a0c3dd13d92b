#include "barimpact/obstacle.hpp"

namespace barimpact {

ObstacleLaw::ObstacleLaw(const ObstacleData& data)
    : kind_(data.kind), k_(data.kind == ObstacleKind::none ? 0.0 : data.stiffness), gap_(data.gap) {}

}  // namespace barimpact
