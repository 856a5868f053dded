#include <gtest/gtest.h>

#include <fmt/format.h>

#include "Compiled.h"

#include "driver/Driver.h"
#include "model/Evaluator.h"
#include "search/FastKey.h"

using namespace gbx;

namespace {

Compiled compile(const std::string& objective) {
  return compileFirst(fmt::format("gearbox K {{\n  stage a: spur {{ pinion.z in 12..40; wheel.z in 30..90; }}\n"
                                  "  stage b: spur {{ pinion.z in 12..40; wheel.z in 30..90; }}\n"
                                  "  require ratio == 9 +- 20%;\n  minimize {};\n}}\n",
                                  objective));
}

} // namespace

// A key read only from the gearbox ratio gives, at an exact ratio, the very rational the
// evaluator's exact arithmetic gives: the search ranks by it in place of the evaluator.
TEST(FastKey, ExactRatioFunctionsEqualTheEvaluator) {
  const char* objectives[] = {"abs(ratio - 9.123)",
                              "(ratio - 9)^2",
                              "max(ratio, 9.5) / 2 - ratio",
                              "-(ratio * 3 - 1/7)",
                              "min(ratio, 8.25, 10) + abs(8.5 - ratio) * 100",
                              "1 / (ratio - 9.0001)",
                              "ratio^-2 + 0.5 * ratio"};
  for (const char* o : objectives) {
    Compiled s = compile(o);
    const ir::Expr& e = *s.m->gearbox.objectives[0].expr;
    auto f = rt::RatioFn::compile(e);
    ASSERT_TRUE(f.has_value()) << o;
    rt::Evaluator ev(*s.m);
    int checked = 0;
    for (int p = 12; p <= 40; p += 3)
      for (int w = 30; w <= 90; w += 7) {
        rt::Assignment a(*s.m);
        a.ratio = units::Rational::make(static_cast<units::i128>(w) * (w + 1), static_cast<units::i128>(p) * (p + 2));
        rt::Value want = ev.eval(e, a);
        auto got = f->exactAt(*a.ratio);
        ASSERT_TRUE(want.exact.has_value()) << o;
        ASSERT_TRUE(got.has_value()) << o;
        EXPECT_EQ(*got, *want.exact) << o << " at " << a.ratio->str();
        EXPECT_NEAR(f->at(a.ratio->toDouble()), want.lo, 1e-9 * (1 + std::fabs(want.lo))) << o;
        auto [lo, hi] = f->over(a.ratio->toDouble() * (1 - 1e-3), a.ratio->toDouble() * (1 + 1e-3));
        EXPECT_LE(lo, want.lo + 1e-9 * (1 + std::fabs(want.lo))) << o;
        EXPECT_GE(hi, want.lo - 1e-9 * (1 + std::fabs(want.lo))) << o;
        ++checked;
      }
    EXPECT_GT(checked, 50);
  }
}

// What the exact path cannot do exactly it declines, and the evaluator answers.
TEST(FastKey, DeclinesWhatIsNotExact) {
  Compiled s = compile("sqrt(ratio)");
  auto f = rt::RatioFn::compile(*s.m->gearbox.objectives[0].expr);
  ASSERT_TRUE(f.has_value());
  EXPECT_FALSE(f->exactAt(units::Rational::make(9, 1)).has_value());
  EXPECT_DOUBLE_EQ(f->at(9.0), 3.0);
  Compiled t = compile("a.pinion.z * ratio");
  EXPECT_FALSE(rt::RatioFn::compile(*t.m->gearbox.objectives[0].expr).has_value());
}
