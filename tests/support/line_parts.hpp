// Helpers shared by the line tests: a bar, a point mass and a joint of a
// case written in code, and a line's momentum.
#pragma once

#include <fmt/format.h>

#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/schemes/scheme.hpp"

namespace barimpact::testing {

inline BodyData bar(const std::string& name, double length, int elements, const std::string& velocity = "0") {
  BodyData b;
  b.name = name;
  b.length = length;
  b.elements = elements;
  b.velocity = velocity;
  return b;
}

inline BodyData mass(const std::string& name, double m, double v) {
  BodyData b;
  b.name = name;
  b.kind = BodyKind::mass;
  b.mass = m;
  b.velocity = fmt::format("{}", v);
  return b;
}

inline JointData joint(const std::string& lower, const std::string& upper, JointLaw law, double gap = 0.0) {
  JointData j;
  j.name = lower + "-" + upper;
  j.lower = lower;
  j.upper = upper;
  j.law.law = law;
  j.law.gap = gap;
  return j;
}

/// A joint of law `law` with its stiffness k and, as the law has one, its
/// dashpot l (spring, viscoelastic) or its restitution e (cushion).
inline JointData law_joint(const std::string& lower, const std::string& upper, JointLaw law, double k,
                           double second = 0.0) {
  JointData j = joint(lower, upper, law);
  j.law.stiffness = k;
  if (law == JointLaw::cushion)
    j.law.restitution = second;
  else
    j.law.viscosity = second;
  return j;
}

/// The momentum sum_j m_j v_j of a scheme's state, m the row sums of its mass.
inline double momentum(const std::vector<double>& m, const Scheme& s) {
  double p = 0.0;
  for (std::size_t j = 0; j < m.size(); ++j) p += m[j] * s.velocity_at(j);
  return p;
}

}  // namespace barimpact::testing
