// A pile-driving blow's results (summary.json's `blow`), watched step by
// step on a line with Smith's soil or a [blow] section: the set, the blow
// counts, the pile's stress extremes, the energy through the analyser's
// gauge (ENTHRU), the hammer's energy at impact and whether the pile came
// to rest. Conventions are the pile-driving analyser's (ASTM D4945): forces
// tension-positive, velocities along +x, so that energy flowing down the
// pile (towards the toe at x = 0) is positive.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "barimpact/case/case.hpp"
#include "barimpact/model/line.hpp"
#include "barimpact/run/observer.hpp"

namespace barimpact {

/// A stress extreme of the pile: its size (>= 0), where along the line and when.
struct StressPeak {
  double value = 0.0;
  std::string body;
  double x = 0.0, t = 0.0;
};

struct BlowSummary {
  std::string pile, ram, gauge;  ///< gauge empty: no ENTHRU
  /// The toe spring's plastic slip, into the soil (its largest penetration
  /// less its quake for a single loading); 0: the hammer did not move it.
  double set = 0.0;
  double toe_penetration = 0.0;  ///< the toe's largest penetration
  StressPeak max_compression, max_tension;
  double enthru = std::numeric_limits<double>::quiet_NaN();  ///< max over t of int N v dt at the gauge
  double impact_time = 0.0, impact_velocity = 0.0;
  double hammer_energy = 0.0;  ///< the ram's kinetic energy at impact
  bool impact = false;         ///< the ram struck the pile (false: no set, no blow counts, no transfer)
  /// The pile came to rest: every node below 1% of the impact velocity from
  /// rest_time on, after the soil's last slip and once the wave has reached
  /// the toe and moved it, and stayed so to the end of the run or, with
  /// [blow] rest_window, for that long (a blow cut short before then, or
  /// still ringing at its end, is not finished).
  /// Under gravity a ram that rebounds falls back and strikes again. Once
  /// the blow is over (the pile at rest, or the soil not slipping for ten
  /// round trips, 20 L/c) that is the next strike, which a hammer in
  /// service (caught and lifted) would not give: the blow ends there
  /// (restrike_time), finished, every number the strikes' before it. One
  /// landing before then, the pile still moving, is part of the blow (strikes).
  bool finished = false;
  double rest_time = std::numeric_limits<double>::quiet_NaN();
  double restrike_time = std::numeric_limits<double>::quiet_NaN();   ///< NaN: none in the run
  double last_slip_time = std::numeric_limits<double>::quiet_NaN();  ///< the soil's last slip; NaN: none
  int strikes = 1;  ///< the ram's strikes in the blow: more than 1 when it fell back before the blow was over
  double rest_window = std::numeric_limits<double>::quiet_NaN();  ///< [blow] rest_window, NaN: to the run's end
  /// The largest tension (>= 0) in an element before the stress wave from
  /// the head can have reached it (two element transits of margin): what a
  /// scheme's oscillation ahead of a steep front puts there, 0 for a scheme
  /// that keeps the front sharp. Its place and time in precursor.
  StressPeak precursor;
  double impedance = std::numeric_limits<double>::quiet_NaN();  ///< Z = A sqrt(E rho) at the gauge
  /// The stress envelopes along the pile: per element its middle x and its
  /// largest compression and tension (>= 0) over every step.
  struct Envelope {
    std::vector<double> x, compression, tension;
  } envelope;
  /// A diesel hammer (the link below the ram a diesel cylinder, contact_law.hpp):
  /// the height above impact the ram rises to, L_c + v^2 / 2g from where it
  /// passes the ports moving up (NaN if it has not by the run's end), and the
  /// gas's compression and expansion works W_c, W_e between the ports and
  /// impact (closed form, DieselGas); false and NaN for other hammers.
  bool diesel = false;
  double next_stroke = std::numeric_limits<double>::quiet_NaN();
  double compression_work = std::numeric_limits<double>::quiet_NaN();
  double expansion_work = std::numeric_limits<double>::quiet_NaN();
  /// A hammer's blows at one soil (a diesel hammer's stroke iteration): this
  /// blow's stroke, the first blow's set and how many blows ran; NaN, NaN, 1
  /// for a single blow.
  double stroke = std::numeric_limits<double>::quiet_NaN();
  double first_set = std::numeric_limits<double>::quiet_NaN();
  int blows_run = 1;
  /// A residual stress analysis's ([drive] blows > 1): the toe's force
  /// locked in before this blow (compression > 0); NaN for one blow.
  double residual_toe_force = std::numeric_limits<double>::quiet_NaN();

  /// Blows per metre: infinite at refusal (set 0 after a finished blow), NaN
  /// when the ram never struck.
  [[nodiscard]] double blows_per_m() const {
    if (!impact) return std::numeric_limits<double>::quiet_NaN();
    return set > 0.0 ? 1.0 / set : std::numeric_limits<double>::infinity();
  }
  [[nodiscard]] double blows_per_250mm() const { return 0.25 * blows_per_m(); }
  /// ENTHRU over the hammer's energy; NaN when the ram brought none.
  [[nodiscard]] double transfer_ratio() const {
    return hammer_energy > 0.0 ? enthru / hammer_energy : std::numeric_limits<double>::quiet_NaN();
  }
};

/// Whether a case's run reports a blow: Smith's soil on its line, or [blow].
[[nodiscard]] bool reports_blow(const Case& c, const Line& line);

class BlowMonitor final : public Observer {
 public:
  BlowMonitor(const Case& c, const Line& line);
  void begin(const Scheme& scheme, long long steps) override;
  bool observe(const Scheme& scheme) override;
  [[nodiscard]] BlowSummary summary() const;

 private:
  void watch_stresses(const Scheme& s);
  void watch_impact(const Scheme& s);
  void watch_rest(const Scheme& s);
  void watch_rebound(const Scheme& s);
  void watch_restrike(const Scheme& s);
  [[nodiscard]] bool settled(double t) const;

  const Line& line_;
  BlowSummary start_;  // what a run starts from: the names, the envelopes' x, nothing seen yet
  BlowSummary out_;
  std::size_t first_ = 0, last_ = 0;          // the pile's nodes
  std::size_t ram_first_ = 0, ram_last_ = 0;  // the ram's
  std::size_t ram_link_ = Link::ground;       // the link below the ram (none: in contact from t = 0)
  bool diesel_ = false;                       // ram_link_ is a diesel cylinder
  std::size_t toe_link_ = Link::ground;       // the near end's Smith link
  double toe_quake_ = 0.0;
  std::optional<GaugePoint> gauge_;
  std::vector<double> mass_;  // lumped, per node
  double dt_ = 0.0, power_ = 0.0, energy_ = 0.0;
  double ram_energy_ = 0.0, ram_velocity_ = 0.0;  // at the last step observed
  bool impacted_ = false;
  double slip_ = 0.0;                      // the soil's slip work at the last step
  double transit_ = 0.0;                   // the wave's time from the pile's head to its toe
  std::vector<double> arrival_;            // per element: the wave's time from the head, less two element transits
  bool at_rest_ = false;                   // below the rule since out_.rest_time, after the last slip
  bool rested_ = false;                    // at rest for the whole rest window: finished, whatever follows
  std::vector<std::size_t> hammer_links_;  // the joints from the pile's head up to the ram's
  std::vector<char> open_at_apex_;         // per hammer link: open when the rising ram turned
  bool ram_rising_ = false;                // the ram moving up, its link open, after impact
  bool apex_ = false;                      // the ram turned in free flight: it falls back
  bool restruck_ = false;                  // a hammer link closed again after the apex: the blow is over
};

}  // namespace barimpact
