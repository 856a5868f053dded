// The Python module's native part, `gbxc._gbxc`: the CLI's front end and runtime in one
// shared object. tools/python/gbxc/__init__.py builds the documented API on these few calls
// (docs/python.md); nothing here is meant to be called from a script directly.
#include <dlfcn.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "Solve.h"
#include "driver/Driver.h"
#include "model/Deadline.h"
#include "python/Overrides.h"
#include "report/Report.h"
#include "sema/Loader.h"

namespace py = pybind11;

namespace gbx::python {

namespace {

// One solve at a time in a process: the runtime's time limit and its worker count are the
// process's (a second Python thread's solve waits for the first, with the GIL released).
std::mutex& solveLock() {
  static std::mutex m;
  return m;
}

// One compilation at a time (the parser's caches are shared): a check need not wait for a
// solve's runtime, only for another compilation.
std::mutex& frontLock() {
  static std::mutex m;
  return m;
}

// The running solve's token, so that Ctrl-C stops that solve and never the next one: an
// interrupt, a solve's start and its end each hold `tokenLock` (docs/python.md).
std::mutex tokenLock;
unsigned long long running = 0;

struct Source {
  std::string text; // the spec, or a path when `isText` is false
  bool isText = false;
  std::string display; // the name diagnostics and the report's title give it (a path: itself)
};

std::unique_ptr<driver::Compilation> compileSource(const Source& s) {
  return s.isText ? driver::compileText(s.display, s.text) : driver::compile(s.text);
}

// What `gbxc check --format json` says of a spec: ok, its gearboxes, its diagnostics.
py::dict check(const Source& s) {
  std::unique_ptr<driver::Compilation> c;
  {
    py::gil_scoped_release free;
    std::lock_guard one(frontLock());
    c = compileSource(s);
  }
  py::list names;
  for (size_t i = 0; c->ok() && i < c->program.gearboxes.size(); ++i)
    names.append(c->program.gearboxes[i].name);
  py::dict out;
  out["ok"] = c->ok();
  out["gearboxes"] = names;
  out["diagnostics"] = c->diags.renderJson(c->sources);
  return out;
}

struct SolveArgs {
  unsigned long long token = 0; // the caller's, for `interrupt`
  Source source;
  std::string gearbox;
  int jobs = 1;
  double timeLimit = 0;
  bool timings = true;
  std::vector<std::pair<std::string, std::string>> overrides;
};

// A solve's result: its exit status, the JSON report, what it printed as errors, the
// diagnostics of a spec that did not check, and the reports behind the JSON (the arrays).
struct Solved {
  int status = 0;
  std::string json, errors, diagnostics, diagnosticsText, summaryHtml;
  std::vector<rt::GearboxReport> reports;
};

// Every `from` in `text` replaced by `to`.
void replaceAll(std::string& text, const std::string& from, const std::string& to) {
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
}

std::unique_ptr<driver::Compilation> compileWithOverrides(const SolveArgs& a, Solved& out, Overridden& o) {
  if (a.overrides.empty()) return compileSource(a.source);
  std::string text = a.source.text;
  if (!a.source.isText) {
    std::error_code ec;
    std::ifstream in(a.source.text, std::ios::binary);
    // The front end's own "cannot read" diagnostic for what is not a readable file.
    if (!std::filesystem::is_regular_file(a.source.text, ec) || !in) return compileSource(a.source);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string& display = a.source.display;
  // The spec alone first, for its gearboxes' names: each gets a variant with the overrides.
  auto plain = driver::compileText(display, text);
  if (!plain->ok()) return plain;
  // Every gearbox, or the one asked for with its baselines (a `relative(…)` reads its
  // baseline, overridden alike, as it is without `gearbox`).
  std::vector<std::string> names;
  for (std::string want = a.gearbox; !want.empty();) {
    std::string next;
    for (const auto& g : plain->program.gearboxes)
      if (g.name == want && std::find(names.begin(), names.end(), want) == names.end()) {
        names.insert(names.begin(), want);
        next = g.baseline;
      }
    want = next;
  }
  if (a.gearbox.empty())
    for (const auto& g : plain->program.gearboxes)
      names.push_back(g.name);
  o = withOverrides(text, names, a.overrides);
  if (!o.error.empty()) {
    out.status = 2;
    out.errors = o.error;
    return nullptr;
  }
  auto c = driver::compileText(display, o.text);
  if (c->ok()) keepVariants(c->program, o.variants);
  return c;
}

Solved solveNow(const SolveArgs& a) {
  Solved out;
  Overridden o;
  std::unique_ptr<driver::Compilation> c;
  {
    std::lock_guard one(frontLock());
    c = compileWithOverrides(a, out, o);
  }
  if (!c) return out;
  // The diagnostics (errors, or the warnings of a spec that checks) name the gearboxes, not
  // the variants the overrides were written as.
  out.diagnostics = c->diags.renderJson(c->sources);
  out.diagnosticsText = c->diags.renderText(c->sources);
  for (const auto& [variant, base] : o.variants) {
    replaceAll(out.diagnostics, variant, base);
    replaceAll(out.diagnosticsText, variant, base);
  }
  if (!c->ok()) {
    out.status = 1;
    return out;
  }
  if (!a.gearbox.empty()) {
    bool found = false;
    for (const auto& g : c->program.gearboxes)
      found = found || g.name == a.gearbox;
    if (!found) {
      out.status = 2;
      out.errors = "the spec declares no gearbox `" + a.gearbox + "`";
      return out;
    }
  }
  rt::SolveOptions so;
  so.gearbox = a.gearbox;
  so.format = "json";
  so.jobs = a.jobs;
  so.quiet = true;
  so.timings = a.timings;
  so.timeLimit = a.timeLimit;
  so.title = std::filesystem::path(a.source.display).filename().string();
  so.version = GBX_VERSION;
  so.keep = &out.reports;
  std::ostringstream json, errors;
  out.status = rt::solve(c->program, so, json, errors);
  out.json = json.str();
  out.errors = errors.str();
  rt::RenderOptions ro;
  ro.title = so.title;
  ro.version = so.version;
  out.summaryHtml = rt::renderHtmlSummary(out.reports, ro);
  return out;
}

// Solves with the GIL released. The package runs this on a thread of its own and, on Ctrl-C
// in the waiting thread, calls `interrupt` until it returns (docs/python.md).
Solved solve(const SolveArgs& a) {
  py::gil_scoped_release free;
  std::lock_guard one(solveLock());
  {
    std::lock_guard t(tokenLock);
    running = a.token;
  }
  Solved done;
  try {
    done = solveNow(a);
  } catch (const std::exception& e) { // as the command's exit 3: said, not a crash
    done = Solved{};
    done.status = 3;
    done.errors = std::string("gbxc: ") + e.what() + "\n";
  }
  std::lock_guard t(tokenLock);
  running = 0;
  rt::Deadline::clear();
  return done;
}

// Stops the solve of `token`, if it is the running one, as its time limit would.
void interrupt(unsigned long long token) {
  std::lock_guard t(tokenLock);
  if (token != 0 && running == token) rt::Deadline::interrupt();
}

// Each scene's plotted outputs: its signals (x in s) and spectra (x in Hz) as NumPy arrays.
py::list plots(const Solved& s) {
  py::list out;
  for (const auto& g : s.reports)
    for (const auto& sc : g.scenes)
      for (const auto& p : sc.plots) {
        py::dict d;
        d["gearbox"] = g.name;
        d["scene"] = sc.name;
        d["key"] = p.key;
        d["signal"] = p.signal;
        d["unit"] = p.unit;
        d["spectrum"] = p.spectrum;
        d["mesh_frequency"] = p.meshFrequency;
        d["x"] = py::array_t<double>(static_cast<py::ssize_t>(p.x.size()), p.x.data());
        d["y"] = py::array_t<double>(static_cast<py::ssize_t>(p.y.size()), p.y.data());
        out.append(d);
      }
  return out;
}

// Each gearbox's warnings and notes, as the text report prints them.
py::dict remarks(const Solved& s) {
  py::dict out;
  for (const auto& g : s.reports) {
    py::dict d;
    d["warnings"] = g.warnings;
    d["notes"] = g.notes;
    out[py::str(g.name)] = d;
  }
  return out;
}

// The command line in this process (`gbxc solve …` as driver::run runs it): what the
// benchmark of the module's overhead compares with.
py::tuple cli(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  int status = 0;
  {
    py::gil_scoped_release free;
    std::lock_guard one(solveLock());
    status = driver::run(args, out, err);
  }
  return py::make_tuple(status, out.str(), err.str());
}

// The shared object's own path, to find the stdlib beside the installation it came with.
std::string ownPath() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<const void*>(&ownPath), &info) == 0 || !info.dli_fname) return {};
  std::error_code ec;
  auto p = std::filesystem::canonical(info.dli_fname, ec);
  return ec ? std::string(info.dli_fname) : p.string();
}

} // namespace

} // namespace gbx::python

