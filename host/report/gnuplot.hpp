// gnuplot for report plots: the script runs in a scratch folder, and the
// images come back as bytes so they are written with the report's other
// files (write_files_atomically). Every plot comes as PNG and SVG: a script
// is written for pngcairo and rendered a second time for svg.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mfv {

using NamedBytes = std::vector<std::pair<std::string, std::string>>;

// Writes `inputs` (name, contents) to a scratch folder, runs `script` there
// and returns the files named in `outputs` (name, bytes). Returns nothing,
// after printing one line, where gnuplot is missing or fails.
// `outputs` name the PNGs the script writes; each comes back followed by its
// SVG twin (X.png, X.svg), drawn by the same script on the svg terminal.
NamedBytes render_gnuplot(const NamedBytes& inputs, const std::string& script, const std::vector<std::string>& outputs);

// `s` as literal text in a gnuplot enhanced-text label inside single quotes:
// _ ^ { } @ & ~ are escaped, so "smith_ggx" does not turn "g" into a subscript.
std::string gnuplot_literal(const std::string& s);

// "lc rgb '#rrggbb'" for the i-th series of a plot: twelve distinct colours
// (gnuplot's default cycle has eight, so a ninth curve repeated the first).
std::string series_colour(size_t i);

}  // namespace mfv
