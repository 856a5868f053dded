// docs/language.md, one meaning everywhere: a reported design holds at the values printed,
// `worst` reads the worse end wherever it stands, and a quantity that depends on the centre
// distance or the shifts agrees with its closed form and with the rating's geometry.
#include <cmath>
#include <random>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "Solve.h"
#include "driver/Driver.h"
#include "driver/Golden.h"
#include "model/Evaluator.h"
#include "passes/Designs.h"
#include "passes/Optimise.h"
#include "passes/Search.h"
#include "report/Report.h"
#include "Solved.h"

using namespace gbx;
using gbx::solved::Solved;
using gbx::solved::solve;

namespace {

std::string replaced(std::string t, const std::string& from, const std::string& to) {
  size_t at = t.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) t.replace(at, from.size(), to);
  return t;
}

std::string report(const std::string& text, const std::string& format = "text") {
  auto c = driver::compileText("t.gbx", text);
  EXPECT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  rt::SolveOptions o;
  o.format = format;
  o.timings = false;
  std::ostringstream out, err;
  rt::solve(c->program, o, out, err);
  return out.str() + err.str();
}

// The 250 kW, 1480 rpm helical reducer of the trial: modules and face widths as sets, the
// helix angle a continuous range, both gears' safeties required, mass minimised.
const char* kReducer = R"(import materials;
gearbox Reducer {
  stage main: helical {
    pinion.z in 25..40;  wheel.z in 90..160;
    normal_module in {3 mm, 3.5 mm, 4 mm, 4.5 mm, 5 mm};
    helix_angle in 8..15 deg;
    face_width in {30 mm, 40 mm, 50 mm, 60 mm};
    material = steel_18CrNiMo7_6;
    accuracy = 6;
    rating {
      application_factor = 1.25;
      life = 20000 h;
      lubricant { viscosity_40 = 150 mm^2/s; }
      roughness { flank = 0.6 um; root = 3.0 um; }
      min_safety { contact = 1.25; bending = 1.5; }
    }
  }
  operating { input_speed = 1480 rpm; power = 250 kW; }
  require main.ratio == 4.06 +- 1%;
  require main.pinion.contact_safety >= 1.25;  require main.wheel.contact_safety >= 1.25;
  require main.pinion.bending_safety >= 1.5;  require main.wheel.bending_safety >= 1.5;
  minimize main.mass;
  report { top 5; columns main.mass, main.pinion.contact_safety, main.wheel.contact_safety; }
}
)";

const char* kSafeties[] = {"main.pinion.contact_safety", "main.wheel.contact_safety", "main.pinion.bending_safety",
                           "main.wheel.bending_safety"};

} // namespace

// The design ranked first holds every rule at the point printed, and no design of the same
// teeth, module and face width is lighter at a helix angle where the rules hold.
TEST(Freedoms, RankedFirstHoldsEveryRuleAtItsPrintedPoint) {
  Solved s = solve(kReducer);
  ASSERT_FALSE(s.result.designs.empty());
  const auto& d = s.result.designs[0];
  ASSERT_EQ(d.freedoms.size(), 1u);
  double beta = d.freedoms[0] * 180 / M_PI;
  EXPECT_GE(s.value("main.pinion.contact_safety"), 1.25);
  EXPECT_GE(s.value("main.wheel.contact_safety"), 1.25);
  EXPECT_GE(s.value("main.pinion.bending_safety"), 1.5);
  EXPECT_GE(s.value("main.wheel.bending_safety"), 1.5);
  // The decided angle is printed to 4 decimals and is that value exactly.
  EXPECT_EQ(rt::formatNumber(beta), fmt::format("{:.4f}", std::round(beta * 1e4) / 1e4));
  // A scan of the same design's helix angle in 0.001 deg steps finds no lighter feasible point.
  double best = s.value("main.mass");
  rt::Assignment a = s.at(0);
  for (double b = 8; b <= 15; b += 0.001) {
    a.box[0] = {b * M_PI / 180, b * M_PI / 180};
    bool ok = true;
    for (const char* q : kSafeties)
      ok = ok && s.ev->quantity(q, a).mid() >= (std::string(q).find("contact") != std::string::npos ? 1.25 : 1.5);
    if (ok) {
      EXPECT_GE(s.ev->quantity("main.mass", a).mid(), best * (1 - 1e-9)) << "lighter at " << b << " deg";
    }
  }
  // The ranking is by the mass at the decided point, ascending.
  for (size_t i = 1; i < s.result.designs.size(); ++i)
    EXPECT_LE(s.value("main.mass", i - 1), s.value("main.mass", i));
}

// The same design with its decided helix angle written into the spec (teeth, module and face
// width pinned too) reports the same numbers, to the last printed digit.
TEST(Freedoms, PinningThePrintedPointReproducesEveryNumber) {
  Solved s = solve(kReducer);
  ASSERT_FALSE(s.result.designs.empty());
  rt::Assignment a = s.at(0);
  auto slotValue = [&](const std::string& path) -> double {
    for (size_t i = 0; i < s.model->slots.size(); ++i)
      if (s.model->slots[i].path == path) return s.model->slots[i].values[static_cast<size_t>(a.choice[i])].lo;
    return NAN;
  };
  std::string pinned = kReducer;
  pinned = replaced(pinned, "pinion.z in 25..40;", fmt::format("pinion.z = {};", slotValue("main.pinion.z")));
  pinned = replaced(pinned, "wheel.z in 90..160;", fmt::format("wheel.z = {};", slotValue("main.wheel.z")));
  pinned = replaced(pinned, "normal_module in {3 mm, 3.5 mm, 4 mm, 4.5 mm, 5 mm};",
                    fmt::format("normal_module = {} mm;", slotValue("main.normal_module") * 1e3));
  pinned = replaced(pinned, "face_width in {30 mm, 40 mm, 50 mm, 60 mm};",
                    fmt::format("face_width = {} mm;", slotValue("main.face_width") * 1e3));
  pinned =
      replaced(pinned, "helix_angle in 8..15 deg;",
               fmt::format("helix_angle = {} deg;", rt::formatNumber(s.result.designs[0].freedoms[0] * 180 / M_PI)));
  Solved p = solve(pinned);
  ASSERT_EQ(p.result.designs.size(), 1u);
  for (const char* q :
       {"main.mass", "main.pinion.contact_safety", "main.wheel.contact_safety", "main.pinion.bending_safety",
        "main.wheel.bending_safety", "main.center_distance", "main.eps_beta"})
    EXPECT_EQ(s.value(q), p.value(q)) << q;
  // And the two reports print the same row and the same rating table.
  std::string r1 = report(kReducer), r2 = report(pinned);
  auto rating = [](const std::string& r) { return r.substr(r.find("  rating main")); };
  EXPECT_EQ(rating(r1), rating(r2));
}

