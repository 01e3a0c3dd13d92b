// Signal matching through an installed barimpact: the record named on the
// command line (examples/pda/steel-pipe.toml) matched on one thread, its
// fitting module found where the install put it (BARIMPACT_MODULE_DIR, for
// an install away from its configured prefix). Exit 0 when the fit ran and
// matches its record, 1 when it does not, 2 on an error (its one line).
#include <barimpact/study/match.hpp>

#include <cmath>
#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: match RECORD.toml\n");
    return 2;
  }
  try {
    const auto m = barimpact::match_pile(barimpact::PileRecord::from_file(argv[1]), 1);
    std::printf("match: capacity %.4g N, quality %.3g\n", m.soil.capacity(), m.quality);
    // The example's record is matched within a few percent of its largest force.
    return std::isfinite(m.quality) && m.quality < 0.1 && m.soil.capacity() > 0.0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "match: %s\n", e.what());
    return 2;
  }
}
