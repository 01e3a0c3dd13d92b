// The case: every datum of one problem (the line of bodies, its joints, end
// laws and gauges, or today's single bar and obstacle; load, time stepping,
// output), read from a TOML case file and validated.
//
// This header owns the case-file contract: section and key names, their
// defaults, and the rules each value obeys. It does not own the numerics:
// expressions are kept as text here and compiled by `Expression`.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "barimpact/case/drive.hpp"
#include "barimpact/model/contact_law.hpp"
#include "barimpact/model/input_error.hpp"
#include "barimpact/model/material.hpp"

namespace barimpact {

enum class FarEnd { free, clamped };

/// The paper's obstacle at x = 0 (the [obstacle] table), seen as its bar's near end.
enum class ObstacleKind { none, elastic, viscoelastic, rigid };
struct ObstacleData {
  ObstacleKind kind = ObstacleKind::elastic;
  double stiffness = 100.0;  ///< k, eq. (2.8)
  double gap = 0.0;          ///< g: the face is at u = -g
  double viscosity = 0.0;    ///< l, viscoelastic: R = max(0, k d + l dd/dt) while d > 0
};

[[nodiscard]] std::string_view to_string(ObstacleKind kind);

struct BarData {
  double length = 1.0;            ///< L
  double density = 1.0;           ///< rho, mass per unit length
  double stiffness = 1.0;         ///< a (Section 2)
  double viscosity = 0.0;         ///< b, Kelvin-Voigt
  int elements = 100;             ///< M, uniform P1 elements
  FarEnd far_end = FarEnd::free;  ///< x = L: free (sigma = 0) or clamped (u = 0)
  MaterialData material;          ///< elastic, or elastic-plastic (stresses a u_x: area 1)
};

struct LoadData {
  std::string body_force = "0";  ///< f(x, t), force per unit length on every bar
  double gravity = 0.0;          ///< g, acceleration towards -x on every body
};

/// A body of the line ([[body]]), listed from the near end (x = 0) outward.
enum class BodyKind { bar, mass };

/// How a shaft's static capacity is spread along its embedded length.
enum class ShaftDistribution {
  uniform,    ///< the same per unit length
  triangular  ///< zero at the ground surface, largest at the toe (the body's near end)
};

/// Smith's side springs on a bar ([body.shaft]): total static capacity R_u
/// spread over the embedded nodes (by the element lengths, consistently with
/// the distribution), each node elastic-perfectly-plastic with quake q and
/// damping J in both directions.
struct ShaftData {
  /// R_u the total static shaft capacity (N), q (m, default Smith's 0.1 in),
  /// J_side (s/m, default Smith's 0.05 s/ft) and the damping law.
  SoilSpring soil{0.0, 0.00254, 0.164, DampingLaw::smith};
  double embedded = -1.0;  ///< length in the soil from the body's near end (< 0: all of it)
  ShaftDistribution distribution = ShaftDistribution::uniform;
  /// The shaft as pieces, ascending (empty: soil, embedded and distribution
  /// say it; else soil.ultimate is their sum and embedded their reach).
  std::vector<ShaftPiece> profile;
};

struct BodyData {
  std::string name;
  BodyKind kind = BodyKind::bar;
  double length = 1.0;             ///< bar
  int elements = 100;              ///< bar: uniform P1 elements on this body
  double area = 1.0;               ///< A
  double modulus = 1.0;            ///< E (the paper's a = E A)
  double density = 1.0;            ///< rho, per unit volume (rho A per unit length)
  double viscosity = 0.0;          ///< Kelvin-Voigt eta (the paper's b = eta A)
  double mass = 1.0;               ///< mass
  std::string displacement = "0";  ///< u0(x) (bar), a number (mass)
  std::string velocity = "0";      ///< v0(x) (bar), a number (mass)
  MaterialData material;           ///< bar: elastic, or elastic-plastic (material.hpp)
  std::optional<ShaftData> shaft;  ///< bar: Smith's side springs along it, if any
};

/// A joint's or an end's law. At an end, the obstacle is a joint with the ground.
enum class JointLaw {
  free,
  clamped,
  welded,
  spring,
  elastic,
  viscoelastic,
  rigid,
  cushion,
  force,
  velocity,
  smith,
  diesel
};

struct LawData {
  JointLaw law = JointLaw::free;
  double stiffness = 100.0;  ///< k: spring, elastic, viscoelastic, cushion (loading)
  double viscosity = 0.0;    ///< l: spring's dashpot, viscoelastic
  double restitution = 1.0;  ///< e: cushion in (0, 1]; rigid in [0, 1] (then replaces time.restitution)
  bool restitution_given = false;
  double gap = 0.0;         ///< unilateral laws: initial clearance >= 0
  std::string value = "0";  ///< force or velocity history along +x, an expression in t
  /// smith (near end only): R_u (toe capacity, N), q (m, default Smith's 0.1 in),
  /// J_toe (s/m, default Smith's 0.15 s/ft) and the damping law.
  SoilSpring soil{0.0, 0.00254, 0.492, DampingLaw::smith};
  /// diesel (joints only): the cylinder; its impact cushion is `stiffness`
  /// and `restitution` (keys impact_stiffness, impact_restitution), the ram's
  /// initial height above impact `gap`.
  DieselGas gas{};
};

struct JointData {
  std::string name;   ///< default "<lower>-<upper>"
  std::string lower;  ///< the body nearer x = 0
  std::string upper;
  LawData law;
  std::string stem;  ///< its columns' and link's name (empty: "joint.<name>"; a diesel hammer's gas: "hammer.gas")

