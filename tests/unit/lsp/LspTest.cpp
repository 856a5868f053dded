// The language server driven through a scripted session, as an editor would, on streams.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

// GCC 12 at -O2 warns of a maybe-uninitialized std::string inside copies of std::variant
// built from initializer lists (a known false positive); the sanitizers run this file too.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

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
  const std::string fixed = "gearbox G {\n  stage s: spur { pinion.z = 20; wheel.z = 40; normal_module = 3 mm; face_width = 30 mm; }\n}\n";
  std::string script = frame(request(1, "initialize", Json::Object{{"capabilities", Json::Object{}}})) +
                       frame(notify("initialized")) + frame(open(uri, broken)) + frame(change(uri, fixed, 2)) +
                       frame(request(2, "textDocument/unknownThing")) + "Content-Length: 7\r\n\r\n{nope!}" +
                       frame(request(3, "shutdown")) + frame(notify("exit"));
  std::istringstream in(script);
  std::ostringstream out;
  EXPECT_EQ(gbx::lsp::serve(in, out), 0);
  auto m = messagesOf(out.str());
  ASSERT_EQ(m.size(), 6u) << out.str();
  // initialize: full text synchronisation on open and change.
  EXPECT_EQ(m[0]["id"].number(), 1);
  EXPECT_EQ(m[0]["result"]["capabilities"]["textDocumentSync"]["change"].number(), 1);
  EXPECT_TRUE(m[0]["result"]["capabilities"]["textDocumentSync"]["openClose"].boolean());
  // didOpen: the CLI's code and sentence, at the `0` (line 2, column 29 1-based).
  EXPECT_EQ(m[1]["method"].string(), "textDocument/publishDiagnostics");
  EXPECT_EQ(m[1]["params"]["uri"].string(), uri);
  const Json& d = m[1]["params"]["diagnostics"];
  ASSERT_EQ(d.size(), 1u) << m[1].dump();
  EXPECT_EQ(d.at(0)["code"].string(), "E0402");
  EXPECT_EQ(d.at(0)["severity"].number(), 1);
  EXPECT_EQ(d.at(0)["message"].string(), "`pinion.z` must be positive, got 0");
  EXPECT_EQ(d.at(0)["range"]["start"]["line"].number(), 1);
  EXPECT_EQ(d.at(0)["range"]["start"]["character"].number(), 29);
  EXPECT_EQ(d.at(0)["range"]["end"]["character"].number(), 30);
  // didChange to the fix: no diagnostics left.
  EXPECT_EQ(m[2]["params"]["diagnostics"].size(), 0u) << m[2].dump();
  // An unknown request and a malformed message are answered; the server goes on.
  EXPECT_EQ(m[3]["error"]["code"].number(), -32601);
  EXPECT_EQ(m[4]["error"]["code"].number(), -32700);
  EXPECT_EQ(m[5]["id"].number(), 3);
  EXPECT_TRUE(m[5]["result"].isNull());
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
  EXPECT_EQ(children, (std::vector<std::string>{"s1", "mesh", "resonance"}));
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
  EXPECT_EQ(m[2]["result"]["contents"]["value"].string(), "**const m** = 3 mm (0.003 in SI)") << m[2].dump();
}