// A freedom feasible only at the end of its range is decided at that end, exactly.
TEST(Freedoms, FeasibleOnlyAtOneEndIsDecidedAtThatEnd) {
  const std::string base = R"(import materials;
gearbox G {
  stage main: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  face_width = 50 mm;
    helix_angle in 8..15 deg;  material = steel_18CrNiMo7_6;
  }
  operating { input_speed = 1000 rpm; power = 100 kW; }
  require main.eps_beta >= LIMIT;
  minimize main.mass;
}
)";
  double at15 = 0.050 * std::sin(15 * M_PI / 180) / (M_PI * 0.004);
  Solved s = solve(replaced(base, "LIMIT", fmt::format("{:.15f}", at15 * (1 - 1e-12))));
  ASSERT_EQ(s.result.designs.size(), 1u);
  EXPECT_EQ(s.result.designs[0].freedoms.at(0), s.model->freedoms[0].hi);
}

// A design whose rules hold nowhere in its range is eliminated, and the funnel names the rule.
TEST(Freedoms, FeasibleNowhereIsEliminatedAndTheFunnelNamesTheRule) {
  // Each rule alone holds somewhere in the box and their enclosures straddle their bounds,
  // so the search keeps the design, undecided; together they hold nowhere.
  const std::string text = R"(import materials;
gearbox G {
  stage a: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  face_width = 50 mm;
    helix_angle in 8..15 deg;  material = steel_18CrNiMo7_6;
  }
  stage b: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  face_width = 50 mm;
    helix_angle in 8..15 deg;  material = steel_18CrNiMo7_6;
  }
  require a.helix_angle - b.helix_angle >= 5 deg;
  require b.helix_angle - a.helix_angle >= 5 deg;
}
)";
  Solved s = solve(text);
  EXPECT_EQ(s.result.count, 0u);
  EXPECT_EQ(s.result.undecided, 0u);
  EXPECT_TRUE(s.result.designs.empty());
  int named = 0;
  for (const auto& f : s.result.funnel)
    if (f.scope == "freedoms" && f.removed == 1 && f.before == 1 && f.rule.find("helix_angle") != std::string::npos)
      ++named;
  EXPECT_EQ(named, 1);
  std::string r = report(text);
  EXPECT_NE(r.find("    freedoms: ((b.helix_angle - a.helix_angle) >= 5 deg): 1 of 1 removed"), std::string::npos) << r;
  // Without the second rule the same design is kept, at a decided point 5 deg apart or more.
  Solved one = solve(replaced(text, "require b.helix_angle - a.helix_angle >= 5 deg;", ""));
  ASSERT_EQ(one.result.designs.size(), 1u);
  EXPECT_GE(one.result.designs[0].freedoms[0] - one.result.designs[0].freedoms[1], 5 * M_PI / 180 - 1e-15);
}

// With no objective the decided point is the feasible one nearest the middle of the range.
TEST(Freedoms, WithoutObjectiveTheMiddleWhereItHolds) {
  const std::string text = R"(import materials;
gearbox G {
  stage main: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  face_width = 50 mm;
    helix_angle in 8..16 deg;  material = steel_18CrNiMo7_6;
  }
  require main.helix_angle <= 10 deg;
}
)";
  Solved s = solve(text);
  ASSERT_EQ(s.result.designs.size(), 1u);
  EXPECT_NEAR(s.result.designs[0].freedoms.at(0) * 180 / M_PI, 10.0, 1e-12);
  Solved free = solve(replaced(text, "require main.helix_angle <= 10 deg;", ""));
  EXPECT_NEAR(free.result.designs.at(0).freedoms.at(0) * 180 / M_PI, 12.0, 1e-12);
}

// A bounded top N over a continuous freedom keeps the designs an exhaustive decision keeps:
// every design decided, then ranked.
TEST(Freedoms, BoundedTopEqualsTheExhaustiveDecision) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    double limit = std::uniform_real_distribution<double>(0.6, 1.3)(rng);
    int top = std::uniform_int_distribution<int>(1, 4)(rng);
    std::string text = fmt::format(R"(import materials;
gearbox G {{
  stage main: helical {{
    pinion.z in 18..26;  wheel.z in 60..90;  normal_module in {{3 mm, 4 mm}};
    face_width in {{30 mm, 45 mm, 60 mm}};  helix_angle in 8..20 deg;  material = steel_18CrNiMo7_6;
  }}
  require main.ratio == 3.5 +- 3%;
  require main.eps_beta >= {:.4f};
  minimize main.mass;
  report {{ top TOP; }}
}}
)",
                                   limit);
    Solved few = solve(replaced(text, "TOP", std::to_string(top)));
    Solved all = solve(replaced(text, "TOP", "100000"));
    ASSERT_GE(all.result.designs.size(), static_cast<size_t>(top)) << "trial " << trial;
    ASSERT_EQ(few.result.designs.size(), static_cast<size_t>(top)) << "trial " << trial;
    for (int i = 0; i < top; ++i) {
      EXPECT_EQ(few.result.designs[static_cast<size_t>(i)].choice, all.result.designs[static_cast<size_t>(i)].choice)
          << "trial " << trial << " rank " << i + 1;
      EXPECT_EQ(few.result.designs[static_cast<size_t>(i)].keys, all.result.designs[static_cast<size_t>(i)].keys);
    }
    EXPECT_EQ(few.result.count, all.result.count);
  }
}

