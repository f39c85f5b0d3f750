// gate-report.xml parsed back with expat: well-formed, counts on <testsuites> and every
// <testsuite> agree with the outcomes, one <testcase> per case and metric, failures and
// skips where the statuses say, hostile names escaped.

#include "giq/gate/junit.h"

#include <expat.h>
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "giq/gate/summary.h"

namespace {

using giq::gate::Outcome;
using giq::gate::Status;

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string parent;
};

struct Parsed {
  std::vector<Element> elements;
  std::vector<std::string> stack;
  std::string error;
};

Parsed parse(const std::string& xml) {
  Parsed p;
  XML_Parser parser = XML_ParserCreate("UTF-8");
  XML_SetUserData(parser, &p);
  XML_SetElementHandler(
      parser,
      [](void* d, const XML_Char* name, const XML_Char** attrs) {
        auto* p = static_cast<Parsed*>(d);
        Element e{name, {}, p->stack.empty() ? "" : p->stack.back()};
        for (int i = 0; attrs[i]; i += 2) e.attributes[attrs[i]] = attrs[i + 1];
        p->elements.push_back(e);
        p->stack.push_back(name);
      },
      [](void* d, const XML_Char*) { static_cast<Parsed*>(d)->stack.pop_back(); });
  if (XML_Parse(parser, xml.data(), int(xml.size()), 1) == XML_STATUS_ERROR)
    p.error = std::string(XML_ErrorString(XML_GetErrorCode(parser))) + " at line " +
              std::to_string(XML_GetCurrentLineNumber(parser));
  XML_ParserFree(parser);
  return p;
}

Outcome make(const std::string& c, const std::string& m, Status s, bool fails, double v) {
  Outcome o;
  o.case_name = c, o.metric = m, o.status = s, o.fails_gate = fails, o.value = v,
  o.bound = "<= 0.1";
  o.message = s == Status::Pass ? "" : "why & <because> \"quoted\" \x01 control";
  return o;
}

TEST(GateJUnit, ParsesBackWithMatchingCounts) {
  const std::string hostile = "scene<script>alert('x')</script>&";
  const std::vector<Outcome> outcomes = {make("a", "flip_mean", Status::Pass, false, 0.01),
                                         make("a", "relmse", Status::Fail, true, 0.3),
                                         make("a", "gpu_ms", Status::Skip, false, 40),
                                         make(hostile, "flicker", Status::Warn, false, 0.05),
                                         make(hostile, "mse", Status::Unresolved, false, 1e-4),
                                         make(hostile, "psnr", Status::Unresolved, true, 20)};
  const std::string xml = giq::gate::junit_xml(outcomes, {{"a", 1.5}, {hostile, 2.25}});
  const Parsed p = parse(xml);
  ASSERT_TRUE(p.error.empty()) << p.error << "\n" << xml;

  std::vector<Element> suites, cases, failures, skipped;
  for (const auto& e : p.elements) {
    if (e.name == "testsuite") suites.push_back(e);
    if (e.name == "testcase") cases.push_back(e);
    if (e.name == "failure") failures.push_back(e);
    if (e.name == "skipped") skipped.push_back(e);
  }
  ASSERT_EQ(p.elements[0].name, "testsuites");
  EXPECT_EQ(p.elements[0].attributes.at("tests"), "6");
  EXPECT_EQ(p.elements[0].attributes.at("failures"), "2");
  EXPECT_EQ(p.elements[0].attributes.at("skipped"), "2");
  EXPECT_EQ(p.elements[0].attributes.at("errors"), "0");
  EXPECT_EQ(p.elements[0].attributes.at("time"), "3.750");
  ASSERT_EQ(suites.size(), 2u);
  EXPECT_EQ(suites[0].attributes.at("name"), "a");
  EXPECT_EQ(suites[0].attributes.at("tests"), "3");
  EXPECT_EQ(suites[0].attributes.at("failures"), "1");
  EXPECT_EQ(suites[0].attributes.at("skipped"), "1");
  EXPECT_EQ(suites[1].attributes.at("name"), hostile);  // escaped in the file, intact when parsed
  EXPECT_EQ(suites[1].attributes.at("failures"), "1");
  ASSERT_EQ(cases.size(), 6u);
  for (size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].attributes.at("name"), outcomes[i].metric);
    EXPECT_EQ(cases[i].attributes.at("classname"), "giq.gate." + outcomes[i].case_name);
    EXPECT_EQ(cases[i].parent, "testsuite");
  }
  ASSERT_EQ(failures.size(), 2u);
  EXPECT_EQ(failures[0].attributes.at("type"), "FAIL");
  EXPECT_NE(failures[0].attributes.at("message").find("relmse = 0.3"), std::string::npos);
  EXPECT_EQ(failures[1].attributes.at("type"), "UNRESOLVED");
  EXPECT_EQ(skipped.size(), 2u);
  EXPECT_EQ(xml.find("<script>"), std::string::npos);
}

TEST(GateSummary, MarkdownAndTable) {
  const std::vector<Outcome> outcomes = {make("a|b", "flip_mean", Status::Pass, false, 0.01),
                                         make("c", "relmse", Status::Fail, true, 0.3)};
  const std::string md = giq::gate::markdown_summary(outcomes);
  EXPECT_EQ(md.rfind("# giq gate: FAILED", 0), 0u);
  EXPECT_LT(md.find("| c | relmse"), md.find("a\\|b"));  // failures first; '|' escaped
  EXPECT_NE(md.find("2 checks: 1 PASS, 0 WARN, 1 FAIL, 0 UNRESOLVED, 0 SKIP"), std::string::npos);
  const std::string table = giq::gate::format_table(outcomes);
  EXPECT_NE(table.find("FAIL"), std::string::npos);
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3);
}

}  // namespace
