// The language server driven through a scripted session, as an editor would, on streams.
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

// GCC 12 at -O2 warns of a maybe-uninitialized std::string inside copies of std::variant
// built from initializer lists (a known false positive); the sanitizers run this file too.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "driver/Driver.h"
#include "ReadFile.h"
#include "lsp/Json.h"
#include "lsp/Server.h"

namespace fs = std::filesystem;
using gbx::lsp::Json;

namespace {

std::string frame(const Json& msg) {
  std::string body = msg.dump();
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

// Every message the server wrote, in order.
std::vector<Json> messagesOf(const std::string& out) {
  std::vector<Json> v;
  size_t i = 0;
  while ((i = out.find("Content-Length: ", i)) != std::string::npos) {
    size_t n = std::stoul(out.substr(i + 16));
    size_t body = out.find("\r\n\r\n", i) + 4;
    auto j = Json::parse(out.substr(body, n));
    EXPECT_TRUE(j.has_value()) << out.substr(body, n);
    if (j) v.push_back(*j);
    i = body + n;
  }
  return v;
}

Json request(int id, const char* method, Json params = Json::Object{}) {
  return Json::Object{{"jsonrpc", "2.0"}, {"id", id}, {"method", method}, {"params", std::move(params)}};
}
Json notify(const char* method, Json params = Json::Object{}) {
  return Json::Object{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
}
Json open(const std::string& uri, const std::string& text) {
  return notify("textDocument/didOpen",
                Json::Object{{"textDocument", Json::Object{{"uri", uri}, {"languageId", "gbx"}, {"version", 1}, {"text", text}}}});
}
Json change(const std::string& uri, const std::string& text, int version) {
  Json::Object whole, doc, params;
  whole["text"] = text;
  doc["uri"] = uri;
  doc["version"] = version;
  params["textDocument"] = Json(std::move(doc));
  Json::Array changes;
  changes.push_back(Json(std::move(whole)));
  params["contentChanges"] = Json(std::move(changes));
  return notify("textDocument/didChange", Json(std::move(params)));
}

} // namespace

TEST(Json, ParsesWritesAndRefusesWhatIsNotJson) {
  auto j = Json::parse(R"({"a": [1, 2.5, "x\u00e9\n", true, null], "b": {"c": -3e2}})");
  ASSERT_TRUE(j);
  EXPECT_EQ((*j)["a"].size(), 5u);
  EXPECT_EQ((*j)["a"].at(1).number(), 2.5);
  EXPECT_EQ((*j)["a"].at(2).string(), "x\xc3\xa9\n");
  EXPECT_EQ((*j)["b"]["c"].number(), -300);
  EXPECT_TRUE((*j)["missing"]["deeper"].isNull());  // lookups never throw
  EXPECT_EQ(Json::parse(j->dump())->dump(), j->dump());
  for (const char* bad : {"", "{", "[1,]", "{\"a\" 1}", "\"\\x\"", "nul", "1e999", "[1] 2", "\"\\ud800"})
    EXPECT_FALSE(Json::parse(bad)) << bad;
  std::string deep(100000, '[');
  EXPECT_FALSE(Json::parse(deep + std::string(100000, ']')));  // refused, not a stack overflow
}

TEST(Lsp, ScriptedSessionFromErrorsToAFixAndShutdown) {
  const std::string uri = "file:///tmp/lsp-session.gbx";
  const std::string broken = "gearbox G {\n  stage s: spur { pinion.z = 0; wheel.z = 40; normal_module = 3 mm; face_width = 30 mm; }\n}\n";
  // The fix, laid out by hand (and not as `gbxc fmt` would).
  const std::string fixed = "const m = 3 mm;\n"
                            "gearbox G {\n"
                            "  stage s: spur {\n"
                            "      pinion.z = 20;\n"
                            "    wheel.z = 40;\n"
                            "    normal_module = m;  face_width = 30 mm;\n"
                            "  }\n"
                            "  report { columns s.center_distance; }\n"
                            "}\n";
  const std::string laidOut = "const m = 3 mm;\n"
                              "gearbox G {\n"
                              "  stage s: spur {\n"
                              "    pinion.z = 20;\n"
                              "    wheel.z  = 40;\n"
                              "    normal_module = m;  face_width = 30 mm;\n"
                              "  }\n"
                              "  report { columns s.center_distance; }\n"
                              "}\n";
  auto pos = [](int line, int character) { return Json::Object{{"line", line}, {"character", character}}; };
  auto at = [&](int id, const char* method, Json position) {
    return frame(request(id, method, Json::Object{{"textDocument", Json::Object{{"uri", uri}}}, {"position", std::move(position)}}));
  };
  Json formatParams = Json::Object{{"textDocument", Json::Object{{"uri", uri}}},
                                   {"options", Json::Object{{"tabSize", 4}, {"insertSpaces", true}}}};
  std::string script = frame(request(1, "initialize", Json::Object{{"capabilities", Json::Object{}}})) +
                       frame(notify("initialized")) + frame(open(uri, broken)) + frame(change(uri, fixed, 2)) +
                       at(10, "textDocument/hover", pos(7, 21)) +              // s.center_distance in the report
                       at(11, "textDocument/definition", pos(5, 20)) +         // the `m` of normal_module = m
                       at(12, "textDocument/completion", pos(5, 39)) +         // after `face_width = 30 `
                       frame(request(13, "textDocument/formatting", formatParams)) +
                       frame(change(uri, laidOut, 3)) + frame(request(14, "textDocument/formatting", formatParams)) +
                       frame(change(uri, "gearbox G { require ratio = 2; }\n", 4)) +
                       frame(request(15, "textDocument/formatting", formatParams)) +
                       frame(request(2, "textDocument/unknownThing")) + "Content-Length: 7\r\n\r\n{nope!}" +
                       frame(request(3, "shutdown")) + frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 0);
  auto m = messagesOf(out.str());
  std::map<int, Json> byId;
  std::vector<Json> published, logged;
  for (const auto& x : m) {
    if (!x["id"].isNull()) byId[static_cast<int>(x["id"].number())] = x;
    if (x["method"].string() == "textDocument/publishDiagnostics") published.push_back(x["params"]);
    if (x["method"].string() == "window/logMessage") logged.push_back(x["params"]);
  }
  // initialize: full text synchronisation on open and change, and formatting.
  const Json& caps = byId[1]["result"]["capabilities"];
  EXPECT_EQ(caps["textDocumentSync"]["change"].number(), 1);
  EXPECT_TRUE(caps["textDocumentSync"]["openClose"].boolean());
  EXPECT_TRUE(caps["documentFormattingProvider"].boolean());
  // didOpen: the CLI's code and sentence, at the `0` (line 2, column 29 1-based).
  ASSERT_EQ(published.size(), 4u) << out.str();
  EXPECT_EQ(published[0]["uri"].string(), uri);
  const Json& d = published[0]["diagnostics"];
  ASSERT_EQ(d.size(), 1u) << published[0].dump();
  EXPECT_EQ(d.at(0)["code"].string(), "E0402");
  EXPECT_EQ(d.at(0)["severity"].number(), 1);
  EXPECT_EQ(d.at(0)["message"].string(), "`pinion.z` must be positive, got 0");
  EXPECT_EQ(d.at(0)["range"]["start"]["line"].number(), 1);
  EXPECT_EQ(d.at(0)["range"]["start"]["character"].number(), 29);
  EXPECT_EQ(d.at(0)["range"]["end"]["character"].number(), 30);
  // didChange to the fix: no diagnostics left.
  EXPECT_EQ(published[1]["diagnostics"].size(), 0u) << published[1].dump();
  // hover: what the centre distance is, and its value for the one design, m (z1 + z2) / 2.
  const std::string hover = byId[10]["result"]["contents"]["value"].string();
  EXPECT_NE(hover.find("center_distance"), std::string::npos) << hover;
  EXPECT_NE(hover.find("= 90.0000 mm"), std::string::npos) << hover;
  // definition: the const on line 0.
  EXPECT_EQ(byId[11]["result"]["uri"].string(), uri);
  EXPECT_EQ(byId[11]["result"]["range"]["start"]["line"].number(), 0);
  EXPECT_EQ(byId[11]["result"]["range"]["start"]["character"].number(), 6);
  // completion after a face width's number: lengths, millimetres first.
  const Json& items = byId[12]["result"]["items"];
  ASSERT_GT(items.size(), 2u) << byId[12].dump();
  std::vector<std::pair<std::string, std::string>> units;
  for (size_t i = 0; i < items.size(); ++i) units.push_back({items.at(i)["sortText"].string(), items.at(i)["label"].string()});
  std::sort(units.begin(), units.end());
  EXPECT_EQ(units.front().second, "mm");
  for (const auto& u : units) EXPECT_NE(u.second, "rad");
  // formatting: one edit from line 3 to the start of line 5; applied, it gives the layout.
  const Json& edits = byId[13]["result"];
  ASSERT_EQ(edits.size(), 1u) << byId[13].dump();
  EXPECT_EQ(edits.at(0)["range"]["start"]["line"].number(), 3);
  EXPECT_EQ(edits.at(0)["range"]["start"]["character"].number(), 0);
  EXPECT_EQ(edits.at(0)["range"]["end"]["line"].number(), 5);
  EXPECT_EQ(edits.at(0)["range"]["end"]["character"].number(), 0);
  size_t from = 0;
  for (int l = 0; l < 3; ++l) from = fixed.find('\n', from) + 1;
  size_t to = from;
  for (int l = 3; l < 5; ++l) to = fixed.find('\n', to) + 1;
  EXPECT_EQ(fixed.substr(0, from) + edits.at(0)["newText"].string() + fixed.substr(to), laidOut);
  // Laid out already: no edit. Syntax errors: no formatting, and the log says why.
  EXPECT_TRUE(byId[14]["result"].isArray());
  EXPECT_EQ(byId[14]["result"].size(), 0u);
  EXPECT_TRUE(byId[15]["result"].isNull());
  EXPECT_TRUE(byId[15]["error"].isNull());
  ASSERT_EQ(logged.size(), 1u);
  EXPECT_NE(logged[0]["message"].string().find("syntax errors"), std::string::npos);
  // An unknown request and a malformed message are answered; the server goes on.
  EXPECT_EQ(byId[2]["error"]["code"].number(), -32601);
  bool parseError = false;
  for (const auto& x : m) parseError = parseError || x["error"]["code"].number() == -32700;
  EXPECT_TRUE(parseError);
  EXPECT_TRUE(byId[3]["result"].isNull());
  EXPECT_TRUE(byId[3]["error"].isNull());
}

// Every spec, cut at a hundred places, sent as changes: the server answers each with
// diagnostics and never dies; exit without shutdown is status 1.
TEST(Lsp, SurvivesEveryTruncatedSpec) {
  std::string script = frame(request(1, "initialize"));
  const std::string uri = "file:///tmp/lsp-garbled.gbx";
  int changes = 0;
  for (const auto& e : fs::directory_iterator(fs::path(GBX_SOURCE_DIR) / "specs")) {
    std::ifstream f(e.path(), std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    std::string text = ss.str();
    for (int k = 1; k <= 100; ++k) script += frame(change(uri, text.substr(0, text.size() * static_cast<size_t>(k) / 100), ++changes));
  }
  script += frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 1);
  auto m = messagesOf(out.str());
  EXPECT_EQ(m.size(), static_cast<size_t>(changes) + 1);
  for (size_t i = 1; i < m.size(); ++i) EXPECT_EQ(m[i]["method"].string(), "textDocument/publishDiagnostics");
}

// Hover, completion, definition and document symbols on a spec of the repository.
TEST(Lsp, HoverCompletionDefinitionAndSymbols) {
  std::ifstream f(fs::path(GBX_SOURCE_DIR) / "specs" / "spur_resonance.gbx", std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  // The 0-based position of `what` (plus `k` characters) in the text.
  auto at = [&](const std::string& what, int k) {
    size_t i = text.find(what);
    EXPECT_NE(i, std::string::npos) << what;
    int line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(i), '\n'));
    size_t start = text.rfind('\n', i);
    int character = static_cast<int>(i - (start == std::string::npos ? 0 : start + 1)) + k;
    return Json::Object{{"line", line}, {"character", character}};
  };
  const std::string uri = "file://" + (fs::path(GBX_SOURCE_DIR) / "specs" / "spur_resonance.gbx").string();
  Json doc = Json::Object{{"uri", uri}};
  auto req = [&](int id, const char* method, Json position) {
    return frame(request(id, method, Json::Object{{"textDocument", doc}, {"position", std::move(position)}}));
  };
  std::string script = frame(request(1, "initialize")) + frame(open(uri, text)) + req(2, "textDocument/hover", at("normal_module", 2)) +
                       req(3, "textDocument/hover", at("harmonics = 10", 2)) + req(4, "textDocument/completion", at("face_width", 0)) +
                       req(5, "textDocument/definition", at("mesh on s1", 9)) +
                       req(6, "textDocument/definition", at("steel_42CrMo4", 3)) +
                       frame(request(7, "textDocument/documentSymbol", Json::Object{{"textDocument", doc}})) +
                       req(9, "textDocument/hover", at("steel_42CrMo4", 3)) + req(10, "textDocument/hover", at("mesh on s1", 9)) +
                       req(11, "textDocument/hover", at("mesh on s1", 1)) +
                       frame(request(8, "shutdown")) + frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 0);
  std::map<int, Json> byId;
  for (const auto& m : messagesOf(out.str()))
    if (!m["id"].isNull()) byId[static_cast<int>(m["id"].number())] = m["result"];
  EXPECT_TRUE(byId[1]["capabilities"]["hoverProvider"].boolean());
  EXPECT_EQ(byId[2]["contents"]["value"].string(), "**normal_module** — normal module\n\na length, in mm");
  EXPECT_NE(byId[3]["contents"]["value"].string().find("varying_stiffness.harmonics"), std::string::npos);
  // Inside a spur stage: its attributes, the per-gear ones by gear.
  std::set<std::string> labels;
  for (size_t i = 0; i < byId[4]["items"].size(); ++i) labels.insert(byId[4]["items"].at(i)["label"].string());
  for (const char* want : {"normal_module", "face_width", "pinion.z", "wheel.shift", "material"})
    EXPECT_TRUE(labels.count(want)) << want;
  EXPECT_FALSE(labels.count("ratio")) << "a derived quantity cannot be written";
  // `on s1` goes to the stage's name; a material to its declaration in the stdlib.
  EXPECT_EQ(byId[5]["uri"].string(), uri);
  EXPECT_EQ(byId[5]["range"]["start"]["line"].number(), 8);
  EXPECT_NE(byId[6]["uri"].string().find("stdlib/materials.gbx"), std::string::npos) << byId[6].dump();
  // Symbols: the gearbox, with its stage, scene and study inside.
  const Json& sym = byId[7];
  ASSERT_EQ(sym.size(), 1u) << sym.dump();
  EXPECT_EQ(sym.at(0)["name"].string(), "SpurResonance");
  std::vector<std::string> children;
  for (size_t i = 0; i < sym.at(0)["children"].size(); ++i) children.push_back(sym.at(0)["children"].at(i)["name"].string());
  EXPECT_EQ(children, (std::vector<std::string>{"s1", "mesh", "mesh_balance", "resonance", "resonance_balance"}));
  // Hover on a name: a material's properties, a stage's kind and bindings, a scene's effects.
  std::string material = byId[9]["contents"]["value"].string();
  EXPECT_NE(material.find("**material steel_42CrMo4**"), std::string::npos) << material;
  EXPECT_NE(material.find("sigma_hlim 1000 MPa"), std::string::npos) << material;
  EXPECT_NE(material.find("treatment nitrided"), std::string::npos) << material;
  std::string stage = byId[10]["contents"]["value"].string();
  EXPECT_NE(stage.find("**stage s1**: spur"), std::string::npos) << stage;
  std::string scene = byId[11]["contents"]["value"].string();
  EXPECT_NE(scene.find("**scene mesh** on s1"), std::string::npos) << scene;
  EXPECT_NE(scene.find("effects: "), std::string::npos) << scene;
}

