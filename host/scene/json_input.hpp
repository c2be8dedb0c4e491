// Strict, typed reading of the JSON that scenes and material files hold
// (issue 17): numbers are finite JSON numbers (not strings, booleans, null),
// arrays have the length their spec gives, and a number that overflows a
// double ("1e400") is one mfv::Error naming the file and the field instead of
// nlohmann's out_of_range exception escaping as an abort.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace mfv {

// Parses `text`; a syntax error or an overflowing number throws mfv::Error
// "<file>: <path>: ..." where <path> is the JSON path reached ("materials[0].roughness").
nlohmann::json parse_json_strict(const std::string& file, const std::string& text);

// `where` names file, material and field for the message: "x.gltf: material 'gold' (materials[2]): roughnessFactor".
double finite_number(const nlohmann::json& v, const std::string& where);
// A JSON integer >= 0 (an index into a glTF array).
size_t json_index(const nlohmann::json& v, const std::string& where);
// An array of exactly n finite numbers.
std::vector<double> number_array(const nlohmann::json& v, size_t n, const std::string& where);
// The value as it was written, shortened, for messages: "\"NaN\"", "null", "true", "[1,2,3]".
std::string json_shown(const nlohmann::json& v);

}  // namespace mfv