PYBIND11_MODULE(_gbxc, m) {
  using namespace gbx::python;
  m.doc() = "gbxc's native part; use the `gbxc` package (docs/python.md)";
  gbx::sema::setProgramLocation(ownPath());
  m.attr("version") = GBX_VERSION;

  py::class_<Solved>(m, "Solved")
      .def_readonly("status", &Solved::status)
      .def_readonly("json", &Solved::json)
      .def_readonly("errors", &Solved::errors)
      .def_readonly("diagnostics", &Solved::diagnostics)
      .def_readonly("diagnostics_text", &Solved::diagnosticsText)
      .def_readonly("summary_html", &Solved::summaryHtml)
      .def("plots", &plots)
      .def("remarks", &remarks);

  m.def("cli", &cli, py::arg("args"));
  // Stops the solve of a token, if it is the running one, as its time limit would (Ctrl-C).
  m.def("interrupt", &interrupt, py::arg("token"));
  m.def(
      "check",
      [](const std::string& source, bool isText, const std::string& display) {
        return check({source, isText, display});
      },
      py::arg("source"), py::arg("is_text"), py::arg("display"));
  m.def(
      "solve",
      [](unsigned long long token, const std::string& source, bool isText, const std::string& display,
         const std::string& gearbox, int jobs, double timeLimit, bool timings,
         const std::vector<std::pair<std::string, std::string>>& overrides) {
        return solve({token, {source, isText, display}, gearbox, jobs, timeLimit, timings, overrides});
      },
      py::arg("token"), py::arg("source"), py::arg("is_text"), py::arg("display"), py::arg("gearbox"), py::arg("jobs"),
      py::arg("time_limit"), py::arg("timings"), py::arg("overrides"));
}