// Hover on a const, where it is used: its value, as written and in SI.
TEST(Lsp, HoverShowsAConstsValue) {
  const std::string uri = "file:///tmp/lsp-const.gbx";
  const std::string text =
      "const m = 3 mm;\ngearbox G { stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = m; face_width = 30 mm; } }\n";
  Json where = Json::Object{{"line", 1}, {"character", static_cast<int>(text.find("= m;") - text.find('\n') - 1 + 2)}};
  std::string script = frame(request(1, "initialize")) + frame(open(uri, text)) +
                       frame(request(2, "textDocument/hover",
                                     Json::Object{{"textDocument", Json::Object{{"uri", uri}}}, {"position", where}})) +
                       frame(request(3, "shutdown")) + frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 0);
  auto m = messagesOf(out.str());
  ASSERT_GE(m.size(), 3u);
  EXPECT_EQ(m[2]["result"]["contents"]["value"].string(), "**const m** = 3 mm (0.003 m in SI)") << m[2].dump();
}

namespace {

// The answers to a session on one document: the requests' results by id.
std::map<int, Json> answers(const std::string& uri, const std::string& text, const std::vector<std::pair<const char*, Json>>& requests) {
  std::string script = frame(request(1, "initialize")) + frame(open(uri, text));
  for (size_t i = 0; i < requests.size(); ++i)
    script += frame(request(static_cast<int>(i) + 2, requests[i].first,
                            Json::Object{{"textDocument", Json::Object{{"uri", uri}}}, {"position", requests[i].second}}));
  script += frame(request(1000, "shutdown")) + frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 0);
  std::map<int, Json> byId;
  for (const auto& m : messagesOf(out.str()))
    if (!m["id"].isNull()) byId[static_cast<int>(m["id"].number())] = m["result"];
  return byId;
}