namespace {

// One helical stage with a tolerance box of face width and helix angle (four corners).
const char* kToleranced = R"(import materials;
gearbox H {
  stage hs: helical {
    pinion.z = 23;  wheel.z = 91;  normal_module = 4 mm;  helix_angle = 12 deg;
    face_width = 45 mm;  material = steel_18CrNiMo7_6;  accuracy = 6;
    rating {
      application_factor = 1.25;  life = 20000 h;
      lubricant { viscosity_40 = 150 mm^2/s; }
      roughness { flank = 0.6 um; root = 3.0 um; }
    }
  }
  operating { input_speed = 1480 rpm; power = 150 kW; }
  tolerances { hs.face_width +- 0.5 mm; hs.helix_angle +- 0.1 deg; }
  RULES
  report { columns COLUMNS; }
}
)";

// q at each corner of the box, computed one corner at a time.
std::vector<double> corners(const Solved& s, const std::string& q) {
  std::vector<double> out;
  for (int fw : {-1, 1})
    for (int hb : {-1, 1}) {
      rt::Evaluator ev(*s.model);
      ev.addOffset(s.model->gearbox.tolerances[0].ref, fw * 0.5e-3);
      ev.addOffset(s.model->gearbox.tolerances[1].ref, hb * 0.1 * M_PI / 180);
      out.push_back(ev.quantity(q, s.at(0)).mid());
    }
  return out;
}

std::string spec(const std::string& rules, const std::string& columns) {
  return replaced(replaced(kToleranced, "RULES", rules), "COLUMNS", columns);
}

} // namespace

// `worst(q)` in a report column is the worse end by q's own direction: the smallest safety,
// the largest stress; a rule on the same `worst(q)` reads the same number.
TEST(Worst, AColumnReadsTheWorseEndAsARuleDoes) {
  Solved s = solve(spec("", "worst(hs.pinion.contact_safety), worst(hs.pinion.contact_stress), worst(hs.mass)"));
  ASSERT_EQ(s.result.designs.size(), 1u);
  auto sh = corners(s, "hs.pinion.contact_safety"), stress = corners(s, "hs.pinion.contact_stress"),
       mass = corners(s, "hs.mass");
  double nominalSh = s.value("hs.pinion.contact_safety");
  double minSh = std::min(nominalSh, *std::min_element(sh.begin(), sh.end()));
  const auto& cols = s.model->gearbox.report->columns;
  EXPECT_DOUBLE_EQ(s.ev->eval(*cols[0], s.at(0)).mid(), minSh);
  EXPECT_DOUBLE_EQ(s.ev->eval(*cols[1], s.at(0)).mid(),
                   std::max(s.value("hs.pinion.contact_stress"), *std::max_element(stress.begin(), stress.end())));
  EXPECT_DOUBLE_EQ(s.ev->eval(*cols[2], s.at(0)).mid(),
                   std::max(s.value("hs.mass"), *std::max_element(mass.begin(), mass.end())));
  EXPECT_LT(minSh, nominalSh); // the box does reach below the nominal safety
  // The report says at which corner the smallest S_H is (corners are listed face width
  // slowest, helix angle fastest, minus first).
  size_t k = static_cast<size_t>(std::min_element(sh.begin(), sh.end()) - sh.begin());
  std::string r = report(spec("", "worst(hs.pinion.contact_safety), worst(hs.pinion.contact_stress), worst(hs.mass)"));
  EXPECT_NE(r.find(fmt::format(
                "`worst(hs.pinion.contact_safety)` of design 1 is found at hs.face_width {} mm, hs.helix_angle {} deg",
                k < 2 ? "-0.5" : "+0.5", k % 2 == 0 ? "-0.1" : "+0.1")),
            std::string::npos)
      << r;
  // A rule just above the smallest corner removes the design; one just below keeps it.
  for (double off : {-1e-6, 1e-6}) {
    Solved r = solve(spec(fmt::format("require worst(hs.pinion.contact_safety) >= {:.9f};", minSh + off), "hs.mass"));
    EXPECT_EQ(r.result.count, off < 0 ? 1u : 0u) << off;
  }
}

// Two-sided and negated rules on a `worst` hold only when every corner holds them.
TEST(Worst, TwoSidedAndNegatedRulesCheckEveryCorner) {
  Solved s = solve(spec("", "hs.mass"));
  auto eb = corners(s, "hs.eps_beta");
  double lo = *std::min_element(eb.begin(), eb.end()), hi = *std::max_element(eb.begin(), eb.end());
  double nominal = s.value("hs.eps_beta");
  ASSERT_LT(lo, nominal);
  ASSERT_GT(hi, nominal);
  // A bound between the nominal value and the lower corner: the lower corner violates it.
  double mid = 0.5 * (lo + nominal);
  for (const std::string& rule :
       {fmt::format("require worst(hs.eps_beta) in {:.9f}..5;", mid),
        fmt::format("require worst(hs.eps_beta) == {:.9f} +- {:.9f};", (mid + 5) / 2, (5 - mid) / 2),
        fmt::format("require not (worst(hs.eps_beta) < {:.9f});", mid)}) {
    Solved r = solve(spec(rule, "hs.mass"));
    EXPECT_EQ(r.result.count, 0u) << rule;
  }
  // And above it from the other side: the upper corner violates `<=`-like bounds.
  double up = 0.5 * (hi + nominal);
  for (const std::string& rule : {fmt::format("require worst(hs.eps_beta) in 0..{:.9f};", up),
                                  fmt::format("require not (worst(hs.eps_beta) > {:.9f});", up)}) {
    Solved r = solve(spec(rule, "hs.mass"));
    EXPECT_EQ(r.result.count, 0u) << rule;
  }
  // Bounds that every corner meets keep the design.
  Solved ok =
      solve(spec(fmt::format("require worst(hs.eps_beta) in {:.9f}..{:.9f};", lo * 0.999, hi * 1.001), "hs.mass"));
  EXPECT_EQ(ok.result.count, 1u);
}

// A `let` that reads `worst` takes the direction of the rule it is used in.
TEST(Worst, ALetTakesTheDirectionOfItsRule) {
  Solved s = solve(spec("", "hs.mass"));
  auto sh = corners(s, "hs.pinion.contact_safety");
  double minSh = std::min(s.value("hs.pinion.contact_safety"), *std::min_element(sh.begin(), sh.end()));
  for (double off : {-1e-6, 1e-6}) {
    Solved r = solve(
        spec(fmt::format("let margin = worst(hs.pinion.contact_safety) - {:.9f}; require margin >= 0;", minSh + off),
             "hs.mass"));
    EXPECT_EQ(r.result.count, off < 0 ? 1u : 0u) << off;
  }
}

