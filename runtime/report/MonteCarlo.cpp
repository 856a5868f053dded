#include "report/MonteCarlo.h"

#include <cmath>

#include <fmt/format.h>

#include "diag/Diagnostic.h"
#include "report/Numbers.h"

namespace gbx::rt {

namespace {

std::string probability(double p) { return fmt::format("{:g}", p); }

// A statistic's value and its error in the quantity's display unit (an error is a difference:
// the unit's zero does not apply to it).
std::string shownError(const MonteCarloReport::Output& o, double si) { return formatNumber(si / o.unit.scale); }

struct Stat {
  std::string name;  // as the report and the CSV name it
  double value = 0, error = NAN;
  long sample = -1;
  bool difference = false;  // a spread, not a value: a unit's zero (degC) does not apply
};

// A statistic in the quantity's display unit.
double shownStat(const MonteCarloReport::Output& o, const Stat& s) { return s.difference ? s.value / o.unit.scale : o.unit.shown(s.value); }

std::vector<Stat> stats(const MonteCarloReport::Output& o) {
  std::vector<Stat> s;
  s.push_back({"nominal", o.nominal});
  s.push_back({"mean", o.mean, o.meanError});
  s.push_back({"standard_deviation", o.stdDev, NAN, -1, true});
  for (const auto& q : o.quantiles) s.push_back({"quantile " + probability(q.p), q.value, q.error});
  s.push_back({"min", o.min});
  s.push_back({"max", o.max});
  if (o.worstSample >= 0) s.push_back({"worst", o.values[static_cast<size_t>(o.worstSample)], NAN, o.worstSample});
  return s;
}

} // namespace

std::string monteCarloHeadline(const MonteCarloReport& r) {
  return fmt::format("{} samples of the tolerances at design 1, {} ({}), seed {}", r.samples, r.distribution,
                     r.uniform ? "between the bounds" : "each ± is three standard deviations", r.seed);
}

std::string monteCarloTolerances(const MonteCarloReport& r) {
  std::string o;
  for (const auto& t : r.tolerances)
    o += fmt::format("{}{} ± {:g}{}", o.empty() ? "" : ", ", t.target, t.amount, t.unit.empty() ? "" : " " + t.unit);
  return o;
}

std::vector<std::string> monteCarloHeader() { return {"quantity", "unit", "statistic", "value", "standard error", "sample"}; }

std::vector<std::vector<std::string>> monteCarloRows(const MonteCarloReport& r) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& o : r.outputs) {
    bool first = true;
    for (const auto& s : stats(o)) {
      rows.push_back({first ? o.quantity : "", first ? o.unit.name : "", s.name, formatNumber(shownStat(o, s)),
                      std::isfinite(s.error) ? shownError(o, s.error) : "", s.sample >= 0 ? std::to_string(s.sample + 1) : ""});
      first = false;
    }
  }
  return rows;
}

std::vector<std::string> monteCarloNotes(const MonteCarloReport& r) {
  std::vector<std::string> notes;
  if (!r.failure.empty()) notes.push_back(r.failure);
  for (const auto& w : r.warnings) notes.push_back("warning: " + w);
  notes.push_back(fmt::format("standard errors: of a mean, the standard deviation over sqrt({}); of a quantile p, half the spread "
                              "of the order statistics sqrt(n p (1 - p)) either side of n p (no distribution assumed), none "
                              "where fewer than five samples lie beyond the quantile; four times the samples halve them",
                              r.samples));
  notes.push_back(fmt::format("the same seed draws the same samples on any number of threads or ranks; `worst` is the worst "
                              "sample, `mean` the samples' mean{}",
                              r.uniform ? "" : "; a normal deviation beyond its tolerance is drawn again (the part would fail "
                                               "inspection)"));
  return notes;
}

