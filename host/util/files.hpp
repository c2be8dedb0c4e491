// Files are written whole or not at all (docs/design.md §7): each goes to a
// temporary name beside its target and is renamed into place only after
// every file of the set was written and flushed.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace mfv {

// (path, contents) pairs; throws mfv::Error and leaves earlier files intact
// if any of them cannot be written.
void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files);

// Creates `dir` (and parents) if missing; throws mfv::Error if it names
// something that is not a folder or cannot be created. Called before a long
// run so a bad --out fails at once.
void prepare_output_dir(const std::string& dir);

// The whole file; throws mfv::Error "OPTION PATH: cannot read the file".
std::string read_text_file(const std::string& path, const std::string& option);

std::string xml_escape(const std::string& s);
std::string utc_timestamp();

}  // namespace mfv
