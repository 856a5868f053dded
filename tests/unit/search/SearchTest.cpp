#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "Compiled.h"
#include "Specs.h"

#include "driver/Driver.h"
#include "search/Search.h"

using namespace gbx;
namespace fs = std::filesystem;

namespace {

struct Solved {
  std::unique_ptr<driver::Compilation> c;
  std::unique_ptr<rt::Model> model;
  rt::SearchResult result;
};

Solved solveText(const std::string& text, const std::string& gearbox, int jobs = 1) {
  Solved s;
  s.c = driver::compileText("t.gbx", text);
  if (!s.c->ok()) throw std::runtime_error(s.c->diags.renderText(s.c->sources));
  for (const auto& g : s.c->program.gearboxes)
    if (g.name == gearbox) {
      s.model = std::make_unique<rt::Model>(s.c->program, g);
      rt::SearchOptions o;
      o.jobs = jobs;
      s.result = rt::search(*s.model, o);
      return s;
    }
  throw std::runtime_error("no gearbox " + gearbox);
}

std::string spec(const std::string& name) { return readSpec(name); }


std::map<std::string, long long> values(const rt::Model& m, const rt::Design& d) {
  std::map<std::string, long long> v;
  for (size_t i = 0; i < m.slots.size(); ++i)
    v[m.slots[i].path] = static_cast<long long>(m.slots[i].values[static_cast<size_t>(d.choice[i])].exact->num());
  return v;
}

// A two-stage design as the paper writes it: {wheel/pinion, wheel/pinion}, order-free.
using Pairing = std::set<std::pair<long long, long long>>;
// All pairings of the two wheels with the two pinions: the orbit under the swaps.
std::set<Pairing> orbitOf(long long p1, long long w1, long long p2, long long w2) {
  return {Pairing{{w1, p1}, {w2, p2}}, Pairing{{w2, p1}, {w1, p2}}};
}

std::set<std::set<Pairing>> twoStageOrbits(const Solved& s) {
  std::set<std::set<Pairing>> out;
  for (const auto& d : s.result.designs) {
    auto v = values(*s.model, d);
    out.insert(orbitOf(v["upper.pinion.z"], v["upper.wheel.z"], v["lower.pinion.z"], v["lower.wheel.z"]));
  }
  return out;
}

} // namespace

TEST(Search, ThrusterOneStageReproducesThePaper) {
  auto s = solveText(spec("thruster_one_stage.gbx"), "ThrusterOneStage");
  ASSERT_EQ(s.result.count, 3u);
  std::map<std::string, std::pair<double, double>> want = {
      {"31/14", {0.1219, 0.1501}}, {"42/19", {0.0899, 0.1108}}, {"46/21", {0.0820, 0.1010}}};
  rt::Evaluator ev(*s.model);
  for (const auto& d : s.result.designs) {
    ASSERT_TRUE(want.count(d.ratio.str())) << d.ratio.str();
    rt::Assignment a(*s.model);
    a.choice = d.choice;
    rt::Value mmnb = ev.quantity("main.mmn_b", a);
    EXPECT_NEAR(mmnb.lo, want[d.ratio.str()].first, 5e-5);
    EXPECT_NEAR(mmnb.hi, want[d.ratio.str()].second, 5e-5);
  }
  EXPECT_EQ(solveText(spec("thruster_one_stage.gbx"), "ThrusterOneStageWindow").result.count, 3u);
  auto pinned = solveText(spec("thruster_one_stage.gbx"), "ThrusterOneStagePinned");
  ASSERT_EQ(pinned.result.count, 1u);
  EXPECT_EQ(pinned.result.designs[0].ratio.str(), "31/14");
}

