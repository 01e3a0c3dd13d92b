#include <cmath>
#include <limits>

#include "barimpact/case/line_builder.hpp"
#include "barimpact/exact/exact.hpp"
#include "barimpact/exact/lines.hpp"
#include "barimpact/model/expression.hpp"

namespace barimpact::exact {

namespace {

class TabulatedLine final : public Scheme {
 public:
  TabulatedLine(const Case& c, std::shared_ptr<const LineSolution> s)
      : s_(std::move(s)), line_(build_line(c)), dt_(c.time.step) {
    for (std::size_t b = 0; b < line_.bodies.size(); ++b)
      for (std::size_t j = line_.bodies[b].first; j <= line_.bodies[b].last; ++j) body_of_.push_back(b);
    body_of_.resize(line_.nodes());
    for (std::size_t b = line_.bodies.size(); b-- > 0;)  // a shared node belongs to the lower body
      for (std::size_t j = line_.bodies[b].first; j <= line_.bodies[b].last; ++j) body_of_[j] = b;
    if (line_.near.kind == EndKind::force) near_force_ = std::make_unique<Expression>(line_.near.value);
    near_link_ = !line_.links.empty() && line_.links.front().name == "near_end";
    for (std::size_t b = 0; b < line_.bodies.size(); ++b)
      if (line_.bodies[b].is_mass) masses_.push_back({b, c.bodies[b].mass});
  }
  void start() override { n_ = 0; }
  void advance() override { ++n_; }
  long long step() const override { return n_; }
  double time() const override { return static_cast<double>(n_) * dt_; }
  std::size_t nodes() const override { return line_.nodes(); }
  double end_displacement() const override { return displacement_at(0); }
  double end_velocity() const override { return velocity_at(0); }
  double reaction() const override {
    if (near_link_) return link_force(0);
    if (near_force_) return (*near_force_)(0.0, time());
    if (line_.near.kind == EndKind::free) return 0.0;
    return -s_->fields(0, line_.x[0], time()).axial_force;  // the support's push on a held end
  }
  void displacement(std::span<double> out) const override {
    for (std::size_t j = 0; j < out.size(); ++j) out[j] = displacement_at(j);
  }
  void velocity(std::span<double> out) const override {
    for (std::size_t j = 0; j < out.size(); ++j) out[j] = velocity_at(j);
  }
  double displacement_at(std::size_t j) const override { return s_->fields(body_of_[j], line_.x[j], time()).u; }
  double velocity_at(std::size_t j) const override { return s_->fields(body_of_[j], line_.x[j], time()).v; }
  double link_force(std::size_t i) const override { return s_->link_force(i, time()); }
  double link_opening(std::size_t i) const override { return s_->link_opening(i, time()); }
  double plastic_strain(std::size_t bond) const override {  // at the element's centre
    const std::size_t b = line_.bonds[bond].body;
    return s_->plastic_strain(b, 0.5 * (line_.x[bond] + line_.x[bond + 1]), time());
  }
  double plastic_work(std::size_t body) const override {
    const auto e = s_->energies(time());
    return e && s_->bodies() == 1 && body == 0 ? e->plastic : 0.0;
  }
  Energies energies() const override;
  bool finite() const override { return true; }

 private:
  std::shared_ptr<const LineSolution> s_;
  Line line_;
  double dt_;
  long long n_ = 0;
  std::vector<std::size_t> body_of_;
  std::unique_ptr<Expression> near_force_;
  bool near_link_ = false;
  std::vector<std::pair<std::size_t, double>> masses_;  // body, mass
};

Energies TabulatedLine::energies() const {
  const double t = time();
  if (auto closed = s_->energies(t)) return *closed;
  Energies e;
  constexpr int cells = 20000;
  for (std::size_t b = 0; b < line_.bodies.size(); ++b) {
    const BodyRange& r = line_.bodies[b];
    if (r.is_mass) continue;
    const Bond& bond = line_.bonds[r.first];
    const double rho_a = bond.mass / bond.h, near = s_->body_near(b), far = s_->body_far(b);
    const double h = (far - near) / cells;
    for (int i = 0; i < cells; ++i) {
      const LineFields f = s_->fields(b, near + (i + 0.5) * h, t);
      e.kinetic += 0.5 * rho_a * f.v * f.v * h;
      e.strain += 0.5 * bond.axial * f.strain * f.strain * h;
    }
  }
  for (const auto& [b, m] : masses_) {
    const double v = s_->fields(b, s_->body_near(b), t).v;
    e.kinetic += 0.5 * m * v * v;
  }
  e.work = s_->work(t);
  return e;
}

// A line solution at x = 0, through the single bar's interface.
class LineEnd final : public Solution {
 public:
  LineEnd(const Case& c, std::unique_ptr<LineSolution> s) : s_(std::move(s)), line_(build_line(c)) {
    near_link_ = !line_.links.empty() && line_.links.front().name == "near_end";
    if (line_.near.kind == EndKind::force) force_ = std::make_unique<Expression>(line_.near.value);
  }
  double U(double t) const override { return s_->fields(0, line_.x[0], t).u; }
  double V(double t) const override { return s_->fields(0, line_.x[0], t).v; }
  double R(double t) const override {
    if (near_link_) return s_->link_force(0, t);
    if (force_) return (*force_)(0.0, t);
    if (line_.near.kind == EndKind::free) return 0.0;
    return -s_->fields(0, line_.x[0], t).axial_force;
  }
  double valid_until() const override { return s_->valid_until(); }
  double energy() const override { return s_->energy(0.0); }
  const char* name() const override { return s_->name(); }

 private:
  std::unique_ptr<LineSolution> s_;
  Line line_;
  bool near_link_ = false;
  std::unique_ptr<Expression> force_;
};

}  // namespace

std::unique_ptr<Solution> line_end(const Case& c) {
  auto s = for_line_case(c);
  if (!s) return nullptr;
  return std::make_unique<LineEnd>(c, std::move(s));
}

std::unique_ptr<Scheme> as_line_scheme(const Case& c, std::shared_ptr<const LineSolution> solution) {
  return std::make_unique<TabulatedLine>(c, std::move(solution));
}

}  // namespace barimpact::exact