  [[nodiscard]] std::string column_stem() const { return stem.empty() ? "joint." + name : stem; }
};

/// [blow]: what a pile-driving blow's results (summary.json's `blow`) read.
struct BlowData {
  std::string gauge;  ///< the gauge ENTHRU is measured at (empty: the pile's top gauge, if any)
  std::string ram;    ///< the ram (empty: the outermost body)
  std::string pile;   ///< the pile (empty: the bar nearest x = 0)
  /// s: the pile is at rest once below the rule this long (none: until the run's end)
  std::optional<double> rest_window;
};

struct GaugeData {
  std::string name;
  std::string body;
  double at = 0.0;  ///< distance from the body's near end
};

struct InitialData {
  std::string displacement = "0";  ///< u0(x)
  std::string velocity = "0";      ///< v0(x)
};

struct TimeData {
  double end = 1.0;
  double step = 0.01;      ///< dt
  bool step_auto = false;  ///< step = "auto": an explicit scheme's stable step for the line
  bool step_given = true;  ///< step set to a number (in code, or by the file or --set): final but for a refusal
  std::string scheme = "paper";
  double alpha = 0.25;       ///< alpha of (6.3)
  double lambda = 0.0;       ///< lambda_shift: z = exp(-lambda t) u, (6.1)
  double beta = 0.25;        ///< Newmark beta
  double gamma = 0.5;        ///< Newmark gamma
  double theta = 0.5;        ///< Moreau-Jean theta
  double restitution = 0.0;  ///< e: Paoli-Schatzman, Moreau-Jean
  /// time.partitions: the chunks an implicit scheme's partitioned solve
  /// takes on a large line (model/partitioned_tridiagonal.hpp); 1 the
  /// sequential solve, 0 ("auto") chosen by the scheme from the line's size.
  int partitions = 0;
};

/// The names time.scheme takes, in the order the table of schemes lists them
/// (schemes/registry.hpp, which holds what each scheme is and runs).
inline constexpr std::array<std::string_view, 7> scheme_names{
    "paper",           "newmark",     "central-difference", "mass-redistribution",
    "paoli-schatzman", "moreau-jean", "characteristic"};

/// How a run directory holds the history and the fields: history.csv and
/// fields.csv, or one results.h5 (HDF5).
enum class OutputFormat { csv, hdf5 };

struct OutputData {
  int every = 1;                  ///< history row every N steps
  std::vector<double> fields_at;  ///< times of field snapshots
  OutputFormat format = OutputFormat::csv;
  int compression = 1;  ///< gzip level 0-9 of results.h5's fields (0: none); CSV files are not compressed
};

/// A line of one uniform elastic bar in the paper's terms (Section 2:
/// a = E A, rho A, b = eta A; the obstacle at x = 0): what the paper's
/// one-bar kernel and the single bar's exact solutions read. It is a view,
/// computed from the line, which is the case's only spelling in memory.
struct OneBar {
  BarData bar;
  InitialData initial;
  ObstacleData obstacle;
};

/// A validated case. Construct with `Case::from_file` or `Case::from_string`;
/// every rule of the case-file contract holds for the result.
struct Case {
  // The line: bodies from x = 0 outward, the joints between them (consecutive
  // bodies without one are welded), the two ends, the gauges.
  std::vector<BodyData> bodies;
  std::vector<JointData> joints;
  LawData near_end;
  LawData far_end;
  std::vector<GaugeData> gauges;
  BlowData blow;
  std::optional<DriveData> drive;    ///< [drive] and [[layer]]: the pile's soil at drive's depth
  std::optional<HammerData> hammer;  ///< [hammer]: the ram's start (and the bodies a model adds)
  LoadData load;
  TimeData time;
  OutputData output;
  /// [units] system: "SI" (figures label N, m, s, Pa, J), "US" (the numbers still SI; the console and
  /// figures show kip, ft, in, ksi, kip-ft) or "none" (unit-free numbers).
  std::string units = "none";
  /// The case file it was read from (from_file), empty for text: an input
  /// its results never overwrite.
  std::filesystem::path source;
  /// Where the keys that fitting the step to the scheme may refuse were set
  /// ("time.step", "time.end", "time.scheme", "time.beta",
  /// "output.fields_at", "output.every"): a file and line, or a --set.
  std::map<std::string, std::string, std::less<>> sites;

