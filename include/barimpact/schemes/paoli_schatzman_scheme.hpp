// `paoli-schatzman`: central differences with the consistent mass M_h and
// the rigid obstacle imposed on the restitution-weighted position
// (u_0^{n+1} + e u_0^{n-1}) / (1 + e) >= -g (Paoli & Schatzman 2002): when
// the free prediction violates it, u^{n+1} is moved along M_h^{-1} e_0 (the
// projection in the kinetic metric) until the constraint holds with
// equality. e = 0 imposes u_0^{n+1} >= -g; e = 1 the mean of u^{n+1} and
// u^{n-1}. Explicit in K (stable below h / (c sqrt 3)), one tridiagonal
// solve with M_h per step, factored once.
#pragma once

#include "barimpact/schemes/three_level_scheme.hpp"

namespace barimpact {

class PaoliSchatzmanScheme final : public ThreeLevelScheme {
 public:
  explicit PaoliSchatzmanScheme(const Case& c);

 protected:
  void apply_inverse_mass(std::span<double> r) const override { mass_factor_.solve(r); }
  [[nodiscard]] const FactoredTridiagonal* mass_factor() const override { return &mass_factor_; }
  double enforce_contact(const double* prev, const double* cur, double* next) override;
  [[nodiscard]] double end_impulse(double prev0, double next0) const override;

 private:
  FactoredTridiagonal mass_factor_;
  std::vector<double> response_;  // M_h^{-1} e_0
  double restitution_;
};

}  // namespace barimpact
