#include <gtest/gtest.h>

#include "ast/Ast.h"
#include "parse/Parser.h"

using namespace gbx;

namespace {

struct Parsed {
  source::SourceManager sm;
  diag::DiagnosticEngine diags;
  ast::File file;
};

std::unique_ptr<Parsed> parseText(const std::string& text) {
  auto p = std::make_unique<Parsed>();
  int id = p->sm.add("t.gbx", "/t.gbx", text);
  p->file = parse::parseFile(p->sm, id, p->diags);
  return p;
}


} // namespace

TEST(Parser, RangeIsNotReadAsDecimalPoint) {
  auto p = parseText("const r = 1; gearbox G { stage s: spur { pinion.z in 11..25; } }");
  ASSERT_FALSE(p->diags.hasErrors()) << p->diags.renderText(p->sm);
  const auto& dom = p->file.decls[1].body[0].body[0];
  EXPECT_EQ(dom.kind, ast::StmtKind::Domain);
  EXPECT_EQ(ast::print(*dom.lo), "11");
  EXPECT_EQ(ast::print(*dom.hi), "25");
}

TEST(Parser, UnitsAreGluedButOperatorsWithBlanksAreNot) {
  auto p = parseText("const a = 22% * whole_depth; const b = 91670 N*m; const c = 16.35 N/(mm*um); const d = 7850 kg/m^3;");
  ASSERT_FALSE(p->diags.hasErrors()) << p->diags.renderText(p->sm);
  EXPECT_EQ(ast::print(*p->file.decls[0].value), "(22 % * whole_depth)");
  EXPECT_EQ(ast::print(*p->file.decls[1].value), "91670 N*m");
  const auto& c = *p->file.decls[2].value;
  ASSERT_TRUE(c.unit);
  ASSERT_EQ(c.unit->factors.size(), 3u);
  EXPECT_EQ(c.unit->factors[1].atom, "mm");
  EXPECT_EQ(c.unit->factors[1].exponent, -1);
  EXPECT_EQ(c.unit->factors[2].exponent, -1);
  EXPECT_EQ(p->file.decls[3].value->unit->factors[1].exponent, -3);
}

TEST(Parser, DegreeSignMicroAndPlusMinus) {
  auto p = parseText("const a = 35\u00B0; const b = 11 \u00B5m; const c = 5.8 \u00B1 0.01; const d = 3.952 +- 1%;");
  ASSERT_FALSE(p->diags.hasErrors()) << p->diags.renderText(p->sm);
  EXPECT_EQ(ast::print(*p->file.decls[0].value), "35 \u00B0");
  EXPECT_EQ(ast::print(*p->file.decls[1].value), "11 \u00B5m");
  EXPECT_EQ(p->file.decls[2].value->kind, ast::ExprKind::Tolerance);
  EXPECT_EQ(ast::print(*p->file.decls[3].value), "(3.952 +- 1 %)");
}

TEST(Parser, PrecedenceAndForall) {
  auto p = parseText("const a = -2^2 + 3 * 4; const b = forall z in teeth: coprime(z, 5) and not z > 3 or true;");
  ASSERT_FALSE(p->diags.hasErrors()) << p->diags.renderText(p->sm);
  EXPECT_EQ(ast::print(*p->file.decls[0].value), "((-(2 ^ 2)) + (3 * 4))");
  EXPECT_EQ(ast::print(*p->file.decls[1].value), "(forall z in teeth: ((coprime(z, 5) and (not (z > 3))) or true))");
}

TEST(Parser, ComparisonWithToleranceAndRangeMembership) {
  auto p = parseText("const a = ratio == 7.62 +- 0.005; const b = s.mmn_b in 0.10..0.14; const c = x in {1, 2};");
  ASSERT_FALSE(p->diags.hasErrors()) << p->diags.renderText(p->sm);
  EXPECT_EQ(ast::print(*p->file.decls[0].value), "(ratio == (7.62 +- 0.005))");
  EXPECT_EQ(ast::print(*p->file.decls[1].value), "(s.mmn_b in 0.10..0.14)");
  EXPECT_EQ(ast::print(*p->file.decls[2].value), "(x in {1, 2})");
}