TEST(Search, ThrusterTwoStageReproducesTheCorrectedCounts) {
  auto base = solveText(spec("thruster_two_stage.gbx"), "ThrusterTwoStage");
  EXPECT_EQ(base.result.count, 31u);
  EXPECT_EQ(twoStageOrbits(base).size(), 31u) << "every design is a distinct orbit";

  auto filtered = solveText(spec("thruster_two_stage.gbx"), "ThrusterTwoStageFiltered");
  EXPECT_EQ(filtered.result.count, 12u);
  auto orbits = twoStageOrbits(filtered);
  // The paper's 7, written (z2, z1, z4, z3) as in its tuples.
  for (auto [w1, p1, w2, p2] : std::vector<std::array<long long, 4>>{
           {28, 11, 41, 18}, {31, 11, 37, 18}, {36, 11, 39, 22}, {32, 13, 33, 14}, {36, 13, 44, 21}, {41, 16, 43, 19}, {39, 17, 43, 17}})
    EXPECT_TRUE(orbits.count(orbitOf(p1, w1, p2, w2))) << w1 << "/" << p1 << " " << w2 << "/" << p2;

  auto pinned = solveText(spec("thruster_two_stage.gbx"), "ThrusterTwoStagePinned");
  EXPECT_EQ(pinned.result.count, 4u);
  auto p = twoStageOrbits(pinned);
  for (auto [w1, p1, w2, p2] : std::vector<std::array<long long, 4>>{{31, 11, 37, 18}, {32, 13, 33, 14}, {37, 12, 32, 17}, {34, 13, 31, 14}})
    EXPECT_TRUE(p.count(orbitOf(p1, w1, p2, w2))) << w1 << "/" << p1 << " " << w2 << "/" << p2;

  // Rated by ISO 10300: 37/12*32/17 puts its 12-tooth pinion in the lower stage whichever way
  // its wheels go, and its contact safety there is below 1.15.
  auto rated = solveText(spec("thruster_two_stage.gbx"), "ThrusterTwoStageRated");
  EXPECT_EQ(rated.result.count, 3u);
  auto r = twoStageOrbits(rated);
  for (auto [w1, p1, w2, p2] : std::vector<std::array<long long, 4>>{{31, 11, 37, 18}, {32, 13, 33, 14}, {34, 13, 31, 14}})
    EXPECT_TRUE(r.count(orbitOf(p1, w1, p2, w2))) << w1 << "/" << p1 << " " << w2 << "/" << p2;
  EXPECT_FALSE(r.count(orbitOf(12, 37, 17, 32)));
}

TEST(Search, ElectricCylinder) {
  auto s = solveText(spec("electric_cylinder.gbx"), "ElectricCylinder");
  s.result.designs.clear();
  rt::SearchOptions all;
  all.top = std::nullopt;
  auto r = rt::search(*s.model, all);
  bool found = false;
  for (const auto& d : r.designs) {
    auto v = values(*s.model, d);
    if (v["planet_stage.sun.z"] == 19 && v["planet_stage.planet.z"] == 23 && v["planet_stage.ring.z"] == 65 &&
        v["transfer.driver.z"] == 29 && v["transfer.driven.z"] == 50) {
      found = true;
      EXPECT_EQ(d.ratio.str(), "4200/551");
    }
  }
  EXPECT_TRUE(found);
  EXPECT_EQ(r.designs.size(), r.count);

  auto built = solveText(spec("electric_cylinder.gbx"), "ElectricCylinderBuilt");
  ASSERT_EQ(built.result.count, 1u);
  rt::Evaluator ev(*built.model);
  rt::Assignment a(*built.model);
  a.choice = built.result.designs[0].choice;
  EXPECT_NEAR(ev.quantity("ratio", a).lo, 7.6225, 5e-5);
  EXPECT_NEAR(ev.quantity("output_speed", a).lo * 180 / M_PI, 472.3, 0.05);
  EXPECT_NEAR(ev.quantity("planet_stage.mesh_frequency", a).lo, 147.02, 0.005);
  EXPECT_NEAR(ev.quantity("transfer.mesh_frequency", a).lo, 65.60, 0.005);
  EXPECT_NEAR(ev.quantity("transfer.center_distance", a).lo, (29 / 2.0 + 30 + 50 / 2.0) * 0.6e-3, 1e-12);
}

TEST(Search, MarineBaselineGeometry) {
  auto s = solveText(spec("marine_reducer.gbx"), "MarineReducer");
  ASSERT_EQ(s.result.count, 1u);
  rt::Evaluator ev(*s.model);
  rt::Assignment a(*s.model);
  a.choice = s.result.designs[0].choice;
  EXPECT_NEAR(ev.quantity("main.center_distance", a).lo, 0.855, 0.0005);
  EXPECT_NEAR(ev.quantity("main.mass", a).lo, 4602, 2);
  EXPECT_NEAR(ev.quantity("main.sliding_balance", a).lo, 0.1389, 0.0005);
}

