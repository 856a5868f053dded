#include "Solve.h"

#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <cctype>
#include <map>
#include <fstream>
#include <ostream>

#include <fmt/format.h>

#include "dynamics/Scene.h"
#include "report/Report.h"
#include "report/Svg.h"
#include "study/WorkPrecision.h"
#include "study/Sweep.h"
#include "modification/Modify.h"
#include "optimise/Optimise.h"
#include "model/Evaluator.h"
#include "search/Search.h"
#include "units/Unit.h"

namespace gbx::rt {

namespace {

constexpr long long kDefaultTop = 50;

GearboxReport reportOf(const Model& m, const SearchResult& r, const std::vector<const ir::Expr*>& columnExprs,
                       const std::vector<std::string>& columnNames, const std::vector<std::vector<double>>& freedoms = {},
                       const Model* baseline = nullptr, const Assignment* baseDesign = nullptr) {
  Evaluator ev(m);
  if (!freedoms.empty()) {
    // Optimised designs: scene results and relative values at the scenes' own accuracy.
    const ir::Setting* own = m.gearbox.scenes.empty() ? nullptr : ir::findSetting(m.gearbox.scenes[0].accuracy, Q::Rtol);
    installHooks(ev, m, baseline, baseDesign, own && own->value ? own->value->toDouble() : 1e-9);
  }
  GearboxReport g;
  g.name = m.gearbox.name;
  g.count = r.count;
  g.undecided = r.undecided;
  g.window = r.window;
  g.funnel = r.funnel;
  // Rules `q in a..b` with constant bounds: the part of q's interval a design may use.
  std::map<std::string, std::pair<double, double>> bounds;
  std::function<void(const ir::Expr&)> collect = [&](const ir::Expr& e) {
    if (e.op == ir::Op::And || e.op == ir::Op::Forall) {
      for (const auto& x : e.args) collect(*x);
      return;
    }
    if (e.op == ir::Op::Within && e.args[0]->op == ir::Op::Quantity && e.args[1]->isConst() && e.args[2]->isConst())
      bounds[e.args[0]->name] = {e.args[1]->value.toDouble(), e.args[2]->value.toDouble()};
  };
  for (const auto& rule : m.gearbox.rules)
    if (rule.expr) collect(*rule.expr);
  for (size_t i = 0; i < columnExprs.size(); ++i) {
    Column c;
    c.name = columnNames[i];
    // A catalogue quantity is monotone in each freedom: its corners give its exact image.
    c.exact = columnExprs[i]->op == ir::Op::Quantity || columnExprs[i]->isConst();
    auto u = units::displayUnitFor(columnExprs[i]->type.dim);
    // Imbalances read best in percent.
    if (columnExprs[i]->op == ir::Op::Quantity && columnExprs[i]->ref.key == Q::Imbalance) u = {"%", 0.01};
    c.unit = u.name;
    c.scale = u.scale;
    g.columns.push_back(c);
  }
  int rank = 0;
  for (const auto& d : r.designs) {
    DesignRow row;
    row.rank = ++rank;
    row.ratio = d.ratio;
    row.undecided = d.undecided;
    Assignment a(m);
    a.choice = d.choice;
    size_t ri = static_cast<size_t>(row.rank - 1);
    if (ri < freedoms.size())
      for (size_t f = 0; f < freedoms[ri].size(); ++f) {
        a.box[f] = {freedoms[ri][f], freedoms[ri][f]};
        const Freedom& fr = m.freedoms[f];
        const ir::Attribute* at = m.attribute(fr.stage, fr.gear, fr.key);
        auto u = units::displayUnitFor(at ? at->dim : units::Dim{});
        row.choices.emplace_back(m.freedoms[f].path, formatNumber(freedoms[ri][f] / u.scale) + (u.name.empty() ? "" : " " + u.name));
      }
    for (size_t s = 0; s < m.stages.size(); ++s) {
      const ir::Stage& st = *m.stages[s].ir;
      for (size_t g = 0; g < st.gears.size(); ++g) {
        Value z = ev.attribute(static_cast<int>(s), static_cast<int>(g), Q::Z, a);
        if (z.exact && z.exact->isInteger()) row.teeth.emplace_back(st.name + "." + st.gears[g] + ".z", static_cast<long long>(z.exact->num()));
      }
      for (int sl : m.stages[s].slots) {
        const Slot& slot = m.slots[static_cast<size_t>(sl)];
        if (slot.key == Q::Z && slot.gear >= 0) continue;
        const Value& v = slot.values[static_cast<size_t>(d.choice[static_cast<size_t>(sl)])];
        if (v.exact && v.exact->isInteger()) row.teeth.emplace_back(slot.path, static_cast<long long>(v.exact->num()));
        else {
          auto du = units::displayUnitFor(st.find(slot.attr) ? st.find(slot.attr)->dim : units::Dim{});
          row.choices.emplace_back(slot.path, formatNumber(v.lo / du.scale) + (du.name.empty() ? "" : " " + du.name));
        }
      }
    }
    for (size_t i = 0; i < columnExprs.size(); ++i) {
      Value v = ev.eval(*columnExprs[i], a);
      Cell c;
      if (v.isNumber()) {
        c.valid = true;
        c.lo = v.lo;
        c.hi = v.hi;
        double s = g.columns[i].scale;
        c.text = v.lo == v.hi ? formatNumber(v.lo / s) : "[" + formatNumber(v.lo / s) + ", " + formatNumber(v.hi / s) + "]";
        auto b = columnExprs[i]->op == ir::Op::Quantity ? bounds.find(columnExprs[i]->name) : bounds.end();
        if (b != bounds.end() && v.lo != v.hi) {
          c.feasible = true;
          c.flo = std::max(v.lo, b->second.first);
          c.fhi = std::min(v.hi, b->second.second);
          c.text += " feasible [" + formatNumber(c.flo / s) + ", " + formatNumber(c.fhi / s) + "]";
        }
      } else {
        c.text = "n/a";
      }
      row.cells.push_back(c);
    }
    g.rows.push_back(std::move(row));
  }
  // Only a column that shows intervals can show enclosures.
  for (size_t i = 0; i < g.columns.size(); ++i) {
    bool interval = false;
    for (const auto& row : g.rows) interval = interval || (row.cells[i].valid && row.cells[i].lo != row.cells[i].hi);
    if (!interval) g.columns[i].exact = true;
  }
  return g;
}

// A one-line progress bar on stderr, cleared when done.
std::function<void(double)> progressBar(std::ostream& err, std::string label) {
  return [&err, label](double f) {
    int filled = static_cast<int>(f * 30);
    err << fmt::format("\r  {} [{}{}] {:3.0f}%", label, std::string(static_cast<size_t>(filled), '#'),
                       std::string(static_cast<size_t>(30 - filled), '.'), f * 100)
        << (f >= 1.0 ? "\r\033[K" : "") << std::flush;
  };
}

std::string fileSafe(const std::string& k) {
  std::string o;
  for (char c : k) o += (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.') ? c : '_';
  while (!o.empty() && o.back() == '_') o.pop_back();
  return o;
}

SceneReport sceneReport(const dyn::SceneResult& r, const ir::Scene& scene, const std::string& prefix, const std::string& outDir) {
  SceneReport s;
  s.name = r.name.empty() ? scene.name : r.name;
  s.target = scene.target;
  s.failure = r.failure;
  if (!r.failure.empty()) return s;
  s.method = r.method;
  s.rtol = r.rtol;
  s.atol = r.atol;
  s.steps = r.stats.steps;
  s.rejected = r.stats.rejected;
  s.rhs = r.stats.rhsEvaluations;
  s.jacobians = r.stats.jacobianEvaluations;
  s.events = r.stats.events;
  s.cpu = r.stats.cpuSeconds;
  s.referenceCpu = r.referenceStats.cpuSeconds;
  s.errorEstimate = r.errorEstimate;
  s.errorMethod = r.errorMethod;
  s.model = r.model;
  for (const auto& n : r.numbers) {
    auto u = units::displayUnitFor(n.dim);
    s.outputs.push_back({n.key, u.name, n.value, n.value / u.scale});
  }
  for (const auto& ser : r.series) {
    auto u = units::displayUnitFor(ser.dim);
    if (ser.isSpectrum) {
      SceneReport::SpectrumRow row{ser.key, u.name, u.scale, {}};
      for (const auto& p : ser.spectrum.peaks) row.peaks.push_back({p.frequency, p.amplitude, p.harmonic});
      s.spectra.push_back(row);
    }
    if (outDir.empty()) continue;
    SvgChart chart;
    chart.title = fmt::format("{} — scene {}: {}", prefix, scene.name, ser.key);
    SvgSeries line;
    if (ser.isSpectrum) {
      chart.xLabel = "frequency [Hz]";
      chart.yLabel = "amplitude" + (u.name.empty() ? std::string() : " [" + u.name + "]");
      double fmax = r.meshFrequency > 0 ? 10.5 * r.meshFrequency : INFINITY;
      for (size_t i = 0; i < ser.spectrum.frequency.size() && ser.spectrum.frequency[i] <= fmax; ++i) {
        line.x.push_back(ser.spectrum.frequency[i]);
        line.y.push_back(ser.spectrum.amplitude[i] / u.scale);
      }
    } else {
      chart.xLabel = "time [s]";
      chart.yLabel = ser.signal + (u.name.empty() ? std::string() : " [" + u.name + "]");
      // At most 4000 points: every k-th sample, so the file stays small and faithful.
      size_t step = std::max<size_t>(1, ser.t.size() / 4000);
      for (size_t i = 0; i < ser.t.size(); i += step) {
        line.x.push_back(ser.t[i]);
        line.y.push_back(ser.v[i] / u.scale);
      }
    }
    chart.series.push_back(line);
    std::string file = fileSafe(prefix + "." + scene.name + "." + ser.key) + ".svg";
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    std::ofstream(std::filesystem::path(outDir) / file) << renderSvg(chart);
    s.files.push_back(file);
  }
  return s;
}

} // namespace

int solve(const ir::Program& program, const SolveOptions& o, std::ostream& out, std::ostream& err) {
  std::vector<GearboxReport> reports;
  int status = 0;
  for (const auto& gb : program.gearboxes) {
    if (!o.gearbox.empty() && gb.name != o.gearbox) continue;
    Model m(program, gb);
    SearchOptions so;
    so.jobs = o.jobs;
    so.top = gb.report && gb.report->top ? *gb.report->top : kDefaultTop;
    if (gb.report && gb.report->sortBy) so.sortBy = gb.report->sortBy.get();
    // A progress bar only for a person watching a terminal; reports stay clean.
    bool tty = !o.quiet && isatty(STDERR_FILENO);
    if (tty) so.progress = progressBar(err, gb.name);
    bool optimising = needsOptimiser(gb);
    if (optimising) {
      so.deferDynamics = true;
      so.top = std::nullopt;
    }
    SearchResult r = search(m, so);
    if (!r.errors.empty()) {
      for (const auto& e : r.errors) err << fmt::format("gbxc: gearbox `{}`: {}\n", gb.name, e);
      status = 3;
      continue;
    }
    std::vector<const ir::Expr*> cols;
    std::vector<std::string> names;
    if (gb.report && !gb.report->columns.empty()) {
      for (size_t i = 0; i < gb.report->columns.size(); ++i) {
        if (gb.report->ratioColumn[i]) continue;  // always shown
        cols.push_back(gb.report->columns[i].get());
        names.push_back(gb.report->columnTexts[i]);
      }
    } else {
      for (const auto& ob : gb.objectives) {
        cols.push_back(ob.expr.get());
        names.push_back(ob.text);
      }
    }
    // Objectives over scene results or a baseline: optimise every candidate's freedoms.
    std::unique_ptr<Model> baseModel;
    std::unique_ptr<Assignment> baseDesign;
    std::vector<std::string> optLines, optTimings;
    std::string optJson;
    std::vector<std::vector<double>> optimumFreedoms;
    if (optimising) {
      for (const auto& other : program.gearboxes)
        if (other.name == gb.baseline) {
          baseModel = std::make_unique<Model>(program, other);
          SearchOptions bo;
          bo.top = 1;
          bo.deferDynamics = true;
          auto br = search(*baseModel, bo);
          if (!br.designs.empty()) {
            baseDesign = std::make_unique<Assignment>(*baseModel);
            baseDesign->choice = br.designs[0].choice;
          }
        }
      OptimiseOptions oo;
      oo.jobs = o.jobs;
      if (tty) oo.progress = progressBar(err, gb.name + " optimising");
      auto wall0 = std::chrono::steady_clock::now();
      OptimiseResult opt = optimise(m, baseModel.get(), baseDesign.get(), r.designs, oo);
      double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      // The ranked optima become the design list.
      size_t keep = gb.report && gb.report->top ? static_cast<size_t>(*gb.report->top) : 10;
      r.count = opt.ranked.size();
      r.designs.clear();
      for (size_t i = 0; i < opt.ranked.size() && i < keep; ++i) {
        Design d;
        d.choice = opt.ranked[i].choice;
        d.ratio = opt.ranked[i].ratio;
        d.keys = {opt.ranked[i].objective};
        r.designs.push_back(d);
        optimumFreedoms.push_back(opt.ranked[i].freedoms);
      }
      optLines.push_back(fmt::format("optimisation: {} candidates, {} with no feasible freedoms; {} objective evaluations (scenes at rtol {:.0e})",
                                     opt.ranked.size() + opt.infeasible, opt.infeasible, opt.evaluations, oo.sceneRtol));
      optLines.push_back("  method: Nelder-Mead (GSL nmsimplex2) over the freedoms of each candidate; bounds by x = lo + (hi - lo) sin^2(u);");
      optLines.push_back("          rules by an exterior penalty (a violated rule costs 1000 (1 + relative violation)); best optimum kept");
      std::string json = fmt::format(R"({{"candidates": {}, "infeasible": {}, "evaluations": {}, "scene_rtol": {}, )", opt.ranked.size() + opt.infeasible,
                                     opt.infeasible, opt.evaluations, oo.sceneRtol);
      if (!opt.ranked.empty()) {
        const auto& best = opt.ranked[0];
        std::string vars;
        for (size_t f = 0; f < m.freedoms.size() && f < best.freedoms.size(); ++f) {
          const ir::Attribute* at = m.attribute(m.freedoms[f].stage, m.freedoms[f].gear, m.freedoms[f].key);
          auto u = units::displayUnitFor(at ? at->dim : units::Dim{});
          vars += fmt::format("{}{} = {}{}", vars.empty() ? "" : ", ", m.freedoms[f].path, formatNumber(best.freedoms[f] / u.scale),
                              u.name.empty() ? "" : " " + u.name);
        }
        optLines.push_back(fmt::format("  optimum: ratio {}, {}; objective {}", best.ratio.str(), vars, formatNumber(best.objective)));
        json += fmt::format(R"("objective": {}, "terms": {{)", best.objective);
        for (size_t t = 0; t < opt.termNames.size() && t < best.terms.size(); ++t) {
          double rel = best.terms[t] / opt.baselineTerms[t];
          optLines.push_back(fmt::format("  {}: {} against the baseline's {}: {:+.1f} %", opt.termNames[t], formatNumber(best.terms[t]),
                                         formatNumber(opt.baselineTerms[t]), (rel - 1) * 100));
          json += fmt::format("{}\"{}\": {{\"value\": {}, \"baseline\": {}, \"relative\": {}}}", t ? ", " : "", opt.termNames[t], best.terms[t],
                              opt.baselineTerms[t], rel);
        }
        json += "}, ";
      }
      if (!opt.rankCheck.empty()) optLines.push_back("  ranking: " + opt.rankCheck);
      json += fmt::format(R"("rank_check": "{}", "pareto": [)", opt.rankCheck);
      for (size_t i = 0; i < opt.pareto.size(); ++i) json += fmt::format("{}[{}, {}]", i ? ", " : "", opt.pareto[i].first, opt.pareto[i].second);
      json += "]}";
      optJson = json;
      if (opt.termNames.size() == 2) {
        optLines.push_back(fmt::format("  Pareto front of ({}, {}) relative to the baseline, {} points:", opt.termNames[0], opt.termNames[1], opt.pareto.size()));
        size_t stepP = std::max<size_t>(1, opt.pareto.size() / 12);
        for (size_t i = 0; i < opt.pareto.size(); i += stepP)
          optLines.push_back(fmt::format("    {:.4f}  {:.4f}", opt.pareto[i].first, opt.pareto[i].second));
        if (!o.outDir.empty()) {
          SvgChart c;
          c.title = fmt::format("{}: objectives relative to {}", gb.name, gb.baseline);
          c.xLabel = "relative " + opt.termNames[0];
          c.yLabel = "relative " + opt.termNames[1];
          SvgSeries cloud{"feasible evaluations", {}, {}, true}, front{"Pareto front", {}, {}, true}, base{"baseline", {1.0}, {1.0}, true},
              weighted{"weighted optimum", {}, {}, true};
          for (const auto& p : opt.cloud) {
            cloud.x.push_back(p.first);
            cloud.y.push_back(p.second);
          }
          for (const auto& p : opt.pareto) {
            front.x.push_back(p.first);
            front.y.push_back(p.second);
          }
          if (!opt.ranked.empty() && opt.ranked[0].terms.size() == 2) {
            weighted.x.push_back(opt.ranked[0].terms[0] / opt.baselineTerms[0]);
            weighted.y.push_back(opt.ranked[0].terms[1] / opt.baselineTerms[1]);
          }
          c.series = {cloud, front, base, weighted};
          std::string text = renderSvg(c);
          // Points only for the cloud: drop its connecting line.
          auto pos = text.find("<polyline fill=\"none\" stroke=\"#1f77b4\"");
          if (pos != std::string::npos) text.erase(pos, text.find("/>", pos) + 3 - pos);
          std::string file = fileSafe(gb.name) + ".pareto.svg";
          std::filesystem::create_directories(o.outDir);
          std::ofstream(std::filesystem::path(o.outDir) / file) << text;
          optLines.push_back("  wrote " + file);
        }
      }
      optTimings.push_back(fmt::format("timing: optimisation {:.2f} s wall with --jobs {}", wall, o.jobs));
    }
    GearboxReport rep = reportOf(m, r, cols, names, optimumFreedoms, baseModel.get(), baseDesign.get());
    rep.optimisation = optLines;
    rep.optimisationJson = optJson;
    rep.optimisationTimings = optTimings;
    // Scenes and studies run on the best design.
    if (!r.designs.empty() && (!gb.scenes.empty() || !gb.studies.empty() || !gb.modifies.empty())) {
      Assignment best(m);
      best.choice = r.designs[0].choice;
      if (!optimumFreedoms.empty())
        for (size_t f = 0; f < optimumFreedoms[0].size(); ++f) best.box[f] = {optimumFreedoms[0][f], optimumFreedoms[0][f]};
      std::map<int, dyn::SceneResult> results;
      for (const auto& sc : gb.scenes) {
        auto res = dyn::runScene(m, best, sc);
        if (!res.failure.empty()) {
          err << fmt::format("gbxc: gearbox `{}`: {}\n", gb.name, res.failure);
          status = 3;
        }
        rep.scenes.push_back(sceneReport(res, sc, gb.name, o.outDir));
        results[static_cast<int>(&sc - gb.scenes.data())] = std::move(res);
      }
      // Report columns that are scene results.
      for (size_t i = 0; i < cols.size() && !rep.rows.empty(); ++i) {
        if (cols[i]->op != ir::Op::SceneOutput) continue;
        auto it = results.find(cols[i]->output.scene);
        if (it == results.end()) continue;
        if (const auto* n = it->second.find(cols[i]->output.fn, cols[i]->output.signal)) {
          Cell& c = rep.rows[0].cells[i];
          c.valid = true;
          c.lo = c.hi = n->value;
          c.text = formatNumber(n->value / rep.columns[i].scale);
        }
      }
      for (const auto& md : gb.modifies) {
        ModifyReport mr;
        mr.stage = md.stage;
        for (const auto& out : evaluateModify(m, best, md)) {
          ModRow row;
          row.target = out.target;
          row.text = out.text;
          row.present = out.present;
          row.error = out.error;
          if (out.value) {
            row.valid = true;
            row.si = *out.value;
            row.shown = formatLength(*out.value);
          }
          if (!out.condition.empty()) row.condition = out.condition;
          for (const auto& in : out.inputs) {
            auto u = units::displayUnitFor(in.dim);
            std::string v = in.dim == units::dims::length ? formatLength(in.value)
                                                          : formatNumber(in.value / u.scale) + (u.name.empty() ? "" : " " + u.name);
            row.inputs.push_back(fmt::format("{} = {}{}", in.name, v, in.given ? " (given)" : ""));
            row.inputsSI.emplace_back(in.name, in.value);
          }
          if (!row.error.empty()) {
            err << fmt::format("gbxc: gearbox `{}`: modify {}: `{}`: {}\n", gb.name, md.stage, row.target, row.error);
            status = 3;
          }
          mr.rows.push_back(std::move(row));
        }
        rep.modifications.push_back(std::move(mr));
      }
      for (const auto& st : gb.studies) {
        if (st.kind == ir::Study::Sweep) {
          rep.studies.push_back(sweep(m, best, st, o.outDir, fileSafe(gb.name)));
          continue;
        }
        const ir::Scene* scene = st.scene >= 0 ? &gb.scenes[static_cast<size_t>(st.scene)] : nullptr;
        if (scene) rep.studies.push_back(workPrecision(m, best, st, *scene, o.outDir, fileSafe(gb.name), o.timings));
      }
    }
    reports.push_back(std::move(rep));
  }
  std::string text;
  std::string ext = o.format;
  RenderOptions ro;
  ro.timings = o.timings;
  if (o.format == "json") text = renderJson(reports, ro);
  else if (o.format == "csv") text = renderCsv(reports);
  else if (o.format == "md") text = renderMarkdown(reports, false);
  else if (o.format == "html") text = renderMarkdown(reports, true);
  else {
    text = renderText(reports, ro);
    ext = "txt";
  }
  out << text;
  if (!o.outDir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.outDir, ec);
    std::ofstream f(std::filesystem::path(o.outDir) / ("report." + ext), std::ios::binary);
    if (!f) {
      err << fmt::format("gbxc: cannot write into `{}`\n", o.outDir);
      return 3;
    }
    f << text;
  }
  return status;
}

} // namespace gbx::rt