  /// Throws InputError "<where key was set>: <key> <rule>", as reading does
  /// (for a case made in code, "<key> <rule>").
  [[noreturn]] void refuse(std::string_view key, std::string_view rule) const;

  /// The line as the paper's single bar, when it is one: one uniform
  /// elastic bar, no joints, gravity or shaft, its near end free or an
  /// elastic, viscoelastic or rigid obstacle, its far end free or clamped.
  [[nodiscard]] std::optional<OneBar> one_bar() const;
  /// Smith's soil at the toe (near_end.law = "smith") or along a shaft.
  [[nodiscard]] bool smith_soil() const;
  /// A pile case's pile (Smith's soil, or a [blow]): [blow] pile, else the
  /// bar nearest x = 0; nothing for another case.
  [[nodiscard]] const BodyData* pile() const;
  /// The bars' total length and number of elements (every bar of the line).
  [[nodiscard]] double bar_length() const;
  [[nodiscard]] long long bar_elements() const;

  /// One `section.key=value` override; the value is read as a TOML value,
  /// a bare word as a string.
  struct Override {
    std::string text;
  };

  /// Reads, overrides and validates. Throws InputError.
  static Case from_file(const std::filesystem::path& path, const std::vector<Override>& overrides = {});
  /// Same from TOML text; `origin` names it in error messages, followed by
  /// the line when `cite_lines` (not for text made from a dict).
  static Case from_string(std::string_view toml, const std::vector<Override>& overrides = {},
                          std::string_view origin = "case", bool cite_lines = true);

  /// The rules that follow from a final time step: at most 1e10 steps,
  /// time.end >= time.step, output.fields_at within the run and at most 1e8
  /// history rows. Reading checks them when time.step is a number; when it
  /// is "auto" or left to the scheme, fitting the step does (fit_scheme).
  /// Throws InputError naming the key.
  void check_steps() const;

  /// The number of steps N: t_N = N dt is the first step time >= end
  /// (up to a relative 1e-9, so that end = 4, step = 0.01 gives 400).
  [[nodiscard]] long long step_count() const;

  /// The resolved case as TOML in the line's spelling ([[body]], [near_end],
  /// ...), with only the keys each law uses, every default filled in:
  /// running it reproduces this case exactly.
  [[nodiscard]] std::string to_toml() const;
};

/// Each body of a line by its name: its index in `bodies`, or the number of
/// bodies for a name none has. One hash look-up a name, so that a line of
/// 10^5 bodies is read and built in O(n log n), not O(n^2).
class BodyIndex {
 public:
  explicit BodyIndex(const std::vector<BodyData>& bodies);
  /// Adds the next body; false (and nothing added) when its name is taken.
  bool add(const std::string& name);
  [[nodiscard]] std::size_t operator()(const std::string& name) const;

 private:
  std::unordered_map<std::string, std::size_t> index_;
  std::size_t size_ = 0;
};

/// Starts the ram of the case's [hammer] for a blow of `stroke` (m): at
/// impact moving down at sqrt(2 g stroke efficiency), or a diesel hammer's
/// at the exhaust ports moving down at sqrt(2 g (stroke - compression_length)),
/// g the case's gravity or 9.81.
void start_ram(Case& c, double stroke);

/// Throws InputError naming `path` (`what`: "case file") when it is a named
/// pipe (FIFO) or a socket, without opening it: the open would block until a
/// writer came. A shell's pipe (`<(...)`, /dev/fd/N) has its writer: fine.
void refuse_blocking_input(const std::filesystem::path& path, std::string_view what);

/// The whole of an input file (`what`: "case file", "sweep file"); empty is
/// fine. Throws InputError when it cannot be read, exceeds 64 MiB or is a
/// named pipe (refuse_blocking_input).
[[nodiscard]] std::string read_input_file(const std::filesystem::path& path, std::string_view what);

/// A finite double as a TOML float that reads back to the same double (fmt's shortest form).
[[nodiscard]] std::string toml_float(double v);

[[nodiscard]] std::string_view to_string(FarEnd end);
[[nodiscard]] std::string_view to_string(OutputFormat format);
[[nodiscard]] std::string_view to_string(BodyKind kind);
[[nodiscard]] std::string_view to_string(JointLaw law);

}  // namespace barimpact