TEST(Search, SlidingBalanceOfThePapersOptimum) {
  // 19/75, beta = 10.8 deg, x = 0.4849/0.4760: a = 780 mm and a balance of 0.0001 (docs/dynamics.md).
  auto s = solveText(R"(
gearbox Opt { stage main: helical { pinion.z = 19; wheel.z = 75; normal_module = 16 mm; helix_angle = 10.8 deg;
  pressure_angle = 20 deg; pinion.shift = 0.4849; wheel.shift = 0.4760; face_width = 400 mm; } }
)", "Opt");
  rt::Evaluator ev(*s.model);
  rt::Assignment a(*s.model);
  a.choice = s.result.designs[0].choice;
  EXPECT_NEAR(ev.quantity("main.center_distance", a).lo, 0.780001, 0.0005);
  EXPECT_NEAR(ev.quantity("main.sliding_balance", a).lo, 0.0001, 0.0002);
}

TEST(Search, RatioOnTheToleranceBoundaryIsKept) {
  auto s = solveText("gearbox B { stage s: spur { pinion.z = 59; wheel.z = 177; } require ratio == 3.02 +- 0.02; }", "B");
  EXPECT_EQ(s.result.count, 1u);
  auto out = solveText("gearbox B { stage s: spur { pinion.z = 59; wheel.z = 177; } require ratio == 3.02 +- 0.0199; }", "B");
  EXPECT_EQ(out.result.count, 0u);
  bool named = false;
  for (const auto& f : out.result.funnel) named = named || (f.rule.find("3.02") != std::string::npos && f.removed == 1);
  EXPECT_TRUE(named) << "the funnel names the window that removed it";
}

TEST(Search, ResultsDoNotDependOnJobs) {
  const char* text = R"(
gearbox Three {
  stage a: spur { pinion.z in 12..24; wheel.z in 20..50; require coprime(pinion.z, wheel.z); }
  stage b like a;
  stage c like a;
  interchangeable a, b, c;
  require ratio == 13.36838 +- 0.1%;
  minimize abs(ratio - 13.36838);
}
)";
  auto one = solveText(text, "Three", 1), four = solveText(text, "Three", 4);
  ASSERT_EQ(one.result.count, four.result.count);
  ASSERT_GT(one.result.count, 50u);
  ASSERT_EQ(one.result.designs.size(), four.result.designs.size());
  for (size_t i = 0; i < one.result.designs.size(); ++i) EXPECT_EQ(one.result.designs[i].choice, four.result.designs[i].choice);
}

// ---- a brute-force reference on randomised small specs ------------------------------------

