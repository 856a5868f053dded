// The Python module's overrides, written as variants in the language: the front end checks
// each as it checks a spec, and the report keeps the spec's gearbox names.
#include <gtest/gtest.h>

#include "driver/Driver.h"
#include "python/Overrides.h"

using namespace gbx;

namespace {

const char* kSpec = R"(gearbox Small {
  stage s1: spur {
    pinion.z in 18..20;  wheel.z in 40..44;
    normal_module = 2 mm;  pressure_angle = 20 deg;  face_width = 20 mm;
  }
  operating { input_speed = 1500 rpm; power = 10 kW; }
}
)";

std::unique_ptr<driver::Compilation> compiled(const python::Overridden& o) {
  auto c = driver::compileText("small.gbx", o.text);
  if (c->ok()) python::keepVariants(c->program, o.variants);
  return c;
}

TEST(Overrides, AVariantPerGearboxUnderItsName) {
  auto o = python::withOverrides(kSpec, {"Small"}, {{"s1.face_width", "25 mm"}, {"operating.power", "12 kW"}});
  ASSERT_TRUE(o.error.empty()) << o.error;
  EXPECT_NE(o.text.find("s1.face_width = 25 mm;"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("operating { power = 12 kW; }"), std::string::npos) << o.text;
  auto c = compiled(o);
  ASSERT_TRUE(c->ok()) << c->diags.renderText(c->sources);
  ASSERT_EQ(c->program.gearboxes.size(), 1u);
  EXPECT_EQ(c->program.gearboxes[0].name, "Small");
  EXPECT_EQ(c->program.gearboxes[0].baseline, "");
  // The program is the spec with the values written in.
  std::string written = kSpec;
  written.replace(written.find("face_width = 20 mm"), 18, "face_width = 25 mm");
  written.replace(written.find("power = 10 kW"), 13, "power = 12 kW");
  auto w = driver::compileText("small.gbx", written);
  ASSERT_TRUE(w->ok());
  // The two programs print alike but for where the value came from: the variant is
  // flattened by the front end, and its values say they are overrides.
  std::string a = ir::print(c->program), b = ir::print(w->program);
  auto at = a.find("[override]");
  ASSERT_NE(at, std::string::npos) << a;
  a.replace(at, 10, "[stage]");
  EXPECT_EQ(a, b);
}

TEST(Overrides, TheFrontEndRefusesAWrongNameOrDimension) {
  auto o = python::withOverrides(kSpec, {"Small"}, {{"s1.nothing", "25 mm"}, {"operating.power", "12 m"}});
  ASSERT_TRUE(o.error.empty());
  auto c = compiled(o);
  ASSERT_FALSE(c->ok());
  std::string text = c->diags.renderText(c->sources);
  EXPECT_NE(text.find("E0211"), std::string::npos) << text;
  EXPECT_NE(text.find("E0302"), std::string::npos) << text;
}

TEST(Overrides, OnePathAndOneValueEach) {
  EXPECT_FALSE(python::withOverrides(kSpec, {"Small"}, {{"s1..face_width", "25 mm"}}).error.empty());
  EXPECT_FALSE(python::withOverrides(kSpec, {"Small"}, {{"1s.face_width", "25 mm"}}).error.empty());
  EXPECT_FALSE(python::withOverrides(kSpec, {"Small"}, {{"s1.face_width", "25 mm; require false"}}).error.empty());
  EXPECT_FALSE(python::withOverrides(kSpec, {"Small"}, {{"s1.face_width", "} gearbox X {"}}).error.empty());
  EXPECT_FALSE(python::withOverrides(kSpec, {"Small"}, {{"s1.face_width", "  "}}).error.empty());
  EXPECT_TRUE(python::withOverrides(kSpec, {"Small"}, {{"s1.pinion.shift", "0.2"}}).error.empty());
}

} // namespace
