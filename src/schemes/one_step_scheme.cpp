#include "barimpact/schemes/one_step_scheme.hpp"

#include <cmath>

namespace barimpact {

OneStepScheme::OneStepScheme(const Case& c, Tridiagonal kinetic_mass)
    : mesh_(c.bar.length, c.bar.elements),
      law_(c.obstacle),
      dt_(c.time.step),
      a_(c.bar.stiffness),
      b_(c.bar.viscosity),
      clamped_(c.bar.far_end == FarEnd::clamped),
      mass_(std::move(kinetic_mass)),
      stiffness_a_(mesh_.stiffness(c.bar.stiffness)),
      stiffness_b_(mesh_.stiffness(c.bar.viscosity)) {
  const std::size_t n = mesh_.nodes();
  for (auto* v : {&u_, &v_, &u_old_, &v_old_, &load_, &load_next_, &work_vector_}) v->assign(n, 0.0);
  body_force_ = std::make_unique<Expression>(c.load.body_force);
  load_zero_ = body_force_->is_zero();
  load_steady_ = !body_force_->depends_on_t();
  initial_displacement_ = std::make_unique<Expression>(c.initial.displacement);
  initial_velocity_ = std::make_unique<Expression>(c.initial.velocity);
}

void OneStepScheme::start_state() {
  mesh_.interpolate(*initial_displacement_, u_);
  mesh_.interpolate(*initial_velocity_, v_);
  if (!load_zero_) {
    mesh_.load(*body_force_, 0.0, load_);
    load_next_ = load_;
  }
  n_ = 0;
  work_ = dissipation_ = contact_ = 0.0;
  reaction_ = law_.reaction(u_[0], v_[0]);
}

void OneStepScheme::begin_step(bool keep_old) {
  if (keep_old) {
    u_old_ = u_;
    v_old_ = v_;
  }
  if (!load_zero_ && !load_steady_) mesh_.load(*body_force_, static_cast<double>(n_ + 1) * dt_, load_next_);
}

void OneStepScheme::end_step(double extra_dissipation) {
  const std::size_t n = mesh_.nodes();
  double dw = 0.0, dd = extra_dissipation;
  if (!load_zero_)
    for (std::size_t j = 0; j < n; ++j) dw += (u_[j] - u_old_[j]) * 0.5 * (load_[j] + load_next_[j]);
  if (stiffness_b_.diag[0] > 0.0) {
    for (std::size_t j = 0; j < n; ++j) work_vector_[j] = 0.5 * (v_[j] + v_old_[j]);
    dd += dt_ * mesh_.stiffness_form(b_, work_vector_, work_vector_);
  }
  work_ += dw;
  dissipation_ += dd;
  std::swap(load_, load_next_);
  if (!load_zero_ && load_steady_) load_next_ = load_;
  ++n_;
}

void OneStepScheme::displacement(std::span<double> out) const {
  std::copy(u_.begin(), u_.end(), out.begin());
}
void OneStepScheme::velocity(std::span<double> out) const {
  std::copy(v_.begin(), v_.end(), out.begin());
}

Energies OneStepScheme::energies() const {
  Energies e;
  e.kinetic = 0.5 * mass_.quadratic_form(v_);
  e.strain = 0.5 * mesh_.stiffness_form(a_, u_, u_);
  e.obstacle = law_.energy(u_[0]);
  e.work = work_;
  e.dissipation = dissipation_;
  e.contact = contact_;
  return e;
}

bool OneStepScheme::finite() const {
  const std::size_t last = mesh_.nodes() - 1;
  return std::isfinite(u_[0]) && std::isfinite(u_[last]) && std::isfinite(v_[0]) && std::isfinite(v_[last]) &&
         std::isfinite(work_) && std::isfinite(dissipation_);
}

}  // namespace barimpact