namespace {

struct StageSpec {
  int p0, p1, w0, w1;
  bool coprime;
};

struct RandomSpec {
  std::vector<StageSpec> stages;
  bool teethCoprime3 = false, cross = false, swapStages = false, swapWheels = false;
  units::Rational lo, hi;
  std::string text;
};

RandomSpec makeSpec(std::mt19937& rng, int stages = 0) {
  RandomSpec s;
  int k = stages > 0 ? stages : 1 + static_cast<int>(rng() % 3);
  int span = k >= 4 ? 2 : k == 3 ? 4 : 8;
  bool like = rng() % 2 == 0;
  for (int i = 0; i < k; ++i) {
    if (i > 0 && like) {
      s.stages.push_back(s.stages[0]);
      continue;
    }
    StageSpec st;
    st.p0 = 10 + static_cast<int>(rng() % 7);
    st.p1 = st.p0 + 1 + static_cast<int>(rng() % static_cast<unsigned>(span));
    st.w0 = st.p0 + 2 + static_cast<int>(rng() % 12);
    st.w1 = st.w0 + 2 + static_cast<int>(rng() % static_cast<unsigned>(span + 4));
    st.coprime = rng() % 5 < 3;
    s.stages.push_back(st);
  }
  s.teethCoprime3 = rng() % 10 < 3;
  s.cross = k >= 2 && rng() % 10 < 3;
  s.swapStages = k >= 2 && like && rng() % 2 == 0;
  s.swapWheels = k == 2 && like && rng() % 10 < 3;
  // A target near a random design's ratio, so that windows are seldom empty.
  double target = 1;
  for (const auto& st : s.stages) {
    int p = st.p0 + static_cast<int>(rng() % static_cast<unsigned>(st.p1 - st.p0 + 1));
    int w = st.w0 + static_cast<int>(rng() % static_cast<unsigned>(st.w1 - st.w0 + 1));
    target *= static_cast<double>(w) / p;
  }
  long long t1000 = std::llround(target * 1000);
  units::Rational t = units::Rational::make(t1000, 1000);
  bool relative = rng() % 3 == 0;
  std::string tol;
  if (relative) {
    int pct = 1 + static_cast<int>(rng() % 3);
    tol = fmt::format("{}%", pct);
    s.lo = *t.mul(units::Rational::make(100 - pct, 100));
    s.hi = *t.mul(units::Rational::make(100 + pct, 100));
  } else {
    static const int tols[] = {5, 10, 20, 50};
    int x = tols[rng() % 4];
    tol = fmt::format("{}", x / 1000.0);
    s.lo = *t.sub(units::Rational::make(x, 1000));
    s.hi = *t.add(units::Rational::make(x, 1000));
  }
  std::string g = "gearbox R {\n";
  for (int i = 0; i < k; ++i) {
    const auto& st = s.stages[static_cast<size_t>(i)];
    g += fmt::format("  stage s{}: spur {{ pinion.z in {}..{}; wheel.z in {}..{};{} }}\n", i, st.p0, st.p1, st.w0, st.w1,
                     st.coprime ? " require coprime(pinion.z, wheel.z);" : "");
  }
  if (s.teethCoprime3) g += "  require forall z in teeth: coprime(z, 3);\n";
  if (s.cross) g += "  require s0.pinion.z <= s1.pinion.z;\n";
  if (s.swapStages) {
    g += "  interchangeable s0";
    for (int i = 1; i < k; ++i) g += fmt::format(", s{}", i);
    g += ";\n";
  }
  if (s.swapWheels) g += "  interchangeable s0.wheel, s1.wheel;\n";
  g += fmt::format("  require ratio == {} +- {};\n}}\n", t.decimal().value_or(t.str()), tol);
  s.text = g;
  return s;
}

using Tuple = std::vector<int>;  // p0, w0, p1, w1, …

std::set<Tuple> orbit(const Tuple& t, const RandomSpec& s) {
  std::set<Tuple> seen = {t};
  std::vector<Tuple> todo = {t};
  int k = static_cast<int>(s.stages.size());
  while (!todo.empty()) {
    Tuple x = todo.back();
    todo.pop_back();
    std::vector<Tuple> next;
    if (s.swapStages)
      for (int i = 0; i + 1 < k; ++i) {
        Tuple y = x;
        std::swap(y[static_cast<size_t>(2 * i)], y[static_cast<size_t>(2 * i + 2)]);
        std::swap(y[static_cast<size_t>(2 * i + 1)], y[static_cast<size_t>(2 * i + 3)]);
        next.push_back(y);
      }
    if (s.swapWheels) {
      Tuple y = x;
      std::swap(y[1], y[3]);
      next.push_back(y);
    }
    for (auto& y : next)
      if (seen.insert(y).second) todo.push_back(y);
  }
  return seen;
}

std::set<std::set<Tuple>> bruteForce(const RandomSpec& s) {
  int k = static_cast<int>(s.stages.size());
  std::set<std::set<Tuple>> orbits;
  Tuple t(static_cast<size_t>(2 * k));
  std::function<void(int)> rec = [&](int i) {
    if (i == k) {
      long long num = 1, den = 1;
      for (int j = 0; j < k; ++j) {
        num *= t[static_cast<size_t>(2 * j + 1)];
        den *= t[static_cast<size_t>(2 * j)];
      }
      auto r = units::Rational::make(num, den);
      if (r < s.lo || r > s.hi) return;
      if (s.cross && t[0] > t[2]) return;
      orbits.insert(orbit(t, s));
      return;
    }
    const auto& st = s.stages[static_cast<size_t>(i)];
    for (int p = st.p0; p <= st.p1; ++p)
      for (int w = st.w0; w <= st.w1; ++w) {
        if (w <= p) continue;
        if (st.coprime && std::gcd(p, w) != 1) continue;
        if (s.teethCoprime3 && (p % 3 == 0 || w % 3 == 0)) continue;
        t[static_cast<size_t>(2 * i)] = p;
        t[static_cast<size_t>(2 * i + 1)] = w;
        rec(i + 1);
      }
  };
  rec(0);
  return orbits;
}

} // namespace

