#pragma once
// Figures of `fragmpm verify three-grain`, laid out as [XLS21] Fig. 16-25
// (three_grain_figures.cpp).
#include <string>
#include <vector>

#include "three_grain_run.hpp"

namespace fragmpm::pipeline {

/// Writes into `directory` (which must exist), for every run: the top grain's CDFs of d_eq and
/// roundness by number and by mass with one curve per sampled displacement (Fig. 17-18), fragment
/// maps (Fig. 19-21) and, with the thermal module, temperature fields (Fig. 23-25) at every sampled
/// displacement; for all runs together the top platen's force–displacement curves (Fig. 16); and,
/// when `isothermal` and `coupled` name runs of the same speed, their damage fields side by side at
/// the last displacement (Fig. 22). Prints each file written to stderr.
void write_three_grain_figures(const std::vector<ThreeGrainRun>& runs, int isothermal, int coupled,
                               const std::string& directory);

}  // namespace fragmpm::pipeline