// The 0-based position just after `what` (its n-th occurrence, from 0) in `text`, less `back` characters.
Json after(const std::string& text, const std::string& what, int back = 0, int n = 0) {
  size_t i = text.find(what);
  for (int k = 0; k < n && i != std::string::npos; ++k) i = text.find(what, i + 1);
  EXPECT_NE(i, std::string::npos) << what;
  if (i == std::string::npos) return Json::Object{{"line", 0}, {"character", 0}};
  i += what.size() - static_cast<size_t>(back);
  int line = static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(i), '\n'));
  size_t start = text.rfind('\n', i - 1);
  return Json::Object{{"line", line}, {"character", static_cast<int>(i - (start == std::string::npos ? 0 : start + 1))}};
}

// A completion's labels, in the order of their sortText.
std::vector<std::string> sortedLabels(const Json& result) {
  std::vector<std::pair<std::string, std::string>> v;
  for (size_t i = 0; i < result["items"].size(); ++i)
    v.emplace_back(result["items"].at(i)["sortText"].string(), result["items"].at(i)["label"].string());
  std::stable_sort(v.begin(), v.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> labels;
  for (const auto& [_, l] : v) labels.push_back(l);
  return labels;
}

bool has(const std::vector<std::string>& v, const std::string& x) { return std::find(v.begin(), v.end(), x) != v.end(); }

std::string readSpec(const char* name) {
  std::ifstream f(fs::path(GBX_SOURCE_DIR) / "specs" / name, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

} // namespace

// After a number, units: those of the dimension of what the statement sets (a stage
// attribute, an effect parameter, a scene setting), the display unit first; all units where
// that is unknown; none for a count; and no unit where none can stand.
TEST(Lsp, CompletesUnitsAfterANumber) {
  const std::string uri = "file:///tmp/lsp-units.gbx";
  const std::string text =
      "gearbox G {\n"
      "  stage s: helical {\n"
      "    pinion.z = 20; wheel.z = 40;\n"
      "    normal_module = 16 m\n"
      "    helix_angle = 8 deg;\n"
      "    face_width in 80..120 mm;  // about 16 mm\n"
      "    rating { life = 20000 h; }\n"
      "  }\n"
      "  operating { input_speed = 1500 rpm; input_torque = 2 kN*m; }\n"
      "  scene v on s {\n"
      "    effects { damping { ratio = 0.07; } backlash { clearance = 100 um; } }\n"
      "    ramp = 0.1 s;\n"
      "  }\n"
      "  require s.center_distance < 400 mm;\n"
      "}\n";
  auto r = answers(uri, text,
                   {{"textDocument/completion", after(text, "normal_module = 16 m")},
                    {"textDocument/completion", after(text, "helix_angle = 8 ")},
                    {"textDocument/completion", after(text, "80..120 ")},
                    {"textDocument/completion", after(text, "ramp = 0.1 ")},
                    {"textDocument/completion", after(text, "clearance = 100 ")},
                    {"textDocument/completion", after(text, "pinion.z = 20")},
                    {"textDocument/completion", after(text, "< 400 ")},
                    {"textDocument/completion", after(text, "input_torque = 2 kN*")},
                    {"textDocument/completion", after(text, "    face_width", 10)},
                    {"textDocument/completion", after(text, "about 16 ")},
                    {"textDocument/completion", after(text, "life = 20000 ")}});
  // `16 m|`: lengths, mm first, the typed `m` replaced.
  auto length = sortedLabels(r[2]);
  ASSERT_FALSE(length.empty()) << r[2].dump();
  EXPECT_EQ(length.front(), "mm");
  for (const char* want : {"m", "um", "cm"}) EXPECT_TRUE(has(length, want)) << want;
  for (const char* not_ : {"rad", "deg", "s", "N", "%"}) EXPECT_FALSE(has(length, not_)) << not_;
  const Json& mm = r[2]["items"].at(0);
  EXPECT_EQ(mm["kind"].number(), 11);
  EXPECT_EQ(mm["detail"].string(), "a length");
  EXPECT_EQ(mm["textEdit"]["range"]["start"]["character"].number(), after(text, "normal_module = 16 m", 1)["character"].number());
  EXPECT_EQ(mm["textEdit"]["range"]["end"]["character"].number(), after(text, "normal_module = 16 m")["character"].number());
  // An angle, a domain's bound, a scene's time (in mesh periods too), an effect's length.
  auto angle = sortedLabels(r[3]);
  ASSERT_FALSE(angle.empty()) << r[3].dump();
  EXPECT_EQ(angle.front(), "deg");
  EXPECT_TRUE(has(angle, "rad"));
  EXPECT_FALSE(has(angle, "mm"));
  EXPECT_EQ(sortedLabels(r[4]).front(), "mm");
  auto time = sortedLabels(r[5]);
  ASSERT_FALSE(time.empty()) << r[5].dump();
  EXPECT_EQ(time.front(), "s");
  EXPECT_TRUE(has(time, "mesh_periods") && has(time, "ms"));
  EXPECT_FALSE(has(time, "mm"));
  auto clearance = sortedLabels(r[6]);
  EXPECT_TRUE(has(clearance, "um") && !has(clearance, "rpm")) << r[6].dump();
  // A tooth count takes no unit.
  EXPECT_EQ(r[7]["items"].size(), 0u) << r[7].dump();
  // A rule's bound, or after `kN*`: any unit.
  for (int id : {8, 9}) {
    auto any = sortedLabels(r[id]);
    EXPECT_TRUE(has(any, "mm") && has(any, "rad") && has(any, "kW") && has(any, "mesh_periods")) << r[id].dump();
  }
  // The start of a statement, and a comment: no units, the attributes as before.
  for (int id : {10, 11}) {
    auto labels = sortedLabels(r[id]);
    EXPECT_FALSE(has(labels, "mm")) << r[id].dump();
  }
  EXPECT_TRUE(has(sortedLabels(r[10]), "normal_module")) << r[10].dump();
  // A block's setting (`rating.life`): hours are its hint, second after seconds.
  auto life = sortedLabels(r[12]);
  ASSERT_GE(life.size(), 2u) << r[12].dump();
  EXPECT_EQ(life[0], "s");
  EXPECT_EQ(life[1], "h");
}

// Hover on a quantity of MarineReducer (its design fixed: one candidate) shows its value
// there, the value `gbxc solve` reports for the same stage; not in MarineReducerOptimised,
// whose ranges leave the design to the search, nor beside a number as written.
TEST(Lsp, HoverShowsAQuantitysValueForAFixedDesign) {
  const std::string text = readSpec("marine_reducer.gbx");
  // The solve of MarineReducer's own stage and operating point, with no scene.
  auto block = [&](const std::string& head) {
    size_t b = text.find(head);
    EXPECT_NE(b, std::string::npos) << head;
    if (b == std::string::npos) return std::string();
    size_t e = text.find('{', b);
    for (int depth = 0; e < text.size(); ++e) {
      depth += text[e] == '{' ? 1 : text[e] == '}' ? -1 : 0;
      if (depth == 0) break;
    }
    return text.substr(b, e + 1 - b);
  };
  fs::path dir = fs::temp_directory_path() / ("gbxc-lsp-value-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ofstream f(dir / "marine.gbx");
    // Without the scene, its K_v is method B's.
    std::string stage = block("stage main");
    size_t kv = stage.find("dynamic_factor = scene vibration;");
    if (kv != std::string::npos) stage.erase(kv, std::string("dynamic_factor = scene vibration;").size());
    f << "import materials;\ngearbox MarineReducer {\n" << stage << "\n" << block("operating")
      << "\nreport { columns main.center_distance, main.mass, main.eps_beta, main.face_width; }\n}\n";
  }
  std::ostringstream solved, err;
  ASSERT_EQ(gbx::driver::run({"solve", (dir / "marine.gbx").string(), "--format", "json", "--quiet", "--no-timings"}, solved, err), 0)
      << err.str();
  auto json = Json::parse(solved.str());
  ASSERT_TRUE(json) << solved.str();
  const Json& values = (*json)["gearboxes"].at(0)["candidates"].at(0)["values"];
  double centerDistance = values["main.center_distance"].number(), mass = values["main.mass"].number();
  EXPECT_NEAR(centerDistance, 0.855, 0.001);  // about 855 mm, 4.6 t (the spec's expectation)
  EXPECT_NEAR(mass, 4600, 100);

  const std::string uri = "file://" + (fs::path(GBX_SOURCE_DIR) / "specs" / "marine_reducer.gbx").string();
  auto r = answers(uri, text,
                   {{"textDocument/hover", after(text, "main.center_distance", 3)},
                    {"textDocument/hover", after(text, "main.mass,", 3)},
                    {"textDocument/hover", after(text, "main.eps_beta", 3)},
                    {"textDocument/hover", after(text, "    face_width", 3)},
                    {"textDocument/hover", after(text, "relative(main.mass", 3)},
                    {"textDocument/hover", after(text, "normal_module", 3)},
                    {"textDocument/hover", after(text, "require main.ratio", 3)}});
  auto hover = [&](int id) { return r[id]["contents"]["value"].string(); };
  auto shows = [&](int id, const std::string& what) {
    EXPECT_NE(hover(id).find(what), std::string::npos) << "want `" << what << "` in:\n" << hover(id);
  };
  shows(2, fmt::format("= {:.4f} mm (", centerDistance * 1e3));
  shows(2, "for the design of MarineReducer");
  shows(2, "**main.center_distance** — centre distance");
  shows(3, fmt::format("= {:.4f} kg for the design of MarineReducer", mass));
  shows(4, fmt::format("= {:.4f} for the design of MarineReducer", values["main.eps_beta"].number()));
  // A stage attribute computed from others, on the left of its assignment.
  shows(5, "**face_width** — face width");
  shows(5, fmt::format("= {:.4f} mm", values["main.face_width"].number() * 1e3));
  // The optimised gearbox searches: its quantities have no one value, the hover says what
  // they are.
  shows(6, "**main.mass** — gear-pair mass");
  shows(8, "**main.ratio** — reduction");
  EXPECT_EQ(hover(6).find("for the design of"), std::string::npos) << hover(6);
  EXPECT_EQ(hover(8).find("for the design of"), std::string::npos) << hover(8);
  // A number as written: its meaning only.
  EXPECT_EQ(hover(7), "**normal_module** — normal module\n\na length, in mm");
  fs::remove_all(dir);
}

// Hover and completion on every prefix of a spec of a fixed design: an answer each time,
// whether the text parses or not.
TEST(Lsp, HoverAndCompletionAnswerOnAHalfTypedSpec) {
  const std::string full = readSpec("marine_reducer.gbx");
  const std::string uri = "file:///tmp/lsp-half-typed.gbx";
  std::string script = frame(request(1, "initialize"));
  int id = 1;
  for (int k = 1; k <= 40; ++k) {
    std::string text = full.substr(0, full.size() * static_cast<size_t>(k) / 40);
    script += frame(change(uri, text, k));
    for (const char* at : {"main.center_distance", "16 mm", "face_width", "1.15"}) {
      Json where = text.find(at) == std::string::npos ? Json(Json::Object{{"line", 1000}, {"character", 1000}}) : after(text, at, 1);
      for (const char* method : {"textDocument/hover", "textDocument/completion"})
        script += frame(request(++id, method, Json::Object{{"textDocument", Json::Object{{"uri", uri}}}, {"position", where}}));
    }
  }
  script += frame(request(++id, "shutdown")) + frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 0);
  std::set<int> answered;
  for (const auto& m : messagesOf(out.str()))
    if (!m["id"].isNull()) answered.insert(static_cast<int>(m["id"].number()));
  EXPECT_EQ(answered.size(), static_cast<size_t>(id));
}

// An attribute that needs itself twice over through a computed quantity (the mass reads the
// face width; sema sees only cycles among given attributes) has no value, and asking for one
// answers at once instead of recursing ever wider; what does not depend on it still has its
// value.
TEST(Lsp, HoverOnASelfReferringAttributeAnswers) {
  const std::string uri = "file:///tmp/lsp-self.gbx";
  const std::string text =
      "import materials;\n"
      "gearbox G {\n"
      "  stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = 3 mm; material = steel_42CrMo4;\n"
      "    face_width = (mass + mass) * 1 mm/kg; }\n"
      "  report { columns s.face_width, s.center_distance; }\n"
      "}\n";
  auto r = answers(uri, text,
                   {{"textDocument/hover", after(text, "columns s.face_width", 2)},
                    {"textDocument/hover", after(text, "s.center_distance", 2)},
                    {"textDocument/hover", after(text, "    face_width", 2)}});
  EXPECT_EQ(r[2]["contents"]["value"].string(), "**s.face_width** — face width\n\na length, in mm") << r[2].dump();
  EXPECT_NE(r[3]["contents"]["value"].string().find("= 90.0000 mm (0.09 m in SI) for the design of G"), std::string::npos) << r[3].dump();
  EXPECT_EQ(r[4]["contents"]["value"].string(), "**face_width** — face width\n\na length, in mm");
}

// Whatever block an assignment stands in, the hover says what it sets: a stage's attribute
// named from the gearbox (the stage inherited), a rating input in nested blocks, an
// operating setting, an accuracy setting; a const shows its value as written and in SI.
TEST(Lsp, HoverSaysWhatEveryTargetIs) {
  const std::string uri = "file:///tmp/lsp-targets.gbx";
  const std::string text =
      "const life_h = 20000 h;\n"
      "gearbox A {\n"
      "  stage main: helical {\n"
      "    pinion.z = 21;  wheel.z = 83;  normal_module = 16 mm;  helix_angle = 8 deg;  face_width = 200 mm;\n"
      "    rating { life = life_h; lubricant { viscosity_40 = 150 mm^2/s; } }\n"
      "  }\n"
      "  operating { input_speed = 800 rpm; input_torque = 91670 N*m; }\n"
      "}\n"
      "gearbox B extends A {\n"
      "  main.pinion.z in 17..25;\n"
      "  require main.ratio > 3;\n"
      "  scene v on main { effects { damping { ratio = 0.07; } } accuracy { rtol = 1e-6; } duration = 1 s; }\n"
      "}\n";
  auto r = answers(uri, text,
                   {{"textDocument/hover", after(text, "main.pinion.z in", 5)},
                    {"textDocument/hover", after(text, "life =", 3)},
                    {"textDocument/hover", after(text, "viscosity_40", 2)},
                    {"textDocument/hover", after(text, "input_torque", 2)},
                    {"textDocument/hover", after(text, "rtol", 1)},
                    {"textDocument/hover", after(text, "main.ratio", 2)},
                    {"textDocument/hover", after(text, "= life_h", 2)}});
  auto value = [&](int id) { return r[id]["contents"]["value"].string(); };
  EXPECT_EQ(value(2), "**main.pinion.z** — tooth count\n\na plain number");
  EXPECT_EQ(value(3).rfind("**rating.life** — required service life", 0), 0u) << value(3);
  EXPECT_EQ(value(4).rfind("**rating.lubricant.viscosity_40** —", 0), 0u) << value(4);
  EXPECT_EQ(value(5).rfind("**operating.input_torque** — input torque\n\na torque", 0), 0u) << value(5);
  EXPECT_EQ(value(6).rfind("**accuracy.rtol** —", 0), 0u) << value(6);
  EXPECT_EQ(value(7).rfind("**main.ratio** — reduction", 0), 0u) << value(7);
  EXPECT_EQ(value(7).find("for the design of"), std::string::npos) << value(7);  // B searches
  EXPECT_EQ(value(8), "**const life_h** = 20000 h (72000000 s in SI)");
}

// Completion after `import`, after `stage x:` and after a dot offers what can stand there:
// modules, kinds, what the dotted name holds (a gear's attributes, a nested block's, an
// inherited stage's from the gearbox).
TEST(Lsp, CompletesWhatCanStandThere) {
  const std::string uri = "file:///tmp/lsp-complete.gbx";
  // A spec with one place being typed, as an editor sends it.
  auto labels = [&](const std::string& typing, const std::string& where) {
    std::string text = "import materials;\n" + std::string(where == "import" ? "import \n" : "") +
                       "gearbox A {\n"
                       "  stage main: helical {\n"
                       "    pinion.z = 21;  wheel.z = 83;  normal_module = 16 mm;  face_width = 200 mm;\n" +
                       std::string(where == "stage" ? "    " + typing + "\n" : "") +
                       "  }\n"
                       "}\n"
                       "gearbox B extends A {\n" +
                       std::string(where == "gearbox" ? "  " + typing + "\n" : "") + "}\n";
    std::string at = where == "import" ? "import " : typing;
    auto r = answers(uri, text, {{"textDocument/completion", after(text, at, 0, where == "import" ? 1 : 0)}});
    std::set<std::string> out;
    for (size_t i = 0; i < r[2]["items"].size(); ++i) out.insert(r[2]["items"].at(i)["label"].string());
    return out;
  };
  EXPECT_EQ(labels("", "import"), (std::set<std::string>{"gleason", "klingelnberg", "materials", "modules", "oils"}));
  auto gear = labels("pinion.", "stage");
  EXPECT_TRUE(gear.count("z") && gear.count("shift"));
  EXPECT_FALSE(gear.count("pinion.z") || gear.count("normal_module"));
  EXPECT_EQ(labels("rating.lubricant.", "stage"), (std::set<std::string>{"base", "density", "fzg_load_stage", "micropitting_load_stage",
                                                                       "oil_temperature", "supply", "viscosity_100", "viscosity_40"}));
  auto kinds = labels("stage extra: ", "gearbox");
  EXPECT_TRUE(kinds.count("spur") && kinds.count("planetary") && kinds.count("helical"));
  EXPECT_FALSE(kinds.count("gearbox"));
  auto inherited = labels("require main.", "gearbox");
  EXPECT_TRUE(inherited.count("ratio") && inherited.count("center_distance") && inherited.count("pinion.z"));
  EXPECT_FALSE(inherited.count("gearbox"));
  auto wheel = labels("require main.wheel.", "gearbox");
  EXPECT_TRUE(wheel.count("z") && wheel.count("shift"));
  EXPECT_FALSE(wheel.count("normal_module"));
}

// Units after a number at gearbox level for a stage the gearbox inherits: the stage's kind
// comes from the gearbox it extends.
TEST(Lsp, CompletesUnitsForAnInheritedStage) {
  const std::string uri = "file:///tmp/lsp-units-inherited.gbx";
  const std::string text = "gearbox A {\n"
                           "  stage main: helical { pinion.z = 21; wheel.z = 83; normal_module = 16 mm; face_width = 200 mm; }\n"
                           "}\n"
                           "gearbox B extends A {\n"
                           "  main.helix_angle in 8..15 \n"
                           "}\n";
  auto r = answers(uri, text, {{"textDocument/completion", after(text, "8..15 ")}});
  auto labels = sortedLabels(r[2]);
  ASSERT_FALSE(labels.empty());
  EXPECT_EQ(labels.front(), "deg");
  EXPECT_EQ(std::find(labels.begin(), labels.end(), "mm"), labels.end());
}

// Formatting counts lines as the editor does: a CRLF document laid out needs no edit, a
// CRLF document that is not gets an edit over its changed line only, and one with a lone CR
// (a line end for the editor, not for the language) is replaced whole.
TEST(Lsp, FormattingCountsLinesAsTheEditorDoes) {
  auto edits = [](const std::string& text) {
    return answers("file:///tmp/lsp-eol.gbx", text, {{"textDocument/formatting", Json::Object{}}})[2];
  };
  Json same = edits("const a = 1;\r\nconst b = 2;\r\n");
  EXPECT_TRUE(same.isArray() && same.size() == 0u) << same.dump();

  Json one = edits("const a=1;\r\nconst b = 2;\r\n");
  ASSERT_EQ(one.size(), 1u) << one.dump();
  EXPECT_EQ(one.at(0)["range"]["start"]["line"].number(), 0);
  EXPECT_EQ(one.at(0)["range"]["end"]["line"].number(), 1);
  EXPECT_EQ(one.at(0)["range"]["end"]["character"].number(), 0);
  EXPECT_EQ(one.at(0)["newText"].string(), "const a = 1;\n");

  Json whole = edits("const a=1;\rconst b = 2;\nconst c=3;\n");
  ASSERT_EQ(whole.size(), 1u) << whole.dump();
  EXPECT_EQ(whole.at(0)["range"]["start"]["line"].number(), 0);
  EXPECT_EQ(whole.at(0)["range"]["start"]["character"].number(), 0);
  EXPECT_EQ(whole.at(0)["range"]["end"]["line"].number(), 3);
  EXPECT_EQ(whole.at(0)["range"]["end"]["character"].number(), 0);
  EXPECT_EQ(whole.at(0)["newText"].string(), "const a = 1;  const b = 2;\nconst c = 3;\n");
}

// Go to definition on an import: the file it loaded, a stdlib module or a path from the
// document's folder.
TEST(Lsp, DefinitionOfAnImportIsItsFile) {
  const fs::path doc = fs::path(GBX_GOLDEN_DIR) / "imports" / "relative_import.gbx";
  std::ifstream f(doc, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  auto r = answers("file://" + doc.string(), text,
                   {{"textDocument/definition", after(text, "\"lib/sh")}, {"textDocument/definition", after(text, "import mat")}});
  EXPECT_EQ(fs::weakly_canonical(r[2]["uri"].string().substr(7)), fs::weakly_canonical(doc.parent_path() / "lib" / "shop.gbx")) << r[2].dump();
  EXPECT_EQ(r[2]["range"]["start"]["line"].number(), 0);
  EXPECT_EQ(fs::path(r[3]["uri"].string()).filename(), "materials.gbx") << r[3].dump();
}

// A shaft's name shows its gears, bearings and notches; a shaft quantity in a rule what it is and, for
// a fixed design, its value there.
TEST(Lsp, HoverOnAShaftAndItsQuantities) {
  const std::string text = readFile(fs::path(GBX_SOURCE_DIR) / "tests" / "golden" / "solve" / "shaft_input.gbx");
  const std::string uri = "file://" + (fs::path(GBX_SOURCE_DIR) / "tests" / "golden" / "solve" / "shaft_input.gbx").string();
  auto r = answers(uri, text,
                   {{"textDocument/hover", after(text, "shaft inp", 0)},
                    {"textDocument/hover", after(text, "require input.B.li", 0)}});
  auto hover = [&](int id) { return r[id]["contents"]["value"].string(); };
  EXPECT_NE(hover(2).find("**shaft input**"), std::string::npos) << hover(2);
  EXPECT_NE(hover(2).find("bearing A at 30 mm"), std::string::npos) << hover(2);
  EXPECT_NE(hover(2).find("gear hs.pinion at 175 mm"), std::string::npos) << hover(2);
  EXPECT_NE(hover(2).find("notch shoulder at 60 mm"), std::string::npos) << hover(2);
  EXPECT_NE(hover(3).find("ISO 281 basic rating life"), std::string::npos) << hover(3);
}