// A column of `worst` of an expression with no direction prints both ends.
TEST(Worst, AColumnWithNoDirectionPrintsBothEnds) {
  Solved s = solve(spec("", "worst(hs.eps_beta)"));
  auto eb = corners(s, "hs.eps_beta");
  rt::Value v = s.ev->eval(*s.model->gearbox.report->columns[0], s.at(0));
  EXPECT_DOUBLE_EQ(v.lo, *std::min_element(eb.begin(), eb.end()));
  EXPECT_DOUBLE_EQ(v.hi, *std::max_element(eb.begin(), eb.end()));
}

// Independent values (involute geometry written from ISO 21771, not from this code):
// z 20/61, m_n 3 mm, beta 15 deg, alpha_n 20 deg.
TEST(Geometry, GivenCentreDistanceSetsTheWorkingPressureAngle) {
  const std::string text = R"(import materials;
gearbox G {
  stage h: helical {
    pinion.z = 20;  wheel.z = 61;  normal_module = 3 mm;  helix_angle = 15 deg;
    face_width = 30 mm;  center_distance = 128 mm;  material = steel_18CrNiMo7_6;  accuracy = 6;
    SHIFTS
    rating {
      application_factor = 1.0;  life = 20000 h;
      lubricant { viscosity_40 = 150 mm^2/s; }
      roughness { flank = 0.6 um; root = 3.0 um; }
    }
  }
  operating { input_speed = 1000 rpm; power = 20 kW; }
}
)";
  Solved plain = solve(replaced(text, "SHIFTS", ""));
  EXPECT_NEAR(plain.value("h.working_pressure_angle") * 180 / M_PI, 23.1344064, 1e-6);
  EXPECT_NEAR(plain.value("h.eps_alpha"), 0.943312025, 1e-8);
  Solved shifted = solve(replaced(text, "SHIFTS", "pinion.shift = 0.4;  wheel.shift = 0.3;"));
  EXPECT_NEAR(shifted.value("h.working_pressure_angle") * 180 / M_PI, 23.1344064, 1e-6);
  EXPECT_NEAR(shifted.value("h.eps_alpha"), 1.41420122, 1e-7);
  // The rating's table reads the same transverse contact ratio.
  std::string r = report(replaced(text, "SHIFTS", "pinion.shift = 0.4;  wheel.shift = 0.3;"));
  EXPECT_NE(r.find("1.4142"), std::string::npos) << r;
  std::string refused = report(replaced(text, "SHIFTS", ""));
  EXPECT_NE(refused.find("0.943"), std::string::npos) << refused;
}

// The balance of specific sliding at a given centre distance, from the line of action: T1 and
// T2 where it touches the base circles, A and E where the wheel's and the pinion's tip circles
// cut it. The pinion's specific sliding at E and the wheel's at A, from the radii of curvature
// there; the balance (docs/dynamics.md) is zeta_2(A) - zeta_1(E).
double slidingBalance(double z1, double z2, double mn, double beta, double x1, double x2, double aw) {
  const double alphaN = 20 * M_PI / 180;
  double alphaT = std::atan(std::tan(alphaN) / std::cos(beta));
  double r1 = 0.5 * z1 * mn / std::cos(beta), r2 = 0.5 * z2 * mn / std::cos(beta);
  double rb1 = r1 * std::cos(alphaT), rb2 = r2 * std::cos(alphaT);
  double alphaWt = std::acos((r1 + r2) * std::cos(alphaT) / aw);
  // Tips shortened by what the centre distance falls short of r1 + r2 + (x1 + x2) m_n.
  double k = std::max(0.0, (r1 + r2 + (x1 + x2) * mn) - aw);
  double ra1 = r1 + mn * (1 + x1) - k, ra2 = r2 + mn * (1 + x2) - k;
  double t1t2 = aw * std::sin(alphaWt);
  double rho1E = std::sqrt(ra1 * ra1 - rb1 * rb1), rho2E = t1t2 - rho1E;
  double rho2A = std::sqrt(ra2 * ra2 - rb2 * rb2), rho1A = t1t2 - rho2A;
  double u = z2 / z1;
  // Rolling speeds along the profiles: omega1 rho1 and omega1 rho2 / u.
  double zeta1E = 1 - rho2E / (u * rho1E), zeta2A = 1 - u * rho1A / rho2A;
  return zeta2A - zeta1E;
}

// The 20/61 helical pair of the trial, without rating inputs; EXTRA is what a test adds.
const char* kPair = R"(gearbox G {
  stage h: helical {
    pinion.z = 20;  wheel.z = 61;  normal_module = 3 mm;  helix_angle = 15 deg;  face_width = 30 mm;
    EXTRA
  }
}
)";

TEST(Geometry, SlidingAtAGivenCentreDistance) {
  const std::string text = replaced(kPair, "EXTRA", "SHIFTS");
  const double beta = 15 * M_PI / 180;
  Solved at128 = solve(replaced(text, "SHIFTS", "center_distance = 128 mm;"));
  EXPECT_NEAR(at128.value("h.sliding_balance"), slidingBalance(20, 61, 3e-3, beta, 0, 0, 0.128), 1e-9);
  // The tip diameter, not given, is the rack's: d + 2 m_n (no shortening at this distance).
  EXPECT_NEAR(at128.value("h.pinion.tip_diameter"), 20 * 3e-3 / std::cos(beta) + 2 * 3e-3, 1e-12);
  Solved shifted = solve(replaced(text, "SHIFTS", "center_distance = 128 mm;  pinion.shift = 0.4;  wheel.shift = 0.3;"));
  EXPECT_NEAR(shifted.value("h.sliding_balance"), slidingBalance(20, 61, 3e-3, beta, 0.4, 0.3, 0.128), 1e-9);
  // Without a given distance the pair meshes without backlash: a from the working pressure angle.
  Solved free = solve(replaced(text, "SHIFTS", "pinion.shift = 0.4;  wheel.shift = 0.3;"));
  EXPECT_NEAR(free.value("h.sliding_balance"),
              slidingBalance(20, 61, 3e-3, beta, 0.4, 0.3, free.value("h.center_distance")), 1e-9);
  // The given distance moves the balance: the two are not the same number by accident.
  EXPECT_GT(std::fabs(at128.value("h.sliding_balance") - free.value("h.sliding_balance")), 1e-3);
}