TEST(Search, AgreesWithBruteForceOnRandomSpecs) {
  std::mt19937 rng(424242);
  int nonEmpty = 0;
  for (int trial = 0; trial < 80; ++trial) {
    RandomSpec s = makeSpec(rng);
    auto want = bruteForce(s);
    Solved got;
    got.c = driver::compileText("r.gbx", s.text);
    ASSERT_TRUE(got.c->ok()) << s.text << got.c->diags.renderText(got.c->sources);
    got.model = std::make_unique<rt::Model>(got.c->program, got.c->program.gearboxes[0]);
    rt::SearchOptions o;
    o.top = std::nullopt;
    o.jobs = 1 + trial % 3;
    auto r = rt::search(*got.model, o);
    ASSERT_EQ(r.count, want.size()) << s.text;
    std::set<std::set<Tuple>> have;
    for (const auto& d : r.designs) {
      auto v = values(*got.model, d);
      Tuple t;
      for (size_t i = 0; i < s.stages.size(); ++i) {
        t.push_back(static_cast<int>(v[fmt::format("s{}.pinion.z", i)]));
        t.push_back(static_cast<int>(v[fmt::format("s{}.wheel.z", i)]));
      }
      EXPECT_TRUE(have.insert(orbit(t, s)).second) << "two designs of one orbit:\n" << s.text;
    }
    EXPECT_EQ(have, want) << s.text;
    nonEmpty += !want.empty();
  }
  EXPECT_GT(nonEmpty, 40) << "the generator should mostly make solvable specs";
}

// Four and five stages: the row walk against a right half of two or three stages.
TEST(Search, AgreesWithBruteForceOnFourAndFiveStages) {
  std::mt19937 rng(5150);
  int nonEmpty = 0;
  for (int trial = 0; trial < 24; ++trial) {
    RandomSpec s = makeSpec(rng, 4 + trial % 2);
    auto want = bruteForce(s);
    auto c = driver::compileText("r.gbx", s.text);
    ASSERT_TRUE(c->ok()) << s.text << c->diags.renderText(c->sources);
    rt::Model m(c->program, c->program.gearboxes[0]);
    rt::SearchOptions o;
    o.top = std::nullopt;
    o.jobs = 1 + trial % 2;
    auto r = rt::search(m, o);
    ASSERT_EQ(r.count, want.size()) << s.text;
    std::set<std::set<Tuple>> have;
    for (const auto& d : r.designs) {
      auto v = values(m, d);
      Tuple t;
      for (size_t i = 0; i < s.stages.size(); ++i) {
        t.push_back(static_cast<int>(v[fmt::format("s{}.pinion.z", i)]));
        t.push_back(static_cast<int>(v[fmt::format("s{}.wheel.z", i)]));
      }
      have.insert(orbit(t, s));
    }
    EXPECT_EQ(have, want) << s.text;
    nonEmpty += !want.empty();
  }
  EXPECT_GT(nonEmpty, 12) << "the generator should mostly make solvable specs";
}

// Narrow windows (a millionth and less) over three interchangeable stages, the benchmark's
// kind: the row scan passes over rows a bit for their window's lowest bucket at a time and
// must not pass over one whose window holds a design.
TEST(Search, AgreesWithBruteForceOnNarrowWindows) {
  // Each target a design's own ratio, so that every window holds at least that design.
  const std::pair<long long, long long> targets[] = {{29 * 23 * 19, 13 * 17 * 14},
                                                     {30 * 29 * 13, 12 * 12 * 12},
                                                     {19 * 17 * 25, 16 * 15 * 14},
                                                     {28 * 27 * 26, 25 * 23 * 13}};
  for (const auto& [num, den] : targets)
    for (long long ppb : {20, 1000, 5000}) { // half-width in parts per billion
      RandomSpec s;
      s.stages.assign(3, StageSpec{12, 30, 12, 30, false});
      s.swapStages = true;
      const units::Rational t = units::Rational::make(num, den);
      s.lo = *t.mul(units::Rational::make(1000000000 - ppb, 1000000000));
      s.hi = *t.mul(units::Rational::make(1000000000 + ppb, 1000000000));
      s.text = fmt::format("gearbox N {{\n  stage s0: spur {{ pinion.z in 12..30; wheel.z in 12..30; }}\n"
                           "  stage s1 like s0;\n  stage s2 like s0;\n  interchangeable s0, s1, s2;\n"
                           "  require ratio == {} +- {}%;\n}}\n",
                           t.decimal().value_or(t.str()), ppb / 1e7);
      auto want = bruteForce(s);
      auto c = driver::compileText("n.gbx", s.text);
      ASSERT_TRUE(c->ok()) << s.text << c->diags.renderText(c->sources);
      rt::Model m(c->program, c->program.gearboxes[0]);
      rt::SearchOptions o;
      o.top = std::nullopt;
      auto r = rt::search(m, o);
      ASSERT_FALSE(want.empty()) << s.text;
      EXPECT_EQ(r.count, want.size()) << s.text;
    }
}

