#pragma once
// The figures `barimpact plot` may draw of a run (python/barimpact/plot.py
// draws them; a line adds joint_forces, gauges and masses, a yielding bar
// the plastic ones, Smith's soil the blows). Named once: the command and
// the Python module list them in the figures' directory marker before
// drawing, so that a plot stopped half-way leaves files barimpact owns.
#include <array>
#include <string_view>

namespace barimpact {

inline constexpr std::array<std::string_view, 14> run_figure_names{
    "displacement", "reaction", "energy",      "stress_map",        "snapshots", "impacts",  "joint_forces",
    "gauges",       "masses",   "plastic_map", "plastic_snapshots", "blow_head", "blow_toe", "blow_envelopes"};

}  // namespace barimpact