// A pair with eps_alpha below 1 is said to be one even where no rule or rating reads it; the
// same pair at its reference distance is not.
TEST(Geometry, ContactRatioBelowOneIsWarned) {
  const std::string text = replaced(kPair, "EXTRA", "DISTANCE");
  std::string r = report(replaced(text, "DISTANCE", "center_distance = 128 mm;"));
  EXPECT_NE(r.find("warning: stage `h` of design 1 has eps_alpha 0.9433, below 1"), std::string::npos) << r;
  std::string json = report(replaced(text, "DISTANCE", "center_distance = 128 mm;"), "json");
  EXPECT_NE(json.find("\"warnings\": [\"stage `h` of design 1 has eps_alpha 0.9433"), std::string::npos) << json;
  std::string plain = report(replaced(text, "DISTANCE", ""));
  EXPECT_EQ(plain.find("warning"), std::string::npos) << plain;
}

// Inverse involute by bisection (the test's own, not the model's Newton iteration).
double inverseInvolute(double t) {
  double lo = 0, hi = 1.5;
  for (int i = 0; i < 200; ++i) {
    double mid = 0.5 * (lo + hi);
    (std::tan(mid) - mid < t ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// A planetary stage with shifted sun and planets: the sun-to-planet centre distance is the
// sun-planet mesh's working centre distance, and the rating's tips are cut to it.
TEST(Geometry, PlanetaryCentreDistanceFromTheShifts) {
  const std::string text = R"(import materials;
gearbox P {
  stage p: planetary {
    sun.z = 21;  planet.z = 30;  ring.z = 81;  planets = 3;  module = 2 mm;  face_width = 20 mm;
    SHIFTS
    material = steel_18CrNiMo7_6;  accuracy = 6;
    rating {
      application_factor = 1.0;  life = 20000 h;
      lubricant { viscosity_40 = 150 mm^2/s; }
      roughness { flank = 0.6 um; root = 3.0 um; }
    }
  }
  operating { input_speed = 1500 rpm; input_torque = 200 N*m; }
}
)";
  const double alpha = 20 * M_PI / 180, inv = std::tan(alpha) - alpha;
  double alphaW = inverseInvolute(inv + 2 * std::tan(alpha) * (0.3 + 0.2) / (21 + 30));
  double aw = 0.5 * 2e-3 * (21 + 30) * std::cos(alpha) / std::cos(alphaW);
  Solved s = solve(replaced(text, "SHIFTS", "sun.shift = 0.3;  planet.shift = 0.2;  ring.shift = -0.7;"));
  EXPECT_NEAR(s.value("p.center_distance"), aw, 1e-12);
  EXPECT_NEAR(aw * 1e3, 51.9386, 1e-4);
  // The rating's sun tip: d/2 + m (1 + x - k), k the tip shortening of that distance.
  double k = (0.3 + 0.2) - (aw - 0.051) / 2e-3;
  std::string r = report(replaced(text, "SHIFTS", "sun.shift = 0.3;  planet.shift = 0.2;  ring.shift = -0.7;"));
  EXPECT_NE(r.find(fmt::format("{:.4f}", 2e3 * (0.021 + 2e-3 * (1 + 0.3 - k)))), std::string::npos) << r;
  // Shifts that sum to zero keep the exact reference distance.
  Solved zero = solve(replaced(text, "SHIFTS", "sun.shift = 0.2;  planet.shift = -0.2;  ring.shift = 0.2;"));
  EXPECT_EQ(zero.value("p.center_distance"), 0.051);
}

// An idler train with shifts: each mesh at its own working centre distance.
TEST(Geometry, IdlerLayoutFromTheWorkingPressureAngles) {
  Solved s = solve(R"(gearbox T {
  stage t: idler {
    driver.z = 20;  idler.z = 30;  driven.z = 50;  module = 2 mm;  face_width = 20 mm;
    driver.shift = 0.5;  idler.shift = 0.3;
  }
}
)");
  EXPECT_NEAR(s.value("t.center_distance") * 1e3, 51.454362 + 80.584290, 1e-5);
  Solved plain = solve(R"(gearbox T {
  stage t: idler { driver.z = 20;  idler.z = 30;  driven.z = 50;  module = 2 mm;  face_width = 20 mm; }
}
)");
  EXPECT_EQ(plain.value("t.center_distance"), 0.130);
}

// `gbxc test` with a tolerance: a whole number (a count, teeth) is exact under any tolerance.
TEST(GoldenTolerance, WholeNumbersAreExact) {
  EXPECT_FALSE(driver::equalWithin("gearbox A: 497844 designs\n", "gearbox A: 497843 designs\n", 1e-5));
  EXPECT_FALSE(driver::equalWithin("  1 33 134\n", "  1 33 135\n", 0.5));
  EXPECT_TRUE(driver::equalWithin("  mass 76.6312 kg\n", "  mass 76.6313 kg\n", 1e-5));
  // A real number that printed short on one side ("2" for 2.0) is compared within the tolerance.
  EXPECT_TRUE(driver::equalWithin("  \"x\": 2\n", "  \"x\": 2.0000000000000004\n", 1e-9));
}

// A ranked baseline with a continuous helix angle and a variant B of it; OBJECTIVE is what B
// adds.
const char* kVariant = R"(import materials;
gearbox A {
  stage h: helical {
    pinion.z in 15..25;  wheel.z in 40..80;  normal_module = 2.5 mm;  helix_angle in 10..14 deg;
    face_width = 30 mm;  material = steel_18CrNiMo7_6;
  }
  require h.ratio == 3 +- 5%;
  require h.eps_beta >= 0.9;
  minimize h.mass;
}
gearbox B extends A {
  OBJECTIVE
  report { columns relative(h.center_distance), relative(h.mass); }
}
)";