// The three-stage row walk reports its progress to the end (it used to stop short).
TEST(Search, ProgressReachesTheEndOfTheJoin) {
  std::string text = "gearbox Bench {\n  stage s0: spur { pinion.z in 12..100; wheel.z in 12..100; require coprime(pinion.z, wheel.z); }\n"
                     "  stage s1 like s0;\n  stage s2 like s0;\n  interchangeable s0, s1, s2;\n"
                     "  require ratio == 13.36838 +- 0.0001%;\n}\n";
  Compiled spec = compileFirst(text);
  const rt::Model& m = *spec.m;
  rt::SearchOptions o;
  std::vector<double> seen;
  o.progress = [&](double f) { seen.push_back(f); };
  auto r = rt::search(m, o);
  EXPECT_EQ(r.count, 1117u);
  ASSERT_FALSE(seen.empty());
  EXPECT_DOUBLE_EQ(seen.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
}

// Equal objectives that differ only by rounding tie, and ties go by stage ratio: every
// design here has the centre distance 100 teeth x 2.5 mm / cos 12 deg / 2, which the
// formula gives as two different doubles.
TEST(Search, RoundingLevelTiesRankByStageRatio) {
  auto s = solveText(R"(gearbox G {
  stage s: helical { pinion.z in 12..49; wheel.z in 51..88; normal_module = 2.5 mm; helix_angle = 12 deg; }
  require s.pinion.z + s.wheel.z == 100;
  minimize s.center_distance;
  report { top 40; }
})", "G");
  ASSERT_EQ(s.result.designs.size(), 38u);
  for (size_t i = 1; i < s.result.designs.size(); ++i)
    EXPECT_LT(s.result.designs[i - 1].ratio, s.result.designs[i].ratio) << "rank " << i + 1;
}