TEST(Parser, StatementsOfEveryKind) {
  auto p = parseText(R"(
import klingelnberg; import "x.gbx";
preset p for bevel { face_ratio in 0.29..0.33; }
material m { youngs_modulus = 206 GPa; }
gearbox G extends B {
  stage a: bevel with p, q { pinion.z in 11..25; }
  stage b like a;
  let t = 5.8;
  interchangeable a, b;
  minimize abs(ratio - t); maximize a.mmn_b;
  operating { input_speed = 800 rpm; }
  scene v on a { effects { damping { ratio = 0.07; } } settle = 200 mesh_periods; accuracy { method = rk8pd; } output rms(acceleration), modes; }
  modify a { pinion.thermal_lead_relief = 8 um when pitch_line_velocity > 100 m/s; }
  split s { torsion_shaft { length = 1 m; } install = free; }
  study w { work_precision of v; rtol in {1e-3, 1e-4}; harmonics in 1..8; }
  study sw { sweep s.torsion_shaft.diameter in 90..130 mm step 10 mm; output s.imbalance; plot; }
  report { top 20; sort by ratio; columns ratio, a.mmn_b; }
})");
  ASSERT_FALSE(p->diags.hasErrors()) << p->diags.renderText(p->sm);
  ASSERT_EQ(p->file.decls.size(), 5u);
  const auto& g = p->file.decls[4];
  EXPECT_EQ(g.base, "B");
  std::vector<ast::StmtKind> kinds;
  for (const auto& s : g.body) kinds.push_back(s.kind);
  using K = ast::StmtKind;
  std::vector<K> want = {K::Stage, K::Like,     K::Let,   K::Interchangeable, K::Minimize, K::Maximize, K::Operating,
                         K::Scene, K::Modify,   K::Split, K::Study,           K::Study,    K::Report};
  EXPECT_EQ(kinds, want);
  EXPECT_EQ(g.body[0].with, (std::vector<std::string>{"p", "q"}));
  EXPECT_TRUE(g.body[8].body[0].when);
  EXPECT_EQ(g.body[11].body[0].kind, K::Sweep);
  EXPECT_EQ(ast::print(*g.body[11].body[0].step), "10 mm");
}

TEST(Parser, RecoversAndReportsEveryError) {
  auto p = parseText("gearbox G { let a = (1 + ; let b = ; require x > 2; let c = 3 }");
  EXPECT_GE(p->diags.errorCount(), 3);
  for (const auto& d : p->diags.all()) EXPECT_EQ(d.code, "E0102");
}

TEST(Parser, MissingSemicolonAtLineEndPointsAtTheLine) {
  auto p = parseText("gearbox G {\n  let a = 41\n  let b = 2;\n}\n");
  ASSERT_EQ(p->diags.errorCount(), 1);
  const auto& d = p->diags.all()[0];
  EXPECT_EQ(d.span.line, 2);
  EXPECT_EQ(d.message, "syntax error: missing `;` after `41`");
}

TEST(Parser, LexicalErrors) {
  auto p = parseText("const a = 3 $;\nconst s = \"open\n/* never closed");
  std::vector<std::string> codes;
  for (const auto& d : p->diags.sorted()) codes.push_back(d.code);
  EXPECT_NE(std::find(codes.begin(), codes.end(), "E0101"), codes.end());
  EXPECT_EQ(std::count(codes.begin(), codes.end(), "E0103"), 2);
}

TEST(Parser, DeepNestingIsRefusedNotOverflowed) {
  std::string deep = "const a = " + std::string(5000, '(') + "1" + std::string(5000, ')') + ";";
  auto p = parseText(deep);
  ASSERT_EQ(p->diags.errorCount(), 1);
  EXPECT_EQ(p->diags.all()[0].code, "E0105");
  auto q = parseText("const a = " + std::string(3000, '-') + "1;");
  EXPECT_EQ(q->diags.all().at(0).code, "E0105");
}

TEST(Parser, SpansCountCodePoints) {
  auto p = parseText("const a = 35\u00B0 + 1 \u00B5m;");
  const auto& e = *p->file.decls[0].value;
  // `const a = 35° + 1 µm;`: `°` and `µ` are one column each.
  EXPECT_EQ(e.args[1]->span.col, 17);
  EXPECT_EQ(e.args[1]->span.endCol, 20);
}
