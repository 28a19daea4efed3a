#pragma once
// Verification figure (docs/design.md): error against wall time, log–log, one line per (variant,
// metric), from the CSV that `fragmpm verify` writes per case.
#include <string>

namespace fragmpm::analysis {

/// Reads a verify CSV (header `case,variant,level,cell_size_m,particles,dt_s,steps,wall_s,metric,
/// value,reference,error`) and writes error versus wall time as PNG, points in level order. Rows
/// with a zero, negative or non-finite error or wall time cannot sit on log axes and are left out
/// (the title says how many). Throws FigureError naming the file and line on a wrong header, a row
/// with another column count or an unreadable number, or when no row can be drawn.
void write_verify_plot(const std::string& csv_path, const std::string& png_path);

}  // namespace fragmpm::analysis
