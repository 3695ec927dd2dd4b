#include "report.h"

#include <expat.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

namespace seaplan::sim {
namespace {

// An SVG read back: every element with its attributes, the text inside it,
// and the class of the group it sits in.
struct Element {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::string group_class;
  double Num(const std::string& attr) const {
    auto it = attrs.find(attr);
    return it == attrs.end() ? std::nan("") : std::strtod(it->second.c_str(), nullptr);
  }
};

struct Parsed {
  std::vector<Element> elements;
  std::vector<std::size_t> open;
  std::vector<std::string> groups;
  std::vector<const Element*> Find(const std::string& name, const std::string& group_class) const {
    std::vector<const Element*> out;
    for (const Element& e : elements) {
      if (e.name == name && e.group_class == group_class) out.push_back(&e);
    }
    return out;
  }
  std::vector<const Element*> WithClass(const std::string& name, const std::string& cls) const {
    std::vector<const Element*> out;
    for (const Element& e : elements) {
      auto it = e.attrs.find("class");
      if (e.name == name && it != e.attrs.end() && it->second == cls) out.push_back(&e);
    }
    return out;
  }
};

Parsed ParseSvg(const std::string& xml) {
  Parsed parsed;
  XML_Parser parser = XML_ParserCreate("UTF-8");
  XML_SetUserData(parser, &parsed);
  XML_SetElementHandler(
      parser,
      [](void* data, const XML_Char* name, const XML_Char** attrs) {
        auto* p = static_cast<Parsed*>(data);
        Element e;
        e.name = name;
        for (int i = 0; attrs[i]; i += 2) e.attrs[attrs[i]] = attrs[i + 1];
        e.group_class = p->groups.empty() ? "" : p->groups.back();
        if (e.name == "g") p->groups.push_back(e.attrs["class"]);
        p->open.push_back(p->elements.size());
        p->elements.push_back(std::move(e));
      },
      [](void* data, const XML_Char* name) {
        auto* p = static_cast<Parsed*>(data);
        if (std::string(name) == "g") p->groups.pop_back();
        p->open.pop_back();
      });
  XML_SetCharacterDataHandler(parser, [](void* data, const XML_Char* s, int len) {
    auto* p = static_cast<Parsed*>(data);
    if (!p->open.empty()) p->elements[p->open.back()].text.append(s, len);
  });
  EXPECT_NE(XML_Parse(parser, xml.data(), static_cast<int>(xml.size()), 1), XML_STATUS_ERROR);
  XML_ParserFree(parser);
  return parsed;
}

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

// A ship sailing 3 km east in 20 minutes, PTO for the first half, PTI after.
MissionReport EastboundReport() {
  MissionReport report;
  report.scenario = "eastbound";
  for (int i = 0; i <= 120; ++i) {
    report.trajectory.push_back(
        {10.0 * i, {25.0 * i, 0.0}, i <= 60 ? mission::MsoMode::kPto : mission::MsoMode::kPti});
  }
  return report;
}

TEST(ReportSvgTest, TrajectoryScaleBarMeasuresTheChart) {
  mission::LocationTable locations;
  locations["west"] = {0, 0};
  locations["east"] = {3000, 0};
  const Parsed svg = ParseSvg(TrajectorySvg(EastboundReport(), {}, locations));
  const auto dots = svg.WithClass("circle", "location");
  ASSERT_EQ(dots.size(), 2u);
  const double px_per_m = std::abs(dots[1]->Num("cx") - dots[0]->Num("cx")) / 3000.0;
  const auto bar = svg.Find("line", "scale-bar");
  ASSERT_FALSE(bar.empty());
  const double bar_px = bar[0]->Num("x2") - bar[0]->Num("x1");
  const auto label = svg.Find("text", "scale-bar");
  ASSERT_EQ(label.size(), 1u);
  // 900 px over 3 km plus margins: a fifth of the width is about 700 m, so 500 m.
  EXPECT_EQ(label[0]->text, "500 m (0.27 NM)");
  EXPECT_NEAR(bar_px, 500 * px_per_m, 0.2);
  EXPECT_EQ(svg.Find("polygon", "north-arrow").size(), 1u);
}

TEST(ReportSvgTest, TrajectoryTrackIsColouredByModeWithTimeMarksAndALegend) {
  const MissionReport report = EastboundReport();
  const Parsed svg = ParseSvg(TrajectorySvg(report, {}, {}));
  const auto runs = svg.WithClass("polyline", "track");
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0]->attrs.at("data-mode"), "PTO");
  EXPECT_EQ(runs[1]->attrs.at("data-mode"), "PTI");
  EXPECT_NE(runs[0]->attrs.at("stroke"), runs[1]->attrs.at("stroke"));
  // Every mark sits on the track where the ship was at that time: 20 minutes
  // gives marks every 2 minutes (0:00 to 0:20).
  const auto marks = svg.WithClass("g", "time-mark");
  const auto dots = svg.Find("circle", "time-mark");
  const auto labels = svg.Find("text", "time-mark");
  ASSERT_EQ(marks.size(), 11u);
  ASSERT_EQ(dots.size(), 11u);
  const double px_per_step = dots[1]->Num("cx") - dots[0]->Num("cx");  // 120 s = 300 m
  for (std::size_t i = 0; i < dots.size(); ++i) {
    EXPECT_DOUBLE_EQ(marks[i]->Num("data-t"), 120.0 * i);
    EXPECT_NEAR(dots[i]->Num("cx") - dots[0]->Num("cx"), px_per_step * i, 0.2);
  }
  EXPECT_EQ(labels.front()->text, "0:00:00");
  EXPECT_EQ(labels.back()->text, "0:20:00");
  std::string legend;
  for (const Element* t : svg.Find("text", "legend")) legend += t->text + "|";
  EXPECT_EQ(legend, "track, PTO|track, MEC|track, PTI|land|mission time h:mm:ss|");
}

TEST(ReportSvgTest, GanttHasATimeAxisAndAKindLegend) {
  const Parsed svg = ParseSvg(GanttSvg(ReportWithAwkwardText()));
  const auto tasks = svg.WithClass("rect", "task");
  ASSERT_EQ(tasks.size(), 2u);  // the move in each version
  EXPECT_EQ(svg.Find("text", "").back()->text, "mission time (h:mm:ss)");
  EXPECT_GE(svg.WithClass("line", "time-mark").size(), 2u);
  std::string legend;
  for (const Element* t : svg.Find("text", "legend")) legend += t->text + "|";
  EXPECT_EQ(legend, "move|load|unload|repair|refuel|other|");
}

TEST(ReportSvgTest, ParserCatchesUnescapedText) {
  // The check above can fail: the unescaped reason is not XML.
  EXPECT_NE(XmlError("<svg><text>fuel 30% <= 30%</text></svg>"), "");
}

}  // namespace
}  // namespace seaplan::sim
