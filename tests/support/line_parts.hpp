// Helpers shared by the line tests: a bar, a point mass and a joint of a
// case written in code.
#pragma once

#include <fmt/format.h>

#include <string>

#include "barimpact/case/case.hpp"

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

}  // namespace barimpact::testing
