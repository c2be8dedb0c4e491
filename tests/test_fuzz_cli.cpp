// Fuzz target: the option parser (cli/app.hpp) with every subcommand's
// callback removed, so only parsing runs (issue 17). Random argv from the
// corpus tests/fuzz/corpus/cli/ (one command line per line) must parse or
// throw CLI11's ParseError or mfv::Error, nothing else; and every numeric
// option takes exactly the values the strict parsers take (util/parse.hpp).
#include "cli/app.hpp"
#include "host/fuzz_util.hpp"
#include "util/error.hpp"
#include "util/parse.hpp"

#include <functional>
#include <sstream>

namespace {

// A fresh app whose subcommands do nothing when chosen.
struct ParseOnly {
  CLI::App app{"mfv"};
  mfv::cli::Globals g;
  int rc = 0;
  ParseOnly() {
    mfv::cli::build_app(app, g, rc);
    for (auto* sub : app.get_subcommands({})) sub->callback(std::function<void()>());
  }
  // 0 parsed, 1 CLI11 rejected, 2 mfv rejected
  int parse(const std::vector<std::string>& args) {
    std::vector<const char*> argv = {"mfv"};
    for (auto& a : args) argv.push_back(a.c_str());
    try {
      mfv::cli::parse_command_line(app, int(argv.size()), argv.data());
      return 0;
    } catch (const CLI::ParseError&) {
      return 1;
    } catch (const mfv::Error&) {
      return 2;
    }
  }
};

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string s; in >> s;) w.push_back(s);
  return w;
}

}  // namespace

TEST_CASE("Random command lines parse or fail with a parse error, never otherwise", "[fuzz][cli]") {
  std::vector<std::vector<std::string>> lines;
  for (auto& f : mfv::fuzz::corpus("cli")) {
    std::istringstream in(mfv::fuzz::read_file(f));
    for (std::string l; std::getline(in, l);)
      if (!l.empty()) lines.push_back(words(l));
  }
  std::vector<std::string> names;  // every option name of every subcommand
  {
    ParseOnly p;
    for (auto* sub : p.app.get_subcommands({}))
      for (auto* o : sub->get_options()) names.push_back(o->get_name(false, true));
  }
  uint64_t outcomes[3] = {0, 0, 0};
  mfv::fuzz::run(mfv::fuzz::corpus("cli"), [&](const auto&, const std::string&, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<std::string> args = lines[size_t(rng() % lines.size())];
    for (int e = 0, edits = 1 + int(rng() % 4); e < edits; ++e) {
      size_t at = args.empty() ? 0 : size_t(rng() % args.size());
      const auto& dict = mfv::fuzz::dictionary();
      switch (rng() % 4) {
        case 0:
          if (!args.empty()) args[at] = dict[size_t(rng() % dict.size())];
          break;
        case 1: args.insert(args.begin() + long(at), names[size_t(rng() % names.size())]); break;
        case 2:
          if (!args.empty()) args.erase(args.begin() + long(at));
          break;
        default:
          if (!args.empty()) args[at] = mfv::fuzz::mutate(args[at], rng);
      }
    }
    CAPTURE(seed);
    ParseOnly p;
    try {
      outcomes[p.parse(args)]++;
    } catch (const std::exception& e) {
      std::string line;
      for (auto& a : args) line += " '" + a + "'";
      FAIL("mfv" << line << ": " << e.what());
    }
  });
  INFO(outcomes[0] << " parsed, " << outcomes[1] << " CLI11 errors, " << outcomes[2] << " mfv errors");
  CHECK(outcomes[0] > 0);
  CHECK(outcomes[1] + outcomes[2] > 0);
}

TEST_CASE("Every numeric option takes exactly what the strict parsers take", "[fuzz][cli]") {
  ParseOnly probe;
  struct Numeric {
    std::string sub, name, type;
  };
  std::vector<Numeric> numeric;
  for (auto* sub : probe.app.get_subcommands({}))
    for (auto* o : sub->get_options()) {
      std::string t = o->get_type_name();
      t = t.substr(0, t.find_first_of(" :"));
      if (t == "UINT" || t == "INT" || t == "FLOAT") numeric.push_back({sub->get_name(), o->get_name(false, true), t});
    }
  REQUIRE(numeric.size() >= 20);  // --seed, --samples, --scale ... of every subcommand
  const std::vector<std::string> values = {"-1",
                                           "18446744073709551615",
                                           "18446744073709551616",
                                           "1e23",
                                           "2e19",
                                           "1e17",
                                           "nan",
                                           "inf",
                                           "-inf",
                                           "1e400",
                                           "",
                                           " 1",
                                           "1.5",
                                           "0x10",
                                           "7",
                                           "9223372036854775808",
                                           "-9223372036854775809",
                                           "1e3",
                                           "abc"};
  for (auto& n : numeric)
    for (auto& v : values) {
      CAPTURE(n.sub, n.name, n.type, v);
      bool strict_ok = true;
      std::string canonical = v;
      try {
        if (n.type == "UINT")
          canonical = std::to_string(mfv::parse_unsigned("x", v));
        else if (n.type == "INT")
          canonical = std::to_string(mfv::parse_signed("x", v));
        else
          mfv::parse_finite("x", v);
      } catch (const mfv::Error&) {
        strict_ok = false;
      }
      ParseOnly p;
      // with the subcommand's required arguments, so only this value decides
      std::vector<std::string> args = {n.sub, n.name, v};
      if (n.sub == "eval") args.push_back("ggx");
      if (n.sub == "check") args.insert(args.end(), {"--brdf", "f.cl"});
      int outcome = p.parse(args);
      if (!strict_ok) {
        CHECK(outcome != 0);  // never wrapped, saturated or read as 0
      } else {
        CHECK(outcome != 2);
        auto* opt = p.app.get_subcommand(n.sub)->get_option(n.name);
        if (outcome == 0) CHECK(opt->results().at(0) == canonical);
      }
      // strict_ok with outcome 1: the value does not fit the option's narrower type (an int)
    }
}
