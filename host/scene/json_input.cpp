#include "scene/json_input.hpp"

#include "util/error.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mfv {

using nlohmann::json;

namespace {

// The path the parser has reached, kept from its callback events so that an
// exception thrown inside a value (a number overflow) can say where it was.
struct PathTracker {
  struct Frame {
    bool array = false;
    size_t index = 0;
    std::string key;
  };
  std::vector<Frame> frames;

  // a value (or a whole container) finished inside the top frame
  void value_done() {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  }
  bool on(json::parse_event_t e, const json& parsed) {
    switch (e) {
      case json::parse_event_t::object_start: frames.push_back({false, 0, ""}); break;
      case json::parse_event_t::array_start: frames.push_back({true, 0, ""}); break;
      case json::parse_event_t::key: frames.back().key = parsed.get<std::string>(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        value_done();
        break;
      case json::parse_event_t::value: value_done(); break;
    }
    return true;
  }
  std::string path() const {
    std::string s;
    for (auto& f : frames) {
      if (f.array)
        s += fmt::format("[{}]", f.index);
      else if (!f.key.empty())
        s += (s.empty() ? "" : ".") + f.key;
    }
    return s.empty() ? "top level" : s;
  }
};

}  // namespace

json parse_json_strict(const std::string& file, const std::string& text) {
  PathTracker where;
  try {
    return json::parse(text, [&](int, json::parse_event_t e, json& parsed) { return where.on(e, parsed); });
  } catch (const json::out_of_range& e) {
    // nlohmann's out_of_range.406: "number overflow parsing '1e400'"
    std::string what = e.what();
    what = what.substr(what.find(']') == std::string::npos ? 0 : what.find(']') + 2);
    throw Error(fmt::format("{}: {}: {} (numbers must be finite)", file, where.path(), what));
  } catch (const json::exception& e) {
    throw Error(fmt::format("{}: malformed JSON: {}", file, e.what()));
  }
}

std::string json_shown(const json& v) {
  std::string s = v.dump();
  return s.size() > 40 ? s.substr(0, 37) + "..." : s;
}

double finite_number(const json& v, const std::string& where) {
  // is_number() is false for booleans, null and strings ("NaN", "0.2")
  if (!v.is_number()) throw Error(fmt::format("{} = {} is not a number", where, json_shown(v)));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error(fmt::format("{} = {} is not a finite number", where, json_shown(v)));
  return x;
}

size_t json_index(const json& v, const std::string& where) {
  if (!v.is_number_unsigned())
    throw Error(fmt::format("{} = {} is not an index (an integer >= 0)", where, json_shown(v)));
  return v.get<size_t>();
}

std::vector<double> number_array(const json& v, size_t n, const std::string& where) {
  if (!v.is_array() || v.size() != n)
    throw Error(fmt::format("{} = {} must be an array of {} numbers", where, json_shown(v), n));
  std::vector<double> out;
  for (size_t k = 0; k < n; ++k) out.push_back(finite_number(v[k], fmt::format("{}[{}]", where, k)));
  return out;
}

}  // namespace mfv
