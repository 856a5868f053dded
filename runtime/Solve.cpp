#include "Solve.h"

#include <unistd.h>

#include <filesystem>
#include <functional>
#include <map>
#include <fstream>
#include <ostream>

#include <fmt/format.h>

#include "report/Report.h"
#include "search/Search.h"
#include "units/Unit.h"

namespace gbx::rt {

namespace {

constexpr long long kDefaultTop = 50;

GearboxReport reportOf(const Model& m, const SearchResult& r, const std::vector<const ir::Expr*>& columnExprs,
                       const std::vector<std::string>& columnNames) {
  Evaluator ev(m);
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
    for (size_t s = 0; s < m.stages.size(); ++s) {
      const ir::Stage& st = *m.stages[s].ir;
      for (const auto& gear : st.gears) {
        Value z = ev.attribute(static_cast<int>(s), gear + ".z", a);
        if (z.exact && z.exact->isInteger()) row.teeth.emplace_back(st.name + "." + gear + ".z", static_cast<long long>(z.exact->num()));
      }
      for (int sl : m.stages[s].slots) {
        const Slot& slot = m.slots[static_cast<size_t>(sl)];
        if (slot.attr.size() > 2 && slot.attr.compare(slot.attr.size() - 2, 2, ".z") == 0) continue;
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
  for (size_t i = 0; i < columnExprs.size(); ++i) {
    bool scene = false;
    std::function<void(const ir::Expr&)> walk = [&](const ir::Expr& e) {
      if (e.op == ir::Op::SceneOutput) scene = true;
      for (const auto& x : e.args)
        if (x) walk(*x);
    };
    walk(*columnExprs[i]);
    if (scene) g.notes.push_back(fmt::format("`{}` is a scene result; scenes are not simulated by this build", columnNames[i]));
  }
  return g;
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
    if (!o.quiet && isatty(STDERR_FILENO))
      so.progress = [&err, name = gb.name](double f) {
        int filled = static_cast<int>(f * 30);
        err << fmt::format("\r  {} [{}{}] {:3.0f}%", name, std::string(static_cast<size_t>(filled), '#'),
                           std::string(static_cast<size_t>(30 - filled), '.'), f * 100)
            << (f >= 1.0 ? "\r\033[K" : "") << std::flush;
      };
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
        if (gb.report->columnTexts[i] == "ratio") continue;  // always shown
        cols.push_back(gb.report->columns[i].get());
        names.push_back(gb.report->columnTexts[i]);
      }
    } else {
      for (const auto& ob : gb.objectives) {
        cols.push_back(ob.expr.get());
        names.push_back(ob.text);
      }
    }
    reports.push_back(reportOf(m, r, cols, names));
  }
  std::string text;
  std::string ext = o.format;
  if (o.format == "json") text = renderJson(reports);
  else if (o.format == "csv") text = renderCsv(reports);
  else if (o.format == "md") text = renderMarkdown(reports, false);
  else if (o.format == "html") text = renderMarkdown(reports, true);
  else {
    text = renderText(reports);
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
