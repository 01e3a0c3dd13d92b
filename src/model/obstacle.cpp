#include "barimpact/model/obstacle.hpp"

namespace barimpact {

namespace {
bool penalty(ObstacleKind k) {
  return k == ObstacleKind::elastic || k == ObstacleKind::viscoelastic;
}
}  // namespace

ObstacleLaw::ObstacleLaw(const ObstacleData& data)
    : kind_(data.kind),
      k_(penalty(data.kind) ? data.stiffness : 0.0),
      l_(data.kind == ObstacleKind::viscoelastic ? data.viscosity : 0.0),
      gap_(data.gap) {}

std::string_view to_string(ObstacleKind kind) {
  switch (kind) {
    case ObstacleKind::none:
      return "none";
    case ObstacleKind::elastic:
      return "elastic";
    case ObstacleKind::viscoelastic:
      return "viscoelastic";
    case ObstacleKind::rigid:
      return "rigid";
  }
  return "?";
}

}  // namespace barimpact