std::string monteCarloJson(const MonteCarloReport& r) {
  using diag::jsonEscape;
  std::string o = fmt::format("{{\"samples\": {}, \"distribution\": \"{}\", \"seed\": {}, \"tolerances\": [", r.samples,
                              jsonEscape(r.distribution), r.seed);
  for (size_t i = 0; i < r.tolerances.size(); ++i)
    o += fmt::format("{}{{\"target\": \"{}\", \"amount\": {}}}", i ? ", " : "", jsonEscape(r.tolerances[i].target),
                     jsonNumber(r.tolerances[i].si));
  o += "], \"outputs\": [";
  for (size_t i = 0; i < r.outputs.size(); ++i) {
    const auto& x = r.outputs[i];
    o += fmt::format("{}{{\"quantity\": \"{}\", \"nominal\": {}, \"mean\": {}, \"mean_standard_error\": {}, \"standard_deviation\": {}, "
                     "\"min\": {}, \"max\": {}, \"quantiles\": [",
                     i ? ", " : "", jsonEscape(x.quantity), jsonNumber(x.nominal), jsonNumber(x.mean), jsonNumber(x.meanError),
                     jsonNumber(x.stdDev), jsonNumber(x.min), jsonNumber(x.max));
    for (size_t k = 0; k < x.quantiles.size(); ++k)
      o += fmt::format("{}{{\"p\": {}, \"value\": {}, \"standard_error\": {}}}", k ? ", " : "", jsonNumber(x.quantiles[k].p),
                       jsonNumber(x.quantiles[k].value), jsonNumber(x.quantiles[k].error));
    o += "], \"worst\": ";
    o += x.worstSample >= 0 ? fmt::format("{{\"value\": {}, \"sample\": {}}}", jsonNumber(x.values[static_cast<size_t>(x.worstSample)]),
                                          x.worstSample + 1)
                            : "null";
    o += ", \"histogram\": {\"edges\": [";
    for (size_t k = 0; k < x.edges.size(); ++k) o += (k ? ", " : "") + jsonNumber(x.edges[k]);
    o += "], \"counts\": [";
    for (size_t k = 0; k < x.counts.size(); ++k) o += (k ? ", " : "") + std::to_string(x.counts[k]);
    o += "]}}";
  }
  o += "]";
  if (!r.failure.empty()) o += fmt::format(", \"failure\": \"{}\"", jsonEscape(r.failure));
  if (!r.warnings.empty()) {
    o += ", \"warnings\": [";
    for (size_t i = 0; i < r.warnings.size(); ++i) o += fmt::format("{}\"{}\"", i ? ", " : "", jsonEscape(r.warnings[i]));
    o += "]";
  }
  return o + "}";
}

std::vector<std::vector<std::string>> monteCarloCsvRows(const std::string& gearbox, const MonteCarloReport& r) {
  std::vector<std::vector<std::string>> rows;
  auto num = [](double v) { return csvNumber(v); };
  for (const auto& o : r.outputs)
    for (const auto& s : stats(o)) {
      std::string name = s.name;
      for (auto& c : name)
        if (c == ' ') c = '_';
      rows.push_back({gearbox, o.quantity, o.unit.name, name, num(shownStat(o, s)),
                      std::isfinite(s.error) ? num(s.error / o.unit.scale) : "", s.sample >= 0 ? std::to_string(s.sample + 1) : ""});
    }
  return rows;
}

std::vector<std::string> sampleCsvHeader(const MonteCarloReport& r) {
  std::vector<std::string> h = {"gearbox", "sample"};
  for (const auto& t : r.tolerances) h.push_back(t.target + " deviation" + (t.unit.empty() ? "" : " [" + t.unit + "]"));
  for (const auto& o : r.outputs) h.push_back(o.quantity + (o.unit.name.empty() ? "" : " [" + o.unit.name + "]"));
  return h;
}

std::vector<std::vector<std::string>> sampleCsvRows(const std::string& gearbox, const MonteCarloReport& r) {
  std::vector<std::vector<std::string>> rows;
  for (long k = 0; k < r.samples; ++k) {
    std::vector<std::string> row = {gearbox, std::to_string(k + 1)};
    size_t ki = static_cast<size_t>(k);
    for (size_t i = 0; i < r.tolerances.size(); ++i)
      row.push_back(ki < r.deviations.size() ? csvNumber(r.deviations[ki][i], r.tolerances[i].unit, r.tolerances[i].scale) : "");
    for (const auto& o : r.outputs) row.push_back(ki < o.values.size() ? csvNumber(o.values[ki], o.unit.name, o.unit.scale, o.unit.offset) : "");
    rows.push_back(std::move(row));
  }
  return rows;
}

} // namespace gbx::rt
