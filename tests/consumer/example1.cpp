// The paper's Example 1 through an installed barimpact: a bar of unit
// length, density and stiffness moving at v0 = -1 onto a penalty obstacle
// (k = 100), 100 elements, dt = 0.01, the alpha-scheme at alpha = 1/4.
// The rigid obstacle's exact answer: contact for 2L/c = 2, rebound at +1;
// the penalty's compliance lengthens the contact a little (about 2.03).
// Exit 0 when the run agrees, 1 when it does not.
#include <barimpact/case/case.hpp>
#include <barimpact/run/simulate.hpp>

#include <cmath>
#include <cstdio>

int main() {
  const auto c = barimpact::Case::from_string(R"(
[bar]
length = 1.0
density = 1.0
stiffness = 1.0
elements = 100
[initial]
velocity = "-1"
[obstacle]
kind = "elastic"
stiffness = 100.0
[time]
end = 4.0
step = 0.01
scheme = "paper"
)",
                                              {}, "example1");
  const barimpact::RunResult r = barimpact::run(c);
  const auto& s = r.summary;
  if (!s.complete || s.contacts.size() != 1) {
    std::printf("example 1: %zu contact episodes, complete %d\n", s.contacts.size(), s.complete ? 1 : 0);
    return 1;
  }
  const auto& contact = s.contacts.front();
  std::printf("example 1: contact t = %.5g .. %.5g, rebound velocity %+.4g, energy error %.3g\n", contact.start,
              contact.end, contact.rebound_velocity, s.energy_error_max);
  // The penalty's contact ends within 2% of the rigid 2L/c = 2, and the bar
  // leaves at the rigid obstacle's +1 within 1% (the paper's Figure 3).
  const bool agrees = std::abs(contact.end - 2.0) < 0.04 && std::abs(contact.rebound_velocity - 1.0) < 0.01;
  return agrees ? 0 : 1;
}
