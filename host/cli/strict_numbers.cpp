#include "cli/strict_numbers.hpp"

#include "util/error.hpp"
#include "util/parse.hpp"

#include <string>

namespace mfv::cli {
namespace {

// The value rewritten in canonical decimal, so CLI11's own conversion is
// exact; a value that does not fit the option's narrower type (an int) is
// then CLI11's "could not convert" error.
CLI::Validator strict(const std::string& type) {
  return CLI::Validator(
      [type](std::string& text) -> std::string {
        if (text.empty()) return "the value is empty";
        try {
          if (type == "UINT")
            text = std::to_string(parse_unsigned("value", text));
          else if (type == "INT")
            text = std::to_string(parse_signed("value", text));
          else
            parse_finite("value", text);
        } catch (const Error& e) {
          std::string m = e.what();
          return m.substr(m.find(": ") + 2);  // CLI11 prefixes the option's name
        }
        return "";
      },
      "", "strict " + type);
}

// CLI11 reads an empty value as 0 or as "not given" ("--out ''" wrote
// nothing); an option that takes a value wants a non-empty one.
CLI::Validator not_empty() {
  return CLI::Validator([](std::string& text) -> std::string { return text.empty() ? "the value is empty" : ""; }, "",
                        "not empty");
}

}  // namespace

void make_options_strict(CLI::App& app) {
  for (CLI::Option* opt : app.get_options()) {
    if (opt->get_type_size_max() > 0 && opt->get_expected_min() > 0) opt->check(not_empty());
    std::string type = opt->get_type_name();
    type = type.substr(0, type.find_first_of(" :"));
    if (type == "UINT" || type == "INT" || type == "FLOAT") opt->transform(strict(type));
  }
  for (CLI::App* sub : app.get_subcommands({})) make_options_strict(*sub);
}

}  // namespace mfv::cli
