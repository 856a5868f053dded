#include "lsp/Server.h"

#include <istream>
#include <map>
#include <ostream>
#include <string>

#include <fmt/format.h>

#include "driver/Driver.h"
#include "lsp/Json.h"

namespace gbx::lsp {

namespace {

constexpr size_t kMaxMessage = 64u << 20;  // a larger Content-Length is refused, not read

// One framed message; nullopt at the end of the stream. `bad` is set for a frame that
// cannot be read (no or an absurd Content-Length): the stream is then out of step.
std::optional<std::string> readMessage(std::istream& in, bool& bad) {
  size_t length = 0;
  bool sawLength = false;
  std::string line;
  while (true) {
    if (!std::getline(in, line)) return std::nullopt;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) {
      if (sawLength) break;
      continue;  // blank lines between messages
    }
    const std::string key = "Content-Length:";
    if (line.size() > key.size() && line.compare(0, key.size(), key) == 0) {
      try {
        unsigned long long n = std::stoull(line.substr(key.size()));
        if (n > kMaxMessage) {
          bad = true;
          return std::nullopt;
        }
        length = static_cast<size_t>(n);
        sawLength = true;
      } catch (...) {
        bad = true;
        return std::nullopt;
      }
    }
  }
  std::string body(length, '\0');
  in.read(body.data(), static_cast<std::streamsize>(length));
  if (static_cast<size_t>(in.gcount()) != length) return std::nullopt;
  return body;
}

void send(std::ostream& out, const Json& message) {
  std::string body = message.dump();
  out << "Content-Length: " << body.size() << "\r\n\r\n" << body << std::flush;
}

Json response(const Json& id, Json result) { return Json::Object{{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}}; }

Json error(const Json& id, int code, std::string message) {
  return Json::Object{{"jsonrpc", "2.0"}, {"id", id},
                      {"error", Json::Object{{"code", code}, {"message", std::move(message)}}}};
}

// file:///a/b%20c.gbx -> /a/b c.gbx (what imports resolve against and diagnostics name).
std::string pathOf(const std::string& uri) {
  std::string p = uri.rfind("file://", 0) == 0 ? uri.substr(7) : uri;
  std::string out;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i] == '%' && i + 2 < p.size() && std::isxdigit(static_cast<unsigned char>(p[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(p[i + 2]))) {
      out += static_cast<char>(std::stoi(p.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += p[i];
    }
  }
  return out.empty() ? "untitled.gbx" : out;
}

// UTF-16 code units before the code point at `col` (1-based) of `line`: LSP's default
// position encoding.
int utf16Column(const std::string& line, int col) {
  int units = 0, points = 0;
  for (size_t i = 0; i < line.size() && points < col - 1;) {
    unsigned char c = static_cast<unsigned char>(line[i]);
    size_t len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 1;
    units += len == 4 ? 2 : 1;
    ++points;
    i += len;
  }
  return units + std::max(0, col - 1 - points);  // past the end: one unit a column
}

class Server {
public:
  explicit Server(std::ostream& out) : out_(out) {}

  // Returns true when the server should stop (after `exit`).
  bool handle(const Json& msg) {
    const std::string& method = msg["method"].string();
    const Json& id = msg["id"];
    bool request = !id.isNull();
    const Json& params = msg["params"];
    if (method == "initialize") {
      Json::Object caps{{"textDocumentSync", Json::Object{{"openClose", true}, {"change", 1}}}};
      send(out_, response(id, Json::Object{{"capabilities", caps},
                                           {"serverInfo", Json::Object{{"name", "gbxc"}, {"version", GBX_VERSION}}}}));
    } else if (method == "shutdown") {
      shutdown_ = true;
      send(out_, response(id, Json()));
    } else if (method == "exit") {
      return true;
    } else if (method == "textDocument/didOpen") {
      const Json& doc = params["textDocument"];
      docs_[doc["uri"].string()] = doc["text"].string();
      publish(doc["uri"].string());
    } else if (method == "textDocument/didChange") {
      const Json& changes = params["contentChanges"];
      // Full synchronisation: the last change holds the whole text.
      if (changes.size() > 0) {
        const std::string& uri = params["textDocument"]["uri"].string();
        docs_[uri] = changes.at(changes.size() - 1)["text"].string();
        publish(uri);
      }
    } else if (method == "textDocument/didClose") {
      const std::string& uri = params["textDocument"]["uri"].string();
      docs_.erase(uri);
      send(out_, notification("textDocument/publishDiagnostics", Json::Object{{"uri", uri}, {"diagnostics", Json::Array{}}}));
    } else if (request) {
      send(out_, error(id, -32601, fmt::format("method `{}` is not served", method)));
    }
    return false;
  }

  bool shutdownRequested() const { return shutdown_; }

private:
  static Json notification(const char* method, Json params) {
    return Json::Object{{"jsonrpc", "2.0"}, {"method", method}, {"params", std::move(params)}};
  }

  // The front end on the document's text, its diagnostics in this file as LSP wants them.
  void publish(const std::string& uri) {
    const std::string path = pathOf(uri);
    auto c = driver::compileText(path, docs_[uri]);
    Json::Array list;
    for (const auto& d : c->diags.all()) {
      bool here = d.span.valid() && d.span.file < c->sources.size() && c->sources.get(d.span.file).displayPath() == path;
      Json range;
      if (here) {
        const auto& f = c->sources.get(d.span.file);
        int endLine = d.span.endLine > 0 ? d.span.endLine : d.span.line;
        int endCol = d.span.endLine > 0 ? d.span.endCol : d.span.col;
        range = Json::Object{
            {"start", Json::Object{{"line", d.span.line - 1}, {"character", utf16Column(f.line(d.span.line), d.span.col)}}},
            {"end", Json::Object{{"line", endLine - 1}, {"character", utf16Column(f.line(endLine), endCol + 1)}}}};
      } else {
        // In an imported file, or with no place: shown at the top of this one.
        range = Json::Object{{"start", Json::Object{{"line", 0}, {"character", 0}}}, {"end", Json::Object{{"line", 0}, {"character", 0}}}};
      }
      int severity = d.severity == diag::Severity::Error ? 1 : d.severity == diag::Severity::Warning ? 2 : 3;
      std::string message = d.message;
      if (!here && d.span.valid() && d.span.file < c->sources.size())
        message += fmt::format(" (in {}:{}:{})", c->sources.get(d.span.file).displayPath(), d.span.line, d.span.col);
      list.push_back(Json::Object{{"range", range}, {"severity", severity}, {"code", d.code}, {"source", "gbxc"}, {"message", message}});
    }
    send(out_, notification("textDocument/publishDiagnostics", Json::Object{{"uri", uri}, {"diagnostics", std::move(list)}}));
  }

  std::ostream& out_;
  std::map<std::string, std::string> docs_;
  bool shutdown_ = false;
};

} // namespace

int serve(std::istream& in, std::ostream& out) {
  Server server(out);
  while (true) {
    bool bad = false;
    auto body = readMessage(in, bad);
    if (!body) return bad ? 1 : (server.shutdownRequested() ? 0 : 1);
    auto msg = Json::parse(*body);
    if (!msg || !msg->isObject()) {
      send(out, error(Json(), -32700, "the message is not a JSON object"));
      continue;
    }
    if (server.handle(*msg)) return server.shutdownRequested() ? 0 : 1;
  }
}

} // namespace gbx::lsp
