#include "report/junit.hpp"

#include "report/suite_report.hpp"
#include "util/files.hpp"
#include "util/version.hpp"

#include <fmt/format.h>

namespace mfv {

double group_seconds(const SuiteReport& rep, const GroupResult& g) {
  double seconds = 0;
  uint64_t integrals = 0;
  for (auto& c : rep.stats)
    if (c.check == g.check) seconds += c.seconds, integrals += c.integrals;
  return integrals > 0 ? seconds * double(g.points.size()) / double(integrals) : 0.0;
}

namespace {

// The worst case in words (the console's), and the case's outcome element.
std::string outcome(const SuiteReport& rep, const GroupResult& g) {
  const std::string w = xml_escape(worst_text(rep, g));
  switch (g.verdict) {
    case Verdict::Fail: {
      std::string why;  // the gate's reasons for this group, one a line
      const std::string who = fmt::format("FAIL {} {}:", g.check, g.model);
      for (auto& line : rep.gate_failures())
        if (line.rfind(who, 0) == 0) why += line + "\n";
      if (g.pooled.failed) why += pooled_text(g) + "\n";
      return fmt::format(
          "<failure message=\"deviation beyond noise and tolerance, or the reference disagrees\">{}</failure>",
          xml_escape(why.empty() ? worst_text(rep, g) : why));
    }
    case Verdict::XPass:
      return fmt::format("<failure message=\"expected to fail ({}) but passed\">{}</failure>", xml_escape(g.reason), w);
    case Verdict::XFail:
      return fmt::format("<skipped message=\"expected failure: {}\"/><system-out>{}</system-out>", xml_escape(g.reason),
                         w);
    case Verdict::Inconclusive:
      return fmt::format("<failure message=\"inconclusive: the estimator did not reach the lobe\">{}</failure>", w);
    case Verdict::Pass: break;
  }
  return "";
}

}  // namespace

std::string suite_junit(const SuiteReport& rep, const SuiteOptions& opt, const std::vector<std::string>& names) {
  size_t failures = !rep.reference_ok(), skipped = 0;
  double total = rep.build_seconds;
  for (auto& g : rep.groups) {
    failures += g.verdict == Verdict::Fail || g.verdict == Verdict::XPass || g.verdict == Verdict::Inconclusive;
    skipped += g.verdict == Verdict::XFail;
    total += group_seconds(rep, g);
  }
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format(
      "<testsuites name=\"mfv\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"{}\" time=\"{:.3f}\">\n",
      rep.groups.size() + 1, failures, skipped, total);
  xml += fmt::format(
      "<testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"{}\" time=\"{:.3f}\" "
      "timestamp=\"{}\">\n",
      xml_escape(rep.title), rep.groups.size() + 1, failures, skipped, total, utc_timestamp());
  xml += fmt::format(
      "  <properties><property name=\"mfv.version\" value=\"{}\"/><property name=\"seed\" value=\"{}\"/>"
      "<property name=\"scale\" value=\"{:g}\"/><property name=\"alpha_fw\" value=\"{:g}\"/></properties>\n",
      xml_escape(version_text()), opt.seed, opt.scale, opt.family_alpha);
  // the kernel/reference comparison runs inside the checks: its time is theirs
  xml += fmt::format(
      "  <testcase classname=\"mfv.reference\" name=\"kernel and reference on the same samples\" "
      "time=\"0\">{}</testcase>\n",
      rep.reference_ok() ? ""
                         : fmt::format("<failure message=\"{}\">{}</failure>", xml_escape(reference_line(rep)),
                                       xml_escape(rep.reference_worst_at)));
  for (size_t i = 0; i < rep.groups.size(); ++i) {
    const GroupResult& g = rep.groups[i];
    const std::string name = i < names.size() ? names[i] : g.model;
    xml +=
        fmt::format("  <testcase classname=\"mfv.{}\" name=\"{} × {}\" time=\"{:.4f}\">{}</testcase>\n",
                    xml_escape(g.check), xml_escape(name), xml_escape(g.check), group_seconds(rep, g), outcome(rep, g));
  }
  xml += "</testsuite>\n</testsuites>\n";
  return xml;
}

}  // namespace mfv