// The pruned search (objective screen, bounds over windows, counting by arithmetic)
// keeps exactly the designs an exhaustive ranking keeps: random specs of one to four
// stages, objectives that decompose over stages or the ratio and one that does not.
TEST(Search, PrunedTopNAgreesWithTheExhaustiveRanking) {
  std::mt19937 rng(20261125);
  int pruned = 0;
  for (int trial = 0; trial < 48; ++trial) {
    int k = 1 + trial % 4;
    bool like = rng() % 2 == 0, swap = like && k >= 2 && rng() % 2 == 0;
    int pSpan = k == 4 ? 1 : k == 3 ? 3 : 4, wSpan = k == 4 ? 3 : k == 3 ? 6 : 10;
    std::string text = "import materials;\ngearbox T {\n";
    double target = 1;
    int p0 = 0, w0 = 0;
    for (int i = 0; i < k; ++i) {
      if (i > 0 && like) {
        text += fmt::format("  stage s{} like s0;\n", i);
      } else {
        p0 = 14 + static_cast<int>(rng() % 6);
        w0 = p0 + 3 + static_cast<int>(rng() % 20);
        bool three = rng() % 2 == 0;
        text += fmt::format("  stage s{}: helical {{ pinion.z in {}..{}; wheel.z in {}..{}; normal_module in {{2 mm, 2.5 mm{}}}; "
                            "helix_angle = 12 deg; face_width = 30 mm; material = steel_20CrMnMo; }}\n",
                            i, p0, p0 + pSpan, w0, w0 + wSpan, three ? ", 3 mm" : "");
      }
      // A target near a design's ratio, so that windows are seldom empty.
      target *= static_cast<double>(w0 + static_cast<int>(rng() % static_cast<unsigned>(wSpan + 1))) /
                static_cast<double>(p0 + static_cast<int>(rng() % static_cast<unsigned>(pSpan + 1)));
    }
    if (swap) {
      text += "  interchangeable s0";
      for (int i = 1; i < k; ++i) text += fmt::format(", s{}", i);
      text += ";\n";
    }
    text += fmt::format("  require ratio == {:.3f} +- {}%;\n", target, 1 + rng() % 4);
    std::string mass = "s0.mass", last = fmt::format("s{}", k - 1);
    for (int i = 1; i < k; ++i) mass += fmt::format(" + s{}.mass", i);
    switch (trial % 6) {
    case 0: text += fmt::format("  minimize {};\n", mass); break;
    case 1: text += fmt::format("  minimize abs(ratio - {:.3f});\n", target); break;
    case 2: text += fmt::format("  minimize s0.center_distance / 1 mm + 2 * (ratio - {:.3f})^2;\n  minimize {};\n", target, mass); break;
    case 3: text += fmt::format("  maximize s0.pinion.z - {}.wheel.z;\n", last); break;
    case 4: text += fmt::format("  minimize s0.pinion.z * {}.wheel.z;\n", last); break;  // not a sum over stages
    default: text += fmt::format("  minimize abs(ratio - {:.3f});\n  report {{ sort by {}; }}\n", target, mass); break;
    }
    text += "}\n";
    auto c = driver::compileText("t.gbx", text);
    ASSERT_TRUE(c->ok()) << text << c->diags.renderText(c->sources);
    rt::Model m(c->program, c->program.gearboxes[0]);
    const ir::Expr* sortBy = c->program.gearboxes[0].report && c->program.gearboxes[0].report->sortBy
                                 ? c->program.gearboxes[0].report->sortBy.get()
                                 : nullptr;
    rt::SearchOptions all;
    all.exhaustive = true;
    all.sortBy = sortBy;
    all.jobs = 2 - trial % 2;  // threads share the evaluator
    auto want = rt::search(m, all);
    rt::SearchOptions top;
    top.top = 1 + static_cast<long long>(rng() % 12);
    top.jobs = 1 + trial % 2;
    top.sortBy = sortBy;
    auto got = rt::search(m, top);
    ASSERT_TRUE(got.errors.empty()) << text;
    EXPECT_EQ(got.count, want.count) << text;
    size_t n = std::min<size_t>(static_cast<size_t>(*top.top), want.designs.size());
    ASSERT_EQ(got.designs.size(), n) << text;
    for (size_t i = 0; i < n; ++i) {
      EXPECT_EQ(got.designs[i].choice, want.designs[i].choice) << "rank " << i + 1 << "\n" << text;
      EXPECT_EQ(got.designs[i].keys, want.designs[i].keys) << "rank " << i + 1 << "\n" << text;
    }
    pruned += want.count > static_cast<unsigned long long>(*top.top);
  }
  EXPECT_GT(pruned, 30) << "most trials should have more designs than they keep";
}

// A steep objective whose best designs tie at zero: the screen in doubles must not drop a
// tied design that the exact ranking keeps (the ratio's rounding, times a million, is
// larger than the slack of a key near zero).
TEST(Search, SteepObjectiveTiesAtZeroAreRankedExactly) {
  std::string text = "gearbox S {\n"
                     "  stage a: spur { pinion.z in 12..22; wheel.z in 20..48; }\n"
                     "  stage b: spur { pinion.z in 12..22; wheel.z in 14..48; }\n"
                     "  stage c like b;\n  stage d like b;\n"
                     "  require ratio == 13.5 +- 0.00001%;\n"
                     "  minimize abs(ratio - 13.5) * 1000000;\n}\n";
  Compiled spec = compileFirst(text);
  const rt::Model& m = *spec.m;
  rt::SearchOptions all;
  all.exhaustive = true;
  auto want = rt::search(m, all);
  ASSERT_GT(want.designs.size(), 3u);
  for (long long n : {1, 3, 20}) {
    rt::SearchOptions top;
    top.top = n;
    auto got = rt::search(m, top);
    EXPECT_EQ(got.count, want.count);
    ASSERT_EQ(got.designs.size(), static_cast<size_t>(n));
    for (size_t i = 0; i < got.designs.size(); ++i) EXPECT_EQ(got.designs[i].choice, want.designs[i].choice) << "top " << n << ", rank " << i + 1;
  }
}

