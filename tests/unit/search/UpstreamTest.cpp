// Rules of a downstream stage bracketed over its upstream ratio (search/Upstream.h) and
// freedoms narrowed to where the rules can hold (search/Narrow.h) give the search the
// designs, counts and funnel that asking every design gives (the exhaustive reference),
// and the keys they rank by stay lower bounds of the decided values.
#include <map>
#include <set>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "Compiled.h"

#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "optimise/Decide.h"
#include "search/Search.h"

using namespace gbx;

namespace {

std::string stage(const std::string& name, const std::string& pinions, const std::string& wheels,
                  const std::string& modules, const std::string& width) {
  return fmt::format(
      "  stage {}: helical {{\n    pinion.z in {}; wheel.z in {};\n    normal_module in {{{}}};\n"
      "    helix_angle = 11 deg;\n    face_width {};\n    material = steel_18CrNiMo7_6;\n    accuracy = 6;\n"
      "    rating {{ application_factor = 1.25; life = 20000 h; lubricant {{ viscosity_40 = 150 mm^2/s; }}\n      "
      "roughness {{ flank = 0.6 um; root = 3.0 um; }} }}\n"
      "  }}\n",
      name, pinions, wheels, modules, width);
}

// A reducer of two or three rated stages, its safeties required of each.
std::string reducer(bool freedoms, int stages, const std::string& extra) {
  std::string t = "import materials;\ngearbox R {\n";
  t += stage("a", "17..19", "70..84", "2 mm, 2.5 mm", freedoms ? "in 20..80 mm" : "= 40 mm");
  t += stage("b", "17..19", "60..72", "3 mm, 4 mm", freedoms ? "in 30..120 mm" : "= 60 mm");
  if (stages == 3) t += stage("c", "18..19", "40..46", "4 mm, 5 mm", freedoms ? "in 40..140 mm" : "= 90 mm");
  t += "  operating { input_speed = 1480 rpm; power = 8 kW; }\n";
  t += stages == 3 ? "  require ratio == 50 +- 4%;\n" : "  require ratio == 17.5 +- 3%;\n";
  for (const char* s : {"a", "b", "c"}) {
    if (std::string(s) == "c" && stages < 3) break;
    t += fmt::format("  require {0}.pinion.contact_safety >= 1.2; require {0}.wheel.contact_safety >= 1.2;\n", s);
    t += fmt::format("  require {0}.pinion.bending_safety >= 1.5; require {0}.wheel.bending_safety >= 1.5;\n", s);
  }
  t += extra;
  t += stages == 3 ? "  minimize a.mass + b.mass + c.mass;\n}\n" : "  minimize a.mass + b.mass;\n}\n";
  return t;
}

std::set<std::vector<int>> choices(const rt::SearchResult& r) {
  std::set<std::vector<int>> out;
  for (const auto& d : r.designs)
    out.insert(d.choice);
  return out;
}

void expectSameSearch(const std::string& text) {
  Compiled s = compileFirst(text);
  rt::SearchOptions all;
  all.exhaustive = true;
  auto want = rt::search(*s.m, all);
  rt::SearchOptions fast;
  fast.jobs = 2;
  auto got = rt::search(*s.m, fast);
  ASSERT_TRUE(want.errors.empty() && got.errors.empty()) << text;
  ASSERT_GT(want.count, 20u) << "the spec should leave designs to compare\n" << text;
  EXPECT_EQ(got.count, want.count) << text;
  EXPECT_EQ(choices(got), choices(want)) << text;
  ASSERT_EQ(got.funnel.size(), want.funnel.size()) << text;
  size_t removedAcross = 0;
  for (size_t i = 0; i < want.funnel.size(); ++i) {
    EXPECT_EQ(got.funnel[i].rule, want.funnel[i].rule);
    EXPECT_EQ(got.funnel[i].before, want.funnel[i].before) << want.funnel[i].rule << "\n" << text;
    EXPECT_EQ(got.funnel[i].removed, want.funnel[i].removed) << want.funnel[i].rule << "\n" << text;
    removedAcross += want.funnel[i].scope.empty() && want.funnel[i].removed > 0;
  }
  EXPECT_GT(removedAcross, 0u) << "a downstream safety should remove designs\n" << text;
}

} // namespace

// A limit between the safeties of one candidate's designs: its bracket lies inside the
// range of its upstream ratios.
const char* kBetween = "  require b.pinion.contact_safety >= 1.3;\n";

TEST(Upstream, DownstreamSafetiesOverFreedomsAsTheExhaustiveJoin) { expectSameSearch(reducer(true, 2, kBetween)); }

TEST(Upstream, DownstreamSafetiesAtFixedWidthsAsTheExhaustiveJoin) { expectSameSearch(reducer(false, 2, kBetween)); }

// A rule that holds above a limit of the upstream ratio (a safety bounded from above) and
// one that holds below, on the same stage.
TEST(Upstream, RulesHoldingAboveAndBelowALimitAsTheExhaustiveJoin) {
  expectSameSearch(
      reducer(false, 2, "  require b.pinion.contact_safety <= 1.45;\n  require b.wheel.bending_safety >= 2.2;\n"));
}

TEST(Upstream, ThreeStagesAsTheExhaustiveJoin) { expectSameSearch(reducer(true, 3, kBetween)); }

// Narrowed to where its rules hold, a design's box still holds its decided point: the key
// it is ranked by is at most the decided objective, and at least the whole box's bound.
TEST(Upstream, NarrowedKeysBoundTheDecidedValues) {
  Compiled s = compileFirst(reducer(true, 2, ""));
  rt::SearchOptions all;
  all.exhaustive = true;
  auto wide = rt::search(*s.m, all);
  auto narrow = rt::search(*s.m, rt::SearchOptions{});
  std::map<std::vector<int>, double> wideKey;
  for (const auto& d : wide.designs)
    wideKey[d.choice] = d.keys.at(0);
  rt::Evaluator ev(*s.m);
  rt::FreedomPlan plan(*s.m);
  int tighter = 0, decided = 0;
  for (size_t i = 0; i < narrow.designs.size(); i += 7) {
    const auto& d = narrow.designs[i];
    auto p = plan.decide(ev, d.choice);
    EXPECT_GE(d.keys.at(0), wideKey.at(d.choice) - 1e-12);
    if (!p.feasible) continue;
    ++decided;
    EXPECT_LE(d.keys.at(0), p.keys.at(0) * (1 + 1e-9)) << "design " << i;
    tighter += d.keys.at(0) > wideKey.at(d.choice) * (1 + 1e-6);
  }
  EXPECT_GT(decided, 10);
  EXPECT_GT(tighter, decided / 2) << "narrowing should raise most bounds";
}
