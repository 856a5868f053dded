// The HTML report as a document an engineer sends on: a summary first (per gearbox what it
// was solved for, the chosen design, its key results, each safety against its minimum, the
// warnings), then every plot, then the tables, long ones folded; one embedded stylesheet for
// screen and print (A4). docs/reports.md.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/Optimisation.h"
#include "report/MonteCarlo.h"
#include "report/Ratings.h"
#include "report/Report.h"
#include "report/Studies.h"
#include "report/Shafts.h"
#include "report/Summary.h"
#include "report/Symbols.h"

namespace gbx::rt {

namespace {

// Tables longer than this fold: their first rows show, the rest open on demand.
constexpr size_t kFoldRows = 30;
constexpr size_t kShownWhenFolded = 12;
// A design table of a few designs and many columns reads better turned: a row per quantity.
constexpr size_t kTurnColumns = 10;
constexpr size_t kTurnRows = 3;

const char* kStyle = R"(<style>
:root{--line:#d0d7de;--muted:#57606a;--ok:#1a7f37;--ok-bg:#dafbe1;--low:#cf222e;--low-bg:#ffebe9;--warn:#9a6700;--warn-bg:#fff8c5}
*{box-sizing:border-box}
body{font:14px/1.45 system-ui,-apple-system,"Segoe UI",sans-serif;color:#1f2328;margin:0 auto;max-width:1200px;padding:20px 28px}
h1{font-size:22px;margin:0 0 2px}h2{font-size:18px;margin:28px 0 8px;border-bottom:1px solid var(--line);padding-bottom:4px}
h3{font-size:15px;margin:18px 0 6px}h4{font-size:13px;margin:10px 0 4px;color:var(--muted);text-transform:uppercase;letter-spacing:.04em}
.meta{color:var(--muted);margin:0 0 12px}
section.summary{margin-bottom:8px}
.card{border:1px solid var(--line);border-radius:6px;padding:10px 16px 12px;margin:12px 0}
.card h3{margin-top:4px}
.cols{display:flex;flex-wrap:wrap;gap:8px 40px}.cols>div{flex:1 1 320px;min-width:0}
dl.kv{display:grid;grid-template-columns:minmax(0,max-content) minmax(7em,1fr);gap:1px 14px;margin:0}
dl.kv dt{color:var(--muted);overflow-wrap:anywhere}dl.kv dd{margin:0;overflow-wrap:anywhere}
ul.results{margin:0;padding-left:18px}ul.results li{overflow-wrap:anywhere}
table{border-collapse:collapse;font-variant-numeric:tabular-nums}
th,td{padding:3px 9px;text-align:right;border-bottom:1px solid #eaeef2;vertical-align:bottom}
th{background:#f6f8fa;font-weight:600;max-width:16em}
td{white-space:nowrap}td.t,th.t{text-align:left;white-space:normal}td.t{overflow-wrap:break-word}
.scroll{overflow-x:auto;max-width:100%;margin:6px 0}
table.safety td.v{font-weight:600}
tr.ok td.v{color:var(--ok);background:var(--ok-bg)}tr.low td.v{color:var(--low);background:var(--low-bg)}
.verdict{font-weight:600}.verdict.ok{color:var(--ok)}.verdict.low{color:var(--low)}
.warnings{border-left:4px solid #d4a72c;background:var(--warn-bg);padding:6px 14px;margin:10px 0;border-radius:0 6px 6px 0}
.warnings h4{color:var(--warn);margin-top:4px}.warnings ul{margin:4px 0;padding-left:18px}
.plots{display:flex;flex-wrap:wrap;gap:14px}
figure{margin:6px 0;max-width:100%}figure svg{width:100%;height:auto;display:block}
.plots figure{flex:1 1 520px;max-width:720px}
figcaption{color:var(--muted);font-size:12px;margin-top:2px}
details{margin:6px 0}details>summary{cursor:pointer;color:#0969da}
.print{display:none}
ul.model{color:var(--muted);font-size:13px;padding-left:18px}
@media print{
 @page{size:A4;margin:14mm 12mm}
 body{max-width:none;padding:0;font-size:9.5pt}
 h2{break-after:avoid;margin-top:14pt}h3,h4{break-after:avoid}
 figure,tr,.warnings,dl.kv>*,.card{break-inside:avoid}
 .cols{display:block}.cols>div{margin-bottom:6px}
 .scroll{overflow:visible}
 table{font-size:8pt}th{max-width:10em}
 figure svg{max-height:120mm;width:auto}
 thead{display:table-header-group}
 .screen{display:none}.print{display:block}
 details::details-content{content-visibility:visible;display:block}
 details>summary{color:inherit;list-style:none}
}
</style>
)";

std::string esc(const std::string& x) {
  std::string o;
  o.reserve(x.size());
  for (char c : x) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

bool numberLike(const std::string& c) {
  return !c.empty() && (std::isdigit(static_cast<unsigned char>(c[0])) || c[0] == '-' || c[0] == '[');
}

// A column heading may break after a dot, an underscore or an opening parenthesis
// (`planet_stage.sun.z`), never inside a word.
std::string heading(const std::string& h) {
  std::string o;
  for (char c : esc(h)) {
    o += c;
    if (c == '.' || c == '_' || c == '(') o += "<wbr>";
  }
  return o;
}

// A column of words (rules, inputs, names, methods) is left-aligned as a whole, a column of
// numbers right-aligned: one alignment per column, whatever a cell starts with.
// (A number column keeps its alignment where a few cells say why they have no number.)
std::vector<bool> wordColumns(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  std::vector<int> text(head.size(), 0), filled(head.size(), 0);
  for (const auto& r : rows)
    for (size_t c = 0; c < r.size() && c < head.size(); ++c)
      if (!r[c].empty()) {
        ++filled[c];
        text[c] += numberLike(r[c]) ? 0 : 1;
      }
  std::vector<bool> words(head.size(), false);
  for (size_t c = 0; c < head.size(); ++c) words[c] = c == 0 || 2 * text[c] > filled[c];
  return words;
}

// `symbols`: the first column holds symbols and units (a rating's), written as engineers do.
std::string tableHtml(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows, size_t from, size_t to,
                      const char* cls = nullptr, bool symbols = false) {
  auto words = wordColumns(head, rows);
  std::string o = cls ? fmt::format("<div class=\"scroll\"><table class=\"{}\">\n<thead><tr>", cls) : "<div class=\"scroll\"><table>\n<thead><tr>";
  for (size_t i = 0; i < head.size(); ++i) o += (words[i] ? "<th class=\"t\">" : "<th>") + heading(head[i]) + "</th>";
  o += "</tr></thead>\n";
  for (size_t r = from; r < to && r < rows.size(); ++r) {
    o += "<tr>";
    for (size_t c = 0; c < rows[r].size(); ++c)
      o += (c < words.size() && words[c] ? "<td class=\"t\">" : "<td>") + (symbols && c == 0 ? symbolHtml(rows[r][c]) : esc(rows[r][c])) +
           "</td>";
    o += "</tr>\n";
  }
  return o + "</table></div>\n";
}

// A table; over kFoldRows rows its first rows show on screen and the whole table folds below
// them. Paper cannot unfold: the printed page has the whole table instead.
std::string table(const std::vector<std::string>& head, const std::vector<std::vector<std::string>>& rows) {
  if (rows.size() <= kFoldRows) return tableHtml(head, rows, 0, rows.size());
  std::string all = tableHtml(head, rows, 0, rows.size());
  return "<div class=\"screen\">\n" + tableHtml(head, rows, 0, kShownWhenFolded) +
         fmt::format("<details><summary>all {} rows (the first {} above)</summary>\n{}</details>\n</div>\n", rows.size(), kShownWhenFolded, all) +
         "<div class=\"print\">\n" + all + "</div>\n";
}

// Text with `quoted` spec expressions, as the notes write them: the quotes become <code>.
std::string withCode(const std::string& text) {
  std::string e = esc(text), o;
  bool open = false;
  for (char c : e) {
    if (c != '`') {
      o += c;
      continue;
    }
    o += open ? "</code>" : "<code>";
    open = !open;
  }
  if (open) o += "</code>";
  return o;
}

std::string list(const std::vector<std::string>& items, const char* cls = nullptr) {
  if (items.empty()) return "";
  std::string o = cls ? fmt::format("<ul class=\"{}\">\n", cls) : "<ul>\n";
  for (const auto& i : items) o += "<li>" + withCode(i) + "</li>\n";
  return o + "</ul>\n";
}

std::string warningBox(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return "";
  return fmt::format("<div class=\"warnings\"><h4>{} warning{}</h4>\n{}</div>\n", warnings.size(), warnings.size() == 1 ? "" : "s",
                     list(warnings));
}

std::string anchor(const std::string& name) {
  std::string o = "gb-";
  for (char c : name) o += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
  return o;
}

std::string summaryCard(const GearboxReport& g) {
  GearboxSummary s = summarise(g);
  std::string o = fmt::format("<div class=\"card\">\n<h3><a href=\"#{}\">{}</a></h3>\n<p class=\"meta\">{}</p>\n<div class=\"cols\">\n",
                              anchor(g.name), esc(g.name), esc(s.headline));
  if (!s.inputs.empty()) {
    o += "<div><h4>Solved for</h4><dl class=\"kv\">\n";
    for (const auto& in : s.inputs) o += fmt::format("<dt>{}</dt><dd>{}</dd>\n", esc(in.label), unitHtml(in.value));
    o += "</dl></div>\n";
  }
  if (!s.design.empty()) {
    o += fmt::format("<div><h4>{}</h4><dl class=\"kv\">\n", g.count > 1 ? "Design 1" : "The design");
    for (const auto& [n, v] : s.design) o += fmt::format("<dt>{}</dt><dd>{}</dd>\n", esc(n), unitHtml(v));
    o += "</dl></div>\n";
  }
  o += "</div>\n";
  if (!s.results.empty()) o += "<h4>Key results</h4>\n" + list(s.results, "results");
  if (!s.safeties.empty()) {
    o += "<h4>Safeties</h4>\n<div class=\"scroll\"><table class=\"safety\">\n<tr><th class=\"t\">where</th><th class=\"t\">safety</th>"
         "<th>value</th><th>minimum</th><th class=\"t\"></th></tr>\n";
    for (const auto& sf : s.safeties)
      o += fmt::format("<tr class=\"{}\"><td class=\"t\">{}</td><td class=\"t\">{}</td><td class=\"v\">{}</td><td>{}</td><td class=\"t\">{}</td></tr>\n",
                       sf.ok() ? "ok" : "low", esc(sf.where), esc(sf.label), sf.computed() ? formatNumber(sf.value) : "not rated",
                       formatNumber(sf.minimum), !sf.computed() ? "see the rating" : sf.ok() ? "met" : "below the minimum");
    o += "</table></div>\n";
  }
  o += warningBox(s.warnings);
  return o + "</div>\n";
}

struct Figure {
  std::string file, caption;
};

// Every chart of the gearbox, in the order of the parts it belongs to.
std::vector<Figure> figures(const GearboxReport& g) {
  std::vector<Figure> f;
  for (const auto& sc : g.scenes)
    for (const auto& x : sc.files) f.push_back({x, x});  // the title says what it is; the caption names its file
  for (const auto& st : g.studies)
    for (const auto& x : st.files) f.push_back({x, "study " + studyName(st)});
  for (const auto& r : g.ratings)
    for (const auto& x : r.files) f.push_back({x, "rating of " + r.stage});
  for (const auto& sh : g.shafts)
    for (const auto& x : sh.files) f.push_back({x, "shaft " + sh.name});
  if (g.optimisation)
    for (const auto& x : g.optimisation->files) f.push_back({x, "optimisation"});
  if (g.monteCarlo)
    for (size_t i = 0; i < g.monteCarlo->files.size() && i < g.monteCarlo->outputs.size(); ++i)
      f.push_back({g.monteCarlo->files[i], "Monte Carlo: " + g.monteCarlo->outputs[i].quantity});
  return f;
}

std::string figureHtml(const Figure& f, const RenderOptions& ro) {
  if (ro.inlineCharts)
    for (const auto& c : *ro.inlineCharts)
      if (c.name == f.file) return fmt::format("<figure>\n{}<figcaption>{}</figcaption></figure>\n", c.svg, esc(f.caption));
  return fmt::format("<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n", esc(f.file), esc(f.file), esc(f.caption));
}

// The width a column takes on screen, estimated from its text: 8.2 px a character of the
// 14 px font, a heading breaking after its dots and underscores, and the cell padding.
double columnWidth(const std::string& head, const std::vector<std::vector<std::string>>& rows, size_t c) {
  size_t widest = 0, part = 0;
  for (char ch : head) {
    ++part;
    if (ch == '.' || ch == '_' || ch == '(') widest = std::max(widest, part), part = 0;
  }
  widest = std::max({widest, part, size_t{4}});
  for (const auto& r : rows)
    if (c < r.size()) widest = std::max(widest, r[c].size());
  return 8.2 * static_cast<double>(widest) + 20;
}

std::string designsHtml(const GearboxReport& g) {
  if (g.rows.empty()) return "";
  auto head = designHeader(g);
  std::vector<std::vector<std::string>> rows;
  for (const auto& r : g.rows) rows.push_back(designCells(r));
  std::string o = "<h3>Designs</h3>\n";
  if (head.size() > kTurnColumns && rows.size() <= kTurnRows) {
    // Turned: a row per quantity, a column per design.
    std::vector<std::string> th = {"quantity"};
    for (const auto& r : rows) th.push_back("design " + r[0]);
    std::vector<std::vector<std::string>> tr;
    for (size_t c = 1; c < head.size(); ++c) {
      std::vector<std::string> line = {head[c]};
      for (const auto& r : rows) line.push_back(c < r.size() ? r[c] : "");
      tr.push_back(line);
    }
    return o + table(th, tr);
  }
  // Wider than a 1280 px window: cut into tables of columns that fit, each opening with the
  // rank, so that every column (the safeties last among them) shows without scrolling.
  // The columns' widths on a page of 1100 px (the 1200 px body less its padding).
  std::vector<double> widths;
  for (size_t c = 0; c < head.size(); ++c) widths.push_back(columnWidth(head[c], rows, c));
  auto parts = columnGroups(widths, 1100);
  if (parts.size() > 1) {
    for (size_t p = 0; p < parts.size(); ++p) {
      std::vector<std::vector<std::string>> rs;
      for (const auto& r : rows) rs.push_back(cellsOf(r, parts[p]));
      o += fmt::format("<h4>columns {} of {}</h4>\n", p + 1, parts.size()) + table(cellsOf(head, parts[p]), rs);
    }
    return o;
  }
  return o + table(head, rows);
}

std::string sceneHtml(const SceneReport& sc, const GearboxReport& g) {
  std::string o = fmt::format("<h3>Scene {} on {}</h3>\n", esc(sc.name), esc(sc.target.empty() ? g.name : sc.target));
  if (!sc.failure.empty()) return o + "<p class=\"verdict low\">failed: " + esc(sc.failure) + "</p>\n";
  std::vector<std::vector<std::string>> rows;
  for (const auto& out : sc.outputs)
    rows.push_back({out.key, std::isfinite(out.shown) ? formatNumber(out.shown) : "none", out.unit,
                    SceneReport::ownError(out, sc.errorEstimate) ? fmt::format("{:.2e}", out.error) : ""});
  if (!rows.empty()) o += tableHtml({"output", "value", "unit", "own error estimate"}, rows, 0, rows.size());
  std::vector<std::string> items;
  if (sc.eigen) items.push_back("accuracy: generalised eigenproblem (Eigen), double precision");
  else if (!sc.integrated)
    items.push_back("accuracy: nothing integrated, the outputs read the loaded mesh's table; steady state: static");
  else
    items.push_back(fmt::format("accuracy: {}, rtol {:.0e}, atol {:.0e}{}; steady state: {}", sc.method, sc.rtol, sc.atol,
                                sc.stepRule.empty() ? "" : ", " + sc.stepRule, sc.steady));
  if (sc.errorEstimate >= 0) items.push_back(fmt::format("error estimate {:.2e} relative = {}", sc.errorEstimate, sc.errorMethod));
  if (!sc.eigen)
    items.push_back(fmt::format("cost: {} steps, {} rejected, {} RHS evaluations, {} Jacobians, {} events located", sc.steps, sc.rejected,
                                sc.rhs, sc.jacobians, sc.events));
  for (const auto& sp : sc.spectra) {
    std::vector<std::string> peaks;
    for (const auto& p : sp.peaks)
      peaks.push_back(fmt::format("{:.2f} Hz{} {}{}", p.frequency, p.harmonic ? fmt::format(" ({}x mesh)", p.harmonic) : "",
                                  formatNumber(p.amplitude / sp.scale), sp.unit.empty() ? "" : " " + sp.unit));
    items.push_back(fmt::format("{} peaks: {}", sp.key, fmt::join(peaks, "; ")));
  }
  o += list(items);
  o += warningBox(sc.warnings);
  if (!sc.model.empty())
    o += fmt::format("<details><summary>the model, {} lines</summary>\n{}</details>\n", sc.model.size(), list(sc.model, "model"));
  return o;
}

// What a rating row is: given (geometry, inputs), a result (a stress, a safety, a damage, a
// temperature, a film thickness) or an intermediate factor.
enum class RowKind { Given, Result, Factor };
RowKind kindOf(const RatingReport::Row& row) {
  static const std::vector<std::string> given = {"z", "shift", "reference_diameter", "tip_diameter", "root_diameter", "base_diameter",
                                                 "tooth_thickness", "working_pressure_angle", "sigma_Hlim", "sigma_Flim", "accuracy",
                                                 "life", "viscosity_40", "roughness_flank_rz", "roughness_root_rz", "basic_rack"};
  auto has = [&](const char* w) { return row.key.find(w) != std::string::npos; };
  if (std::find(given.begin(), given.end(), row.key) != given.end() || has("allowance") || has("backlash")) return RowKind::Given;
  if (row.minimum != RatingReport::Row::NoMinimum || has("stress") || has("safety") || has("damage") || has("temperature") ||
      has("film_thickness"))
    return RowKind::Result;
  return RowKind::Factor;
}

// The rating as three tables: what it was given, what it found (never folded), and the
// factors between them, folded on screen and whole on paper.
std::string ratingTables(const RatingReport& r) {
  auto head = ratingHeader(r);
  auto rows = ratingRows(r);
  std::vector<std::vector<std::string>> part[3];
  for (size_t i = 0; i < rows.size() && i < r.rows.size(); ++i) part[static_cast<int>(kindOf(r.rows[i]))].push_back(rows[i]);
  std::string o;
  if (!part[1].empty()) o += "<h4>stresses and safeties</h4>\n" + tableHtml(head, part[1], 0, part[1].size(), "safety-table", true);
  if (!part[0].empty()) o += "<h4>geometry and inputs</h4>\n" + tableHtml(head, part[0], 0, part[0].size(), nullptr, true);
  if (!part[2].empty())
    o += fmt::format("<details class=\"factors\"><summary>the {} influence factors</summary>\n{}</details>\n", part[2].size(),
                     tableHtml(head, part[2], 0, part[2].size(), nullptr, true));
  return o;
}

std::string ratingHtml(const RatingReport& r) {
  std::string o = fmt::format("<h3>Rating of {}{} ({})</h3>\n", esc(r.stage), r.mesh.empty() ? "" : ", mesh " + esc(r.mesh), esc(r.standard));
  bool ok = r.error.empty() && r.governingRatio >= 1;
  o += fmt::format("<p class=\"verdict {}\">{}</p>\n", ok ? "ok" : "low", esc(ratingVerdict(r)));
  if (r.error.empty()) o += ratingTables(r);
  // Its warnings in a box, as everywhere; what it leaves out and how the model factors were
  // found as lines.
  std::vector<std::string> rest;
  for (const auto& n : r.notRated) rest.push_back(fmt::format("not rated: the {}'s {}: {}", n.gear, n.what, n.reason));
  for (const auto& line : r.model) rest.push_back(line);
  o += warningBox(r.warnings);
  o += list(rest, "model");
  return o;
}

std::string gearboxDetails(const GearboxReport& g, const RenderOptions& ro) {
  std::string o = fmt::format("<section class=\"gearbox\" id=\"{}\">\n<h2>{}</h2>\n", anchor(g.name), esc(g.name));
  // Plots before any table.
  auto figs = figures(g);
  if (!figs.empty()) {
    o += "<div class=\"plots\">\n";
    for (const auto& f : figs) o += figureHtml(f, ro);
    o += "</div>\n";
  }
  o += designsHtml(g);
  std::vector<std::string> notes;
  for (const auto& c : g.columns)
    if (!c.exact) notes.push_back("intervals of `" + c.name + "` are enclosures (interval arithmetic), not exact images");
  for (const auto& n : g.notes) notes.push_back(n);
  o += list(notes, "model");
  if (g.count == 0 || g.undecided) {
    std::vector<std::vector<std::string>> f;
    for (const auto& x : g.funnel)
      f.push_back(x.domain ? std::vector<std::string>{"stage " + x.scope, "candidates", fmt::format("{:.0f}", -x.removed + 0.0), ""}
                           : std::vector<std::string>{x.scope, x.rule, fmt::format("{:.0f}", x.before), fmt::format("{:.0f}", x.removed)});
    o += "<h3>Elimination funnel</h3>\n" + table({"scope", "rule", "before", "removed"}, f);
  }
  if (g.optimisation) o += "<h3>Optimisation</h3>\n" + list(optimisationLines(*g.optimisation, false));
  if (g.monteCarlo) {
    const auto& mc = *g.monteCarlo;
    o += "<h3>Monte Carlo over the tolerances</h3>\n<p>" + esc(monteCarloHeadline(mc)) + "; tolerances " + esc(monteCarloTolerances(mc)) +
         ".</p>\n" + table(monteCarloHeader(), monteCarloRows(mc)) + list(monteCarloNotes(mc), "model");
  }
  for (const auto& r : g.ratings) o += ratingHtml(r);
  for (const auto& sh : g.shafts) {
    o += "<h3>Shaft " + esc(sh.name) + " (design 1)</h3>\n";
    for (const auto& t : shaftTables(sh)) o += (t.caption.empty() ? "" : "<p>" + esc(t.caption) + "</p>\n") + table(t.header, t.rows);
    o += list(shaftNotes(sh));
  }
  for (const auto& md : g.modifications) {
    o += "<h3>Modification of " + esc(md.stage) + "</h3>\n" + table(modificationHeader(), modificationRows(md));
  }
  for (const auto& sc : g.scenes) o += sceneHtml(sc, g);
  for (const auto& study : g.studies) {
    StudyTable st = studyTable(study, ro);
    o += "<h3>Study " + esc(st.name) + "</h3>\n" + table(st.header, st.rows) + list(st.notes, "model") + warningBox(st.warnings);
  }
  return o + "</section>\n";
}

// Printed pages: the spec, gbxc's version and the date at the top of every page, and the
// page number at the bottom (CSS page-margin boxes).
std::string pageStyle(const std::string& title, const RenderOptions& ro) {
  std::string block = title;
  if (!ro.version.empty()) block += " · gbxc " + ro.version;
  if (!ro.date.empty()) block += " · " + ro.date;
  std::string css;
  for (char c : block) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';  // a line break would end the CSS string
    if (c == '"' || c == '\\') css += '\\';
    if (c == '<') css += "\\3c ";
    else css += c;
  }
  return "<style>@page{@top-left{content:\"" + css +
         "\";font:8pt system-ui,sans-serif;color:#57606a}@bottom-right{content:\"page \" counter(page) \" of \" counter(pages);"
         "font:8pt system-ui,sans-serif;color:#57606a}}</style>\n";
}

} // namespace

namespace {

// The summary section: per gearbox what it is, what was found and what governs.
std::string summarySection(const std::vector<GearboxReport>& reports, const RenderOptions& ro,
                           const std::string& title) {
  std::string o = "<section class=\"summary\">\n<header><h1>" + esc(title) + "</h1>\n";
  std::vector<std::string> meta;
  if (!ro.version.empty()) meta.push_back("gbxc " + ro.version);
  if (!ro.date.empty()) meta.push_back(ro.date);
  meta.push_back(fmt::format("{} gearbox{}", reports.size(), reports.size() == 1 ? "" : "es"));
  o += "<p class=\"meta\">" + esc(fmt::format("{}", fmt::join(meta, " · "))) + "</p></header>\n";
  for (const auto& g : reports) o += summaryCard(g);
  return o + "</section>\n";
}

} // namespace

std::string renderHtml(const std::vector<GearboxReport>& reports, const RenderOptions& ro) {
  std::string title = ro.title.empty() ? "gbxc report" : ro.title;
  std::string o = "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
                  "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
                  esc(title) + " · gbxc</title>\n" + kStyle + pageStyle(title, ro) + "</head><body>\n";
  // docs/reports.md: the body opens with the summary.
  o += summarySection(reports, ro, title);
  for (const auto& g : reports) o += gearboxDetails(g, ro);
  return o + "</body></html>\n";
}

std::string renderHtmlSummary(const std::vector<GearboxReport>& reports, const RenderOptions& ro) {
  return std::string(kStyle) + summarySection(reports, ro, ro.title.empty() ? "gbxc report" : ro.title);
}

} // namespace gbx::rt