// The order a group is written in does not change what is one design.
TEST(Search, InterchangeableInAnyWrittenOrderCountsEachOrbitOnce) {
  auto spec = [](const std::string& group) {
    return "gearbox Three {\n  stage a: spur { pinion.z in 12..20; wheel.z in 20..40; require coprime(pinion.z, wheel.z); }\n"
           "  stage b like a;\n  stage c like a;\n  interchangeable " +
           group + ";\n  require ratio == 13.36838 +- 0.05%;\n}\n";
  };
  unsigned long long counts[3];
  const char* groups[] = {"a, b, c", "c, a, b", "a, c, b"};
  for (int i = 0; i < 3; ++i) counts[i] = solveText(spec(groups[i]), "Three").result.count;
  EXPECT_EQ(counts[0], 45u);
  EXPECT_EQ(counts[1], counts[0]);
  EXPECT_EQ(counts[2], counts[0]);
}

// Stages equal in every attribute and rule filter once (s2 like s0 takes s0's candidates and
// funnel under its own name); a stage that differs only in a fixed value its rule reads
// (s1's module) is filtered on its own. The count is the exact one (Python fractions).
TEST(Search, EqualStagesFilterOnceAndDifferentOnesEachTheirOwn) {
  const char* text = R"(gearbox D {
  stage s0: spur { pinion.z in 12..20; wheel.z in 40..50; normal_module = 3 mm; pressure_angle = 20 deg; require pinion.d >= 45 mm; }
  stage s1: spur { pinion.z in 12..20; wheel.z in 40..50; normal_module = 4 mm; pressure_angle = 20 deg; require pinion.d >= 45 mm; }
  stage s2 like s0;
  require ratio == 30 +- 50%;
}
)";
  Solved s = solveText(text, "D");
  EXPECT_EQ(s.result.count, 351894u);
  std::map<std::string, double> removed;
  for (const auto& f : s.result.funnel)
    if (f.rule.find("pinion.d") != std::string::npos) removed[f.scope] = f.removed;
  EXPECT_EQ(removed["s0"], 33);  // pinion.z 12, 13, 14 at 3 mm: d below 45 mm, with each of 11 wheels
  EXPECT_EQ(removed["s1"], 0);   // at 4 mm every pinion is at least 48 mm
  EXPECT_EQ(removed["s2"], 33);
}

// A compact listing holds the same designs in the same order as the designs it replaces:
// choices, exact ratios, keys, undecided flags; over three interchangeable stages and two
// threads, whose shares it merges.
TEST(Search, ACompactListingHoldsTheSameDesigns) {
  const std::string text =
      "gearbox B {\n"
      "  stage s0: spur { pinion.z in 12..40; wheel.z in 12..40; require coprime(pinion.z, wheel.z); }\n"
      "  stage s1 like s0;\n  stage s2 like s0;\n  interchangeable s0, s1, s2;\n"
      "  require ratio == 5.8 +- 0.5%;\n  minimize abs(ratio - 5.8);\n}\n";
  auto c = driver::compileText("t.gbx", text);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  rt::Model m(c->program, c->program.gearboxes[0]);
  rt::SearchOptions o;
  o.jobs = 2;
  rt::SearchResult held = rt::search(m, o);
  o.compact = true;
  rt::SearchResult compact = rt::search(m, o);
  ASSERT_GT(held.designs.size(), 100u);
  ASSERT_TRUE(compact.designs.empty());
  ASSERT_TRUE(compact.listing);
  ASSERT_EQ(compact.listing->size(), held.designs.size());
  EXPECT_EQ(compact.count, held.count);
  rt::Design d;
  for (size_t i = 0; i < held.designs.size(); ++i) {
    compact.listing->get(i, d);
    ASSERT_EQ(d.choice, held.designs[i].choice) << "design " << i + 1;
    EXPECT_EQ(d.ratio.str(), held.designs[i].ratio.str());
    EXPECT_EQ(d.keys, held.designs[i].keys);
    EXPECT_EQ(d.undecided, held.designs[i].undecided);
  }
}
