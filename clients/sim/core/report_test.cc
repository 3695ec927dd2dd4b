#include "report.h"

#include <expat.h>
#include <gtest/gtest.h>

#include <string>

namespace seaplan::sim {
namespace {

// Parses `xml` with expat; empty on success, else the error and its line.
std::string XmlError(const std::string& xml) {
  XML_Parser parser = XML_ParserCreate("UTF-8");
  std::string error;
  if (XML_Parse(parser, xml.data(), static_cast<int>(xml.size()), 1) == XML_STATUS_ERROR) {
    error = std::string(XML_ErrorString(XML_GetErrorCode(parser))) + " at line " +
            std::to_string(XML_GetCurrentLineNumber(parser));
  }
  XML_ParserFree(parser);
  return error;
}

MissionReport ReportWithAwkwardText() {
  MissionReport report;
  mission::PlanVersion v1;
  v1.version = 1;
  v1.reason = "initial plan";
  mission::Task move;
  move.id = "v1-t0";
  move.kind = mission::TaskKind::kMove;
  move.duration_s = 120;
  move.action.name = "move-ship";
  move.action.args = {"ship0", "port-a", "port-b"};
  v1.tasks.push_back(move);
  mission::PlanVersion v2 = v1;
  v2.version = 2;
  v2.reason = "fuel 30% <= 30% & \"low\"";
  report.versions = {v1, v2};
  report.trajectory = {{0, {0, 0}}, {10, {50, 20}}};
  report.traffic_tracks["ferry <A&B>"] = {{0, {10, 10}}, {5, {40, 40}}};
  return report;
}

TEST(ReportSvgTest, GanttIsWellFormedXmlWithTheReasonEscaped) {
  const std::string svg = GanttSvg(ReportWithAwkwardText());
  EXPECT_EQ(XmlError(svg), "") << svg;
  EXPECT_NE(svg.find("fuel 30% &lt;= 30% &amp; &quot;low&quot;"), std::string::npos) << svg;
}

TEST(ReportSvgTest, TrajectoryIsWellFormedXmlWithNamesEscaped) {
  mission::LocationTable locations;
  locations["port<1>"] = {0, 0};
  const Rings land = {{{-100, -100}, {-50, -100}, {-50, -50}}};
  const std::string svg = TrajectorySvg(ReportWithAwkwardText(), land, locations);
  EXPECT_EQ(XmlError(svg), "") << svg;
  EXPECT_NE(svg.find("ferry &lt;A&amp;B&gt;"), std::string::npos);
  EXPECT_NE(svg.find("port&lt;1&gt;"), std::string::npos);
}

TEST(ReportSvgTest, ParserCatchesUnescapedText) {
  // The check above can fail: the unescaped reason is not XML.
  EXPECT_NE(XmlError("<svg><text>fuel 30% <= 30%</text></svg>"), "");
}

}  // namespace
}  // namespace seaplan::sim
