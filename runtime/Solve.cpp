#include "Solve.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>

#include <fmt/format.h>

#include "passes/Designs.h"
#include "report/Progress.h"
#include "passes/Modifications.h"
#include "passes/Ratings.h"
#include "passes/Optimise.h"
#include "passes/Render.h"
#include "passes/Scenes.h"
#include "passes/Search.h"
#include "passes/Studies.h"

namespace gbx::rt {

namespace {

// A progress bar on stderr, shared by the callback; finished when the last copy goes.
std::function<void(double)> progressBar(std::ostream& err, std::string label) {
  auto bar = std::make_shared<ProgressBar>(err, std::move(label));
  return [bar](double f) { bar->update(f); };
}

} // namespace

int solve(const ir::Program& program, const SolveOptions& o, std::ostream& out, std::ostream& err) {
  // The driver accepts only names of the table; any other reads as the default, text.
  const ReportFormat* format = findReportFormat(o.format);
  if (!format) format = &reportFormats().front();
  // A progress bar only for a person watching a terminal; reports stay clean.
  bool tty = !o.quiet && isatty(STDERR_FILENO);
  auto progress = [&](const std::string& label) { return tty ? progressBar(err, label) : std::function<void(double)>(); };
  int status = 0;
  auto fail = [&](const std::string& gearbox, const std::vector<std::string>& errors) {
    for (const auto& e : errors) err << fmt::format("gbxc: gearbox `{}`: {}\n", gearbox, e);
    if (!errors.empty()) status = 3;
    return !errors.empty();
  };
  std::vector<GearboxReport> reports;
  // A CSV listing's rows are made as the report is written, from the gearbox's model.
  const bool lazyRows = format->name == "csv" && o.outDir.empty();
  std::vector<std::unique_ptr<Model>> models;
  for (const auto& gb : program.gearboxes) {
    if (!o.gearbox.empty() && gb.name != o.gearbox) continue;
    models.push_back(std::make_unique<Model>(program, gb));
    const Model& m = *models.back();
    SearchResult found = passes::search(m, o.jobs, progress(gb.name));
    if (fail(gb.name, found.errors)) continue;
    passes::Optimised designs = passes::optimise(program, m, std::move(found), o.jobs, progress(gb.name + " optimising"));
    passes::Columns columns = passes::reportColumns(gb);
    std::optional<Assignment> best = passes::bestDesign(m, designs);
    GearboxReport rep = passes::designTable(m, designs, columns, lazyRows);
    rep.notes = designs.designs.notes;
    fail(gb.name, passes::unevaluated(m, rep, columns));
    rep.optimisation = std::move(designs.summary);
    // The table holds every listed design now; the search's copies are not read again.
    std::vector<Design>().swap(designs.designs.designs);
    if (best && (!gb.scenes.empty() || !gb.studies.empty() || !gb.modifies.empty())) {
      passes::SceneRuns scenes = passes::scenes(m, *best, columns);
      fail(gb.name, scenes.errors);
      rep.scenes = std::move(scenes.scenes);
      passes::setSceneColumns(rep, scenes.columns);
      passes::Modifications mods = passes::modifications(m, *best);
      fail(gb.name, mods.errors);
      rep.modifications = std::move(mods.modifications);
      rep.studies = passes::studies(m, *best, progress(gb.name + " studies"));
      std::vector<std::string> studyErrors;
      for (const auto& st : rep.studies)
        if (const auto* s = std::get_if<SweepStudy>(&st.study); s && !s->failure.empty()) studyErrors.push_back(s->failure);
      fail(gb.name, studyErrors);
    }
    if (best) {
      passes::Ratings rated = passes::ratings(m, *best);
      fail(gb.name, rated.errors);
      rep.ratings = std::move(rated.ratings);
    }
    reports.push_back(std::move(rep));
  }
  RenderOptions ro;
  ro.timings = o.timings;
  ro.charts = !o.outDir.empty();
  passes::Rendered rendered = passes::render(std::move(reports), *format, ro);
  out << rendered.report;
  if (!o.outDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    for (const auto& c : rendered.charts) std::ofstream(std::filesystem::path(o.outDir) / c.name) << c.svg;
    for (const auto& t : rendered.tables) std::ofstream(std::filesystem::path(o.outDir) / t.name, std::ios::binary) << t.text;
    std::ofstream f(std::filesystem::path(o.outDir) / rendered.reportFile, std::ios::binary);
    if (!f) {
      err << fmt::format("gbxc: cannot write into `{}`\n", o.outDir);
      return 3;
    }
    f << rendered.report;
  }
  return status;
}

} // namespace gbx::rt