// `relative(x)` of a variant that changes nothing is 1: the baseline's design is its own
// design 1, ranked by its own objective, at its decided freedoms.
TEST(Relative, AnUnchangedVariantIsOne) {
  const std::string text = replaced(kVariant, "OBJECTIVE", "");
  auto c = driver::compileText("t.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  rt::Model m(c->program, c->program.gearboxes.at(1));
  auto found = rt::passes::search(m, 1, 1e9, nullptr);
  auto designs = rt::passes::optimise(c->program, m, std::move(found), 1, nullptr);
  auto table = rt::passes::designTable(m, designs, rt::passes::reportColumns(m.gearbox));
  ASSERT_FALSE(table.rows.empty());
  EXPECT_EQ(table.rows[0].cells.at(0).lo, 1.0);
  EXPECT_EQ(table.rows[0].cells.at(0).hi, 1.0);
  EXPECT_EQ(table.rows[0].cells.at(1).lo, 1.0);
}

// A variant that only adds an objective over the baseline's quantity (`minimize
// relative(h.mass)`) goes through the optimiser, which decides each design's freedoms as the
// search does: its design 1 is the baseline's, at the same printed point, and reads 1 exactly.
TEST(Relative, AVariantWithItsOwnObjectiveDecidesAsTheSearchDoes) {
  const std::string text = replaced(kVariant, "OBJECTIVE", "minimize relative(h.mass);");
  std::string json = report(text, "json");
  EXPECT_NE(json.find("\"values\": {\"relative(h.center_distance)\": 1, \"relative(h.mass)\": 1}"), std::string::npos)
      << json;
  Solved a = solve(text, 0), b = solve(text, 1);
  ASSERT_FALSE(a.result.designs.empty());
  ASSERT_FALSE(b.result.designs.empty());
  EXPECT_EQ(a.result.designs[0].choice, b.result.designs[0].choice);
  EXPECT_EQ(a.result.designs[0].freedoms, b.result.designs[0].freedoms);
}

// A whole-gearbox modes scene of one helical stage at beta = 30 deg: the mesh acts on the
// base radii of the transverse section, r_b = d/2 cos(alpha_t), as the stage's own quantity
// and the time-domain model have them (cos alpha_n would raise the frequency by 1.9 %).
TEST(Geometry, ModesUseTheTransverseBaseRadius) {
  const std::string text = R"(gearbox G {
  stage main: helical {
    pinion.z = 20;  wheel.z = 61;  normal_module = 3 mm;  helix_angle = 30 deg;  face_width = 30 mm;
    mesh_stiffness = 20 N/mm/um;  pinion.inertia = 0.002 kg*m^2;  wheel.inertia = 0.05 kg*m^2;
  }
  operating { input_speed = 1500 rpm; input_torque = 100 N*m; }
  scene torsion on G { effects {} duration = 1 s; output modes; }
}
)";
  std::string r = report(text);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r, m, std::regex("mode 1 = ([0-9.]+) Hz"))) << r;
  double alphaT = std::atan(std::tan(20 * M_PI / 180) / std::cos(30 * M_PI / 180));
  double d1 = 20 * 0.003 / std::cos(30 * M_PI / 180), d2 = 61 * 0.003 / std::cos(30 * M_PI / 180);
  double rb1 = 0.5 * d1 * std::cos(alphaT), rb2 = 0.5 * d2 * std::cos(alphaT);
  double k = 20e9 * 0.030;
  double f = std::sqrt(k * (rb1 * rb1 / 0.002 + rb2 * rb2 / 0.05)) / (2 * M_PI);
  EXPECT_NEAR(std::stod(m[1]), f, 1e-4 * f) << r;
}

// A rule whose boundary bends across two freedoms: b sin(beta) >= 1.5 pi m_n with the mass
// (b / cos^2 beta) minimised. The optimum lies on the boundary at the largest helix angle,
// b = 1.5 pi m_n / sin 15 deg = 91.0364 mm; moves along one freedom at a time stall short of it.
TEST(Freedoms, ABoundaryAcrossTwoFreedomsIsFollowed) {
  Solved s = solve(R"(import materials;
gearbox C {
  stage main: helical {
    pinion.z = 17;  wheel.z = 67;  normal_module = 5 mm;  helix_angle in 8..15 deg;
    face_width in 40..120 mm;  material = steel_20CrMnMo;
  }
  require main.eps_beta >= 1.5;
  minimize main.mass;
}
)");
  ASSERT_EQ(s.result.designs.size(), 1u);
  const auto& f = s.result.designs[0].freedoms;
  EXPECT_NEAR(f.at(0) * 180 / M_PI, 15.0, 1e-4);
  double b = 1.5 * M_PI * 0.005 / std::sin(15 * M_PI / 180);
  EXPECT_NEAR(f.at(1), b, 2e-7); // rounded up to the printed 1e-4 mm, where the rule still holds
  EXPECT_GE(s.value("main.eps_beta"), 1.5);
}

// `sort by` orders the decided designs; it does not choose their freedoms.
TEST(Freedoms, SortByDoesNotChooseThePoint) {
  const std::string text = R"(import materials;
gearbox A {
  stage main: helical {
    pinion.z in 17..25;  wheel.z in 60..100;  normal_module = 5 mm;  helix_angle in 8..15 deg;
    face_width in 40..80 mm;  material = steel_20CrMnMo;
  }
  require main.ratio == 3.95 +- 1%;
  report { top 3; SORT columns main.mass; }
}
)";
  Solved plain = solve(replaced(text, "SORT", ""));
  Solved sorted = solve(replaced(text, "SORT", "sort by main.mass;"));
  for (const auto* s : {&plain, &sorted})
    for (const auto& d : s->result.designs) {
      EXPECT_NEAR(d.freedoms.at(0) * 180 / M_PI, 11.5, 1e-12);
      EXPECT_NEAR(d.freedoms.at(1), 0.060, 1e-12);
    }
  for (size_t i = 1; i < sorted.result.designs.size(); ++i)
    EXPECT_LE(sorted.value("main.mass", i - 1), sorted.value("main.mass", i));
}

