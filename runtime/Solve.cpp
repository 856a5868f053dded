#include "Solve.h"

#include <signal.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <ctime>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>

#include <fmt/format.h>

#include "WriteWhole.h"
#include "model/Deadline.h"
#include "parallel/Ranks.h"
#include "passes/Designs.h"
#include "report/Progress.h"
#include "passes/Modifications.h"
#include "passes/Ratings.h"
#include "passes/Shafts.h"
#include "passes/Optimise.h"
#include "passes/Render.h"
#include "passes/Scenes.h"
#include "passes/Search.h"
#include "passes/Studies.h"
#include "passes/Summary.h"

namespace gbx::rt {

namespace {

// A progress bar on stderr, shared by the callback; finished when the last copy goes. It
// appears once the work has taken a second (a quick solve prints nothing).
std::function<void(double)> progressBar(std::ostream& err, std::string label) {
  auto bar = std::make_shared<ProgressBar>(err, std::move(label));
  auto start = std::chrono::steady_clock::now();
  auto shown = std::make_shared<bool>(false);
  return [bar, start, shown](double f) {
    if (!*shown && std::chrono::steady_clock::now() - start < std::chrono::seconds(1)) return;
    *shown = true;
    bar->update(f);
  };
}

// The report's date; SOURCE_DATE_EPOCH, where set, fixes it (reproducible builds of documents).
std::string today() {
  std::time_t now = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH"); epoch && *epoch) now = static_cast<std::time_t>(std::strtoll(epoch, nullptr, 10));
  char day[16];
  return std::strftime(day, sizeof day, "%Y-%m-%d", std::gmtime(&now)) ? std::string(day) : std::string();
}

// `-o DIR`: the charts, the tables, then the report; false (said on err) where one fails.
bool writeFolder(const passes::Rendered& rendered, const std::string& outDir, std::ostream& err) {
  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  if (ec) {
    err << fmt::format("gbxc: cannot create the output folder `{}`: {}\n", outDir, ec.message());
    return false;
  }
  const std::filesystem::path dir(outDir);
  std::vector<std::string> failures;
  auto put = [&](const std::string& name, const std::string& text) {
    std::string e = writeWhole(dir / name, text);
    if (!e.empty()) failures.push_back(e);
  };
  for (const auto& c : rendered.charts) put(c.name, c.svg);
  for (const auto& t : rendered.tables) put(t.name, t.text);
  // The report last: a new report is never beside old plots it does not name.
  if (failures.empty() && !rendered.reportFile.empty()) put(rendered.reportFile, rendered.report);
  for (const auto& f : failures) err << "gbxc: " << f << "\n";
  return failures.empty();
}

// The report of a search the time limit stopped: its designs so far and a note that says so.
GearboxReport partialReport(const Model& m, SearchResult found, bool lazyRows) {
  std::string note = "partial result: " + found.partial;
  passes::Optimised designs;
  designs.designs = std::move(found);
  for (const auto& d : designs.designs.designs)
    if (!d.freedoms.empty()) designs.freedoms.push_back(d.freedoms);
  passes::Columns columns = passes::reportColumns(m.gearbox);
  GearboxReport rep = passes::designTable(m, designs, columns, lazyRows);
  rep.notes.insert(rep.notes.begin(), designs.designs.notes.begin(), designs.designs.notes.end());
  rep.notes.insert(rep.notes.begin(), note);
  rep.partial = true;
  rep.inputs = passes::decisiveInputs(m.gearbox);
  return rep;
}

// Writes the reports in their format: to `out` (rank 0 alone under mpirun) and the folder of
// -o DIR, kept for the caller that asks. CSV on stdout goes out as its rows are made.
int writeReports(std::vector<GearboxReport> reports, const ReportFormat& format, const SolveOptions& o, bool lazyRows,
                 int status, std::ostream& out, std::ostream& err) {
  RenderOptions ro;
  ro.timings = o.timings;
  ro.title = o.title;
  ro.version = o.version;
  if (o.timings) ro.date = today();
  ro.charts = !o.outDir.empty();
  // CSV on stdout is the design table alone: a note says which tables are not in it.
  auto noteUnwritten = [&](const std::vector<std::string>& unwritten) {
    if (!unwritten.empty() && !o.quiet)
      err << fmt::format("gbxc: note: stdout holds the design table only; {} {} written with -o DIR\n",
                         fmt::join(unwritten, ", "), unwritten.size() == 1 ? "is" : "are");
  };
  // Under mpirun every rank has solved the same; rank 0 alone writes. CSV on stdout: the
  // design table goes out as its rows are made, never held whole.
  if (lazyRows) {
    if (par::root()) streamCsv(reports, [&](const std::string& piece) { out << piece; });
    std::vector<std::string> unwritten = csvOtherTables(reports, ro);
    if (o.keep) *o.keep = std::move(reports);
    if (par::root()) noteUnwritten(unwritten);
    return status;
  }
  passes::Rendered rendered = passes::render(std::move(reports), format, ro);
  if (o.keep) *o.keep = std::move(rendered.reports);
  if (!par::root()) return status;
  out << rendered.report;
  noteUnwritten(rendered.unwritten);
  if (!o.outDir.empty() && !writeFolder(rendered, o.outDir, err)) return 3;
  return status;
}

} // namespace

int solve(const ir::Program& program, const SolveOptions& o, std::ostream& out, std::ostream& err) {
  // The driver accepts only names of the table; any other reads as the default, text.
  const ReportFormat* format = findReportFormat(o.format);
  if (!format) format = &reportFormats().front();
  // A progress bar only for a person watching a terminal; reports stay clean.
  bool tty = !o.quiet && isatty(STDERR_FILENO);
  auto progress = [&](const std::string& label) { return tty ? progressBar(err, label) : std::function<void(double)>(); };
  // The time limit runs from here; it is lifted when the solve returns.
  Deadline::start(o.timeLimit);
  par::setJobs(o.jobs);
  struct Lift {
    ~Lift() { Deadline::clear(); }
  } lift;
  int status = 0;
  auto fail = [&](const std::string& gearbox, const std::vector<std::string>& errors) {
    for (const auto& e : errors) err << fmt::format("gbxc: gearbox `{}`: {}\n", gearbox, e);
    if (!errors.empty()) status = 3;
    return !errors.empty();
  };
  // Past the time limit nothing more is worked out. A search stopped part way reports the
  // designs of the part done, marked partial (exit 3); stopped later, no report is written: a
  // report with some of its results missing would read as complete.
  auto timeUp = [&](const std::string& gearbox, const char* during) {
    if (!Deadline::expired()) return false;
    err << fmt::format("gbxc: gearbox `{}`: time limit of {:g} s (--time-limit) reached during {}; no report written\n", gearbox,
                       Deadline::seconds(), during);
    return true;
  };
  std::vector<GearboxReport> reports;
  // A CSV listing's rows are made as the report is written, from the gearbox's model (the
  // one case: the other renderers and the tables of -o DIR read held rows).
  const bool lazyRows = format->name == "csv" && o.outDir.empty();
  std::vector<std::unique_ptr<Model>> models;
  for (const auto& gb : program.gearboxes) {
    if (!o.gearbox.empty() && gb.name != o.gearbox) continue;
    models.push_back(std::make_unique<Model>(program, gb));
    const Model& m = *models.back();
    SearchResult found =
        passes::search(m, o.jobs, o.maxDesigns, progress(gb.name), progress(gb.name + " deciding freedoms"), lazyRows);
    // Stopped part way by the time limit: the designs of the part done, marked partial, and
    // nothing more worked out (exit 3).
    if (!found.partial.empty() && found.errors.empty()) {
      err << fmt::format("gbxc: gearbox `{}`: {}\n", gb.name, found.partial);
      status = 3;
      reports.push_back(partialReport(m, std::move(found), lazyRows));
      break;
    }
    if (fail(gb.name, found.errors)) {
      if (Deadline::expired()) return 3;  // the message says so; nothing more is worked out
      continue;
    }
    if (timeUp(gb.name, "the search")) return 3;
    passes::Optimised designs = passes::optimise(program, m, std::move(found), o.jobs, progress(gb.name + " optimising"),
                                                        o.optimiserIterations);
    if (timeUp(gb.name, "the optimisation")) return 3;
    passes::Columns columns = passes::reportColumns(gb);
    std::optional<Assignment> best = passes::bestDesign(m, designs);
    GearboxReport rep = passes::designTable(m, designs, columns, lazyRows);
    rep.notes.insert(rep.notes.begin(), designs.designs.notes.begin(), designs.designs.notes.end());
    fail(gb.name, passes::unevaluated(m, rep, columns));
    rep.optimisation = std::move(designs.summary);
    // The table holds every listed design now; the search's copies are not read again.
    std::vector<Design>().swap(designs.designs.designs);
    designs.designs.listing.reset();
    passes::SceneRuns scenes;
    if (best && (!gb.scenes.empty() || !gb.studies.empty() || !gb.modifies.empty())) {
      scenes = passes::scenes(m, *best, columns, o.jobs);
      fail(gb.name, scenes.errors);
      rep.scenes = std::move(scenes.scenes);
      passes::setSceneColumns(rep, scenes.columns);
      rep.notes.insert(rep.notes.end(), scenes.notes.begin(), scenes.notes.end());
      passes::Modifications mods = passes::modifications(m, *best);
      fail(gb.name, mods.errors);
      rep.modifications = std::move(mods.modifications);
      rep.studies = passes::studies(m, *best, progress(gb.name + " studies"), designs.baseline.get(),
                                    designs.baselineDesign.get());
      std::vector<std::string> studyErrors;
      for (const auto& st : rep.studies)
        if (const auto* s = std::get_if<SweepStudy>(&st.study); s && !s->failure.empty()) studyErrors.push_back(s->failure);
      fail(gb.name, studyErrors);
      if (timeUp(gb.name, "its scenes and studies")) return 3;
    }
    if (best) {
      rep.monteCarlo = passes::monteCarlo(m, *best, columns, scenes.samples.get(), scenes.results);
      if (timeUp(gb.name, "its Monte Carlo samples")) return 3;
      if (rep.monteCarlo && !rep.monteCarlo->failure.empty()) fail(gb.name, {rep.monteCarlo->failure});
      if (rep.monteCarlo) rep.warnings.insert(rep.warnings.end(), rep.monteCarlo->warnings.begin(), rep.monteCarlo->warnings.end());
      passes::Ratings rated = passes::ratings(m, *best);
      fail(gb.name, rated.errors);
      rep.ratings = std::move(rated.ratings);
      passes::Shafts solved = passes::shafts(m, *best);
      rep.shafts = std::move(solved.shafts);
      rep.warnings.insert(rep.warnings.end(), solved.warnings.begin(), solved.warnings.end());
    }
    rep.inputs = passes::decisiveInputs(gb);
    reports.push_back(std::move(rep));
  }
  return writeReports(std::move(reports), *format, o, lazyRows, status, out, err);
}

} // namespace gbx::rt
