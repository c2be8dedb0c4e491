// gnuplot for report plots: the script runs in a scratch folder, and the
// images come back as bytes so they are written with the report's other
// files (write_files_atomically). mfv energy's make_plots does the same
// inline and could move onto this.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mfv {

using NamedBytes = std::vector<std::pair<std::string, std::string>>;

// Writes `inputs` (name, contents) to a scratch folder, runs `script` there
// and returns the files named in `outputs` (name, bytes). Returns nothing,
// after printing one line, where gnuplot is missing or fails.
NamedBytes render_gnuplot(const NamedBytes& inputs, const std::string& script, const std::vector<std::string>& outputs);

}  // namespace mfv