// The count does not depend on `top`: designs counted but removed by deciding are not counted.
TEST(Freedoms, TheCountDoesNotDependOnTop) {
  const std::string text = R"(import materials;
gearbox T {
  stage a: spur { pinion.z in 17..24;  wheel.z in 25..30;  normal_module = 5 mm;  face_width in 40..120 mm;  material = steel_20CrMnMo; }
  stage b: spur { pinion.z in 17..18;  wheel.z in 25..26;  normal_module = 5 mm;  face_width in 40..120 mm;  material = steel_20CrMnMo; }
  require a.mass + b.mass <= 26 kg;
  require a.face_width + b.face_width >= 170 mm;
  minimize a.pinion.z + b.pinion.z;
  report { top TOP; }
}
)";
  Solved two = solve(replaced(text, "TOP", "2"));
  Solved all = solve(replaced(text, "TOP", "500"));
  EXPECT_EQ(two.result.count, all.result.count);
  EXPECT_EQ(all.result.count, all.result.designs.size());
  for (size_t i = 0; i < two.result.designs.size(); ++i)
    EXPECT_EQ(two.result.designs[i].choice, all.result.designs[i].choice);
}

// A rule on `worst(q)` over a freedom: the freedom is decided like any other (on the rule's
// boundary, at the printed digits), not left to the optimiser's simplex.
TEST(Freedoms, ARuleOnWorstIsDecidedOnItsBoundary) {
  const std::string text = R"(import materials;
gearbox F {
  stage main: helical {
    pinion.z = 29;  wheel.z = 100;  normal_module = 4 mm;  helix_angle in 8..15 deg;
    face_width = 50 mm;  material = steel_18CrNiMo7_6;
  }
  tolerances { main.face_width +- 0.5 mm; main.helix_angle +- 0.1 deg; }
  require worst(main.eps_beta) >= 0.9;
  minimize main.mass;
}
)";
  Solved s = solve(text);
  ASSERT_EQ(s.result.designs.size(), 1u);
  double beta = s.result.designs[0].freedoms.at(0) * 180 / M_PI;
  EXPECT_NEAR(beta * 1e4, std::round(beta * 1e4), 1e-6); // at the printed digits
  // Feasible there, not one printed digit lower: the smallest eps_beta over the corners is
  // b_min sin(beta - 0.1 deg) / (pi m_n).
  auto worstEb = [](double deg) { return 0.0495 * std::sin((deg - 0.1) * M_PI / 180) / (M_PI * 0.004); };
  EXPECT_GE(worstEb(beta), 0.9 * (1 - 1e-12));
  EXPECT_LT(worstEb(beta - 1e-4), 0.9);
}

// A helical mesh's vibration at its periodic steady state: cheap enough to run per corner.
static const char* const kVibrationScene = R"(  scene vib on main {
    effects {
      varying_stiffness { harmonics = 5; }
      damping { ratio = 0.05; }
      transmission_error { mean = 0 um; amplitude = 5 um; phase = 0 deg; }
    }
    steady_state = periodic;
    record = 1 mesh_period;  samples = 64;
    output rms(acceleration);
  }
)";

// The same with an optimised baseline (its objective reads a scene): the baseline's design is
// its optimum, freedoms included, and the unchanged variant's optimum is the same point.
TEST(Relative, AnUnchangedVariantOfAnOptimisedBaselineIsOne) {
  const std::string text = R"(import materials;
gearbox A {
  stage main: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  helix_angle in 8..15 deg;
    face_width = 50 mm;  material = steel_18CrNiMo7_6;
  }
  operating { input_speed = 1500 rpm; input_torque = 500 N*m; }
)" + std::string(kVibrationScene) +
                           R"(  minimize vib.rms(acceleration);
}
gearbox B extends A {
  report { columns relative(vib.rms(acceleration)), relative(main.mass); }
}
)";
  std::string json = report(text, "json");
  // The objective's own value follows the spec's columns.
  EXPECT_NE(json.find("\"values\": {\"relative(vib.rms(acceleration))\": 1, \"relative(main.mass)\": 1, \"vib.rms(acceleration)\": "),
            std::string::npos)
      << json;
}

// `worst` of a vibration output (smaller is better: the largest over the corners), checked
// against the scene run at each corner on its own.
TEST(Worst, AVibrationOutputReadsItsLargestCorner) {
  const std::string text = R"(import materials;
gearbox A {
  stage main: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  helix_angle = 12 deg;
    face_width = WIDTH;  material = steel_18CrNiMo7_6;
  }
  operating { input_speed = 1500 rpm; input_torque = 500 N*m; }
)" + std::string(kVibrationScene) +
                           R"(  TOLERANCES
  report { columns COLUMN; }
}
)";
  auto value = [](const std::string& json, const std::string& key) {
    std::smatch m;
    EXPECT_TRUE(std::regex_search(
        json, m, std::regex("\"" + std::regex_replace(key, std::regex("[()]"), "\\$&") + "\": ([-0-9.e]+)")))
        << json;
    return m.empty() ? NAN : std::stod(m[1]);
  };
  double largest = 0;
  std::string where;
  for (const char* w : {"49 mm", "50 mm", "51 mm"}) {
    std::string one =
        replaced(replaced(replaced(text, "WIDTH", w), "TOLERANCES", ""), "COLUMN", "vib.rms(acceleration)");
    double v = value(report(one, "json"), "vib.rms(acceleration)");
    if (v > largest) {
      largest = v;
      where = w == std::string("49 mm") ? "at main.face_width -1 mm" : w == std::string("51 mm") ? "at main.face_width +1 mm" : "at the nominal design";
    }
  }
  std::string boxed =
      replaced(replaced(replaced(text, "WIDTH", "50 mm"), "TOLERANCES", "tolerances { main.face_width +- 1 mm; }"),
               "COLUMN", "worst(vib.rms(acceleration))");
  EXPECT_NEAR(value(report(boxed, "json"), "worst(vib.rms(acceleration))"), largest, 1e-9 * largest);
  // The report names the corner, as it does for a catalogue quantity.
  std::string text1 = report(boxed);
  EXPECT_NE(text1.find("`worst(vib.rms(acceleration))` of design 1 is found " + where), std::string::npos) << text1;
}

// A set's member reads in the report as it was written, not converted to the display unit.
TEST(Choices, ASetMemberReadsAsWritten) {
  std::string r = report(R"(gearbox G {
  stage s: helical { pinion.z = 20; wheel.z = 40; normal_module = 2 mm; face_width = 20 mm; helix_angle in {0.2 rad, 12 deg}; }
}
)");
  EXPECT_NE(r.find("0.2 rad"), std::string::npos) << r;
  EXPECT_NE(r.find("12 deg"), std::string::npos) << r;
  EXPECT_EQ(r.find("11.4592"), std::string::npos) << r;
}

// A rule on no freedom that the search leaves to deciding (`worst` over the tolerance of a
// stage without freedoms) is checked on the whole design, also where the freedoms are decided
// stage by stage.
TEST(Freedoms, ARuleOnNoFreedomIsStillChecked) {
  const std::string text = R"(import materials;
gearbox H {
  stage a: helical { pinion.z = 21; wheel.z = 83; normal_module = 4 mm; helix_angle in 8..15 deg; face_width = 50 mm; material = steel_18CrNiMo7_6; }
  stage b: helical { pinion.z = 21; wheel.z = 83; normal_module = 4 mm; helix_angle = 12 deg; face_width = 50 mm; material = steel_18CrNiMo7_6; }
  tolerances { b.face_width +- 1 mm; }
  require worst(b.mass) <= LIMIT;
  minimize a.mass;
}
)";
  EXPECT_EQ(solve(replaced(text, "LIMIT", "0.1 kg")).result.count, 0u);
  EXPECT_EQ(solve(replaced(text, "LIMIT", "1000 kg")).result.count, 1u);
}

// A rule over the tolerance corners of a design with no freedoms is checked at its one point:
// the design goes, and the funnel names the rule (no optimiser runs for it).
TEST(Worst, ARuleWithoutFreedomsRemovesTheDesignAndIsNamed) {
  const std::string text = R"(import materials;
gearbox T {
  stage hs: helical {
    pinion.z = 21;  wheel.z = 83;  normal_module = 4 mm;  helix_angle = 12 deg;  face_width = 50 mm;
    material = steel_18CrNiMo7_6;
  }
  tolerances { hs.face_width +- 0.5 mm; hs.helix_angle +- 0.1 deg; }
  require worst(hs.eps_beta) >= LIMIT;
}
)";
  // eps_beta = b sin(beta) / (pi m_n) at its smallest corner (49.5 mm, 11.9 deg).
  double low = 0.0495 * std::sin(11.9 * M_PI / 180) / (M_PI * 0.004);
  std::string kept = report(replaced(text, "LIMIT", fmt::format("{:.6f}", low - 1e-6)));
  EXPECT_NE(kept.find("gearbox T: 1 design"), std::string::npos) << kept;
  std::string gone = report(replaced(text, "LIMIT", fmt::format("{:.6f}", low + 1e-6)));
  EXPECT_NE(gone.find("gearbox T: 0 designs"), std::string::npos) << gone;
  EXPECT_NE(gone.find("worst(hs.eps_beta) >= "), std::string::npos) << gone;
  EXPECT_EQ(gone.find("optimisation"), std::string::npos) << gone;
}

// Geometry a parallel-axis pair cannot have is refused where it is written, in the unit written.
TEST(Geometry, AnglesBeyondTheirLimitsAreRefused) {
  auto check = [](const std::string& stage) {
    auto c = driver::compileText("t.gbx", "gearbox G {\n  stage s: helical { pinion.z = 20; wheel.z = 61; normal_module = 3 mm; face_width = 30 mm; " +
                                              stage + " }\n}\n");
    return c->diags.renderText(c->sources);
  };
  EXPECT_NE(check("helix_angle = 95 deg;").find("E0405"), std::string::npos);
  EXPECT_NE(check("helix_angle = -15 deg;").find("got -15 deg"), std::string::npos) << check("helix_angle = -15 deg;");
  EXPECT_NE(check("helix_angle in 8..95 deg;").find("E0405"), std::string::npos);
  EXPECT_NE(check("helix_angle = 15 deg; pressure_angle = 89 deg;").find("E0405"), std::string::npos);
  EXPECT_EQ(check("helix_angle in 8..15 deg;"), "");
}

// A pair whose tip circles do not reach the line of action at the given centre distance is
// said not to mesh.
TEST(Geometry, APairThatDoesNotMeshIsSaidToBeOne) {
  std::string r = report(R"(gearbox G {
  stage s: helical { pinion.z = 20; wheel.z = 61; normal_module = 3 mm; helix_angle = 15 deg; face_width = 30 mm; center_distance = 500 mm; }
}
)");
  EXPECT_NE(r.find("warning: stage `s` of design 1 does not mesh"), std::string::npos) << r;
}

// docs/reports.md: one display unit per quantity in every format. A deviation, a modification
// or a transmission error reads in um whatever its size (a 0.2 mm tip relief as 200 um, not as
// 0.2 mm in one table and um in another); other lengths in mm, however small.
TEST(OneMeaning, MicrometreQuantitiesReadInMicrometresWhateverTheirSize) {
  auto quantity = [](cat::Q key) {
    ir::Expr e;
    e.op = ir::Op::Quantity;
    e.type.dim = units::dims::length;
    e.ref.key = key;
    return e;
  };
  for (cat::Q key : {cat::Q::PitchDeviation, cat::Q::ProfileDeviation, cat::Q::TipRelief, cat::Q::LeadCrowning, cat::Q::LoadDeflection})
    EXPECT_EQ(rt::displayUnitOf(quantity(key)).name, "um") << cat::keyName(key);
  for (cat::Q key : {cat::Q::CenterDistance, cat::Q::FaceWidth, cat::Q::TipReliefHeight})
    EXPECT_EQ(rt::displayUnitOf(quantity(key)).name, "mm") << cat::keyName(key);
  ir::Expr te;
  te.op = ir::Op::SceneOutput;
  te.type.dim = units::dims::length;
  EXPECT_EQ(rt::displayUnitOf(te).name, "um") << "a number read from a transmission error";
  // worst(), max() of a micrometre quantity keep its unit.
  ir::Expr worst;
  worst.op = ir::Op::Scatter;
  worst.type.dim = units::dims::length;
  worst.args.push_back(std::make_unique<ir::Expr>(std::move(te)));
  EXPECT_EQ(rt::displayUnitOf(worst).name, "um");
  for (auto signal : {cat::Signal::TransmissionError, cat::Signal::StaticTransmissionError, cat::Signal::Displacement})
    EXPECT_EQ(cat::signalUnit(signal).name, "um");
  EXPECT_EQ(cat::signalUnit(cat::Signal::MeshForce).name, "N");
}
