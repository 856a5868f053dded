#include "search/StageFilter.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include <fmt/format.h>

#include "catalogue/StageKinds.h"
#include "model/Deadline.h"
#include "model/StageKind.h"
#include "search/Narrow.h"

namespace gbx::rt {

namespace {

struct StageRule {
  std::string text;
  std::function<Truth(const Evaluator&, const Assignment&)> test;
  const Conjunct* conjunct = nullptr;
};

// The rules the stage's kind implies, before the spec's own.
std::vector<StageRule> implicitRules(const Model& m, int s) {
  std::vector<StageRule> rules;
  for (const auto& r : m.info(s).kind->rules)
    rules.push_back({r.text, [s, test = r.test](const Evaluator& ev, const Assignment& a) {
                       return test(KindContext{ev, s, a});
                     }});
  return rules;
}

// By exact ratio, then by values: where the doubles differ by far more than their rounding
// they decide, and only near-ties compare the rationals.
void sortByRatio(std::vector<Candidate>& candidates) {
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& x, const Candidate& y) {
    if (std::fabs(x.r - y.r) > 1e-12 * std::max(std::fabs(x.r), std::fabs(y.r))) return x.r < y.r;
    int c = x.ratio.compare(y.ratio);
    return c != 0 ? c < 0 : x.idx < y.idx;
  });
}

// A thread's share of a stage's filter.
struct Chunk {
  std::vector<Candidate> out;
  std::vector<double> removed, unevaluable;
  double jointRemoved = 0;
  double stoppedAt = -1;
};

// The threads' shares merged: the candidates by ratio, the funnel and the notes.
StageResult collect(std::vector<Chunk>& chunks, const std::vector<StageRule>& rules, const std::string& name,
                    double total) {
  StageResult res;
  if (std::any_of(chunks.begin(), chunks.end(), [](const Chunk& c) { return c.stoppedAt >= 0; })) {
    res.timedOutAt = 0;
    for (const auto& c : chunks) res.timedOutAt += (c.stoppedAt >= 0 ? c.stoppedAt : 1.0) / static_cast<double>(chunks.size());
    return res;
  }
  double before = total;
  res.funnel.push_back({"domain", name, 0, -before, true});
  for (size_t r = 0; r < rules.size(); ++r) {
    double removed = 0, unevaluable = 0;
    for (const auto& ch : chunks) {
      removed += ch.removed[r];
      unevaluable += ch.unevaluable[r];
    }
    res.funnel.push_back({rules[r].text, name, before, removed});
    if (unevaluable > 0)
      res.notes.push_back(
          fmt::format("stage {}: `{}` could not be evaluated for {:.0f} of its {:.0f} candidates, which it removed "
                      "(a rating refuses their geometry, or an input is missing)",
                      name, rules[r].text, unevaluable, before));
    before -= removed;
  }
  double joint = 0;
  for (const auto& ch : chunks)
    joint += ch.jointRemoved;
  if (joint > 0) {
    res.funnel.push_back({"no freedom value satisfies the rules together", name, before, joint});
    before -= joint;
  }
  if (chunks.size() == 1) {
    res.candidates = std::move(chunks[0].out);
  } else {
    size_t kept = 0;
    for (const auto& ch : chunks)
      kept += ch.out.size();
    res.candidates.reserve(kept);
    for (auto& ch : chunks)
      for (auto& c : ch.out)
        res.candidates.push_back(std::move(c));
  }
  sortByRatio(res.candidates);
  return res;
}

} // namespace

std::string stageRanges(const Model& m, int s) {
  std::vector<std::string> parts;
  for (int sl : m.stages[static_cast<size_t>(s)].slots) {
    const Slot& slot = m.slots[static_cast<size_t>(sl)];
    if (slot.values.size() < 2) continue;
    parts.push_back(fmt::format("`{}` {}..{} ({} values)", slot.path, slot.values.front().lo, slot.values.back().lo,
                                slot.values.size()));
  }
  return fmt::format("{}", fmt::join(parts, " x "));
}

double stageDomain(const Model& m, int s) {
  double domain = 1;
  for (int sl : m.stages[static_cast<size_t>(s)].slots)
    domain *= static_cast<double>(m.slots[static_cast<size_t>(sl)].values.size());
  return domain;
}

std::string timeLimitMessage(const std::string& doing, double done, double limit, double space) {
  std::string estimate = done > 0.001 ? fmt::format("; the whole would take about {:.3g} s", limit / done) : "";
  return fmt::format("time limit of {:g} s (--time-limit) reached while {} ({:.1f} % of {:.3g} done{}); narrow the ranges "
                     "or raise --time-limit",
                     limit, doing, 100 * done, space, estimate);
}

StageResult filterStage(const Evaluator& ev, int s, const std::vector<const Conjunct*>& local, int jobs, bool narrow) {
  const Model& m = ev.model();
  const StageInfo& info = m.stages[static_cast<size_t>(s)];
  auto rules = implicitRules(m, s);
  for (const auto* c : local)
    rules.push_back({c->text, nullptr, c});
  std::vector<size_t> sizes;
  size_t total = 1;  // within the budget (checked by the caller), so no overflow
  for (int sl : info.slots) {
    sizes.push_back(m.slots[static_cast<size_t>(sl)].values.size());
    total *= sizes.back();
  }
  int threads = std::max(1, std::min<int>(jobs, static_cast<int>(total / 2048) + 1));
  std::vector<Chunk> chunks(static_cast<size_t>(threads));
  auto work = [&](int t) {
    Chunk& ch = chunks[static_cast<size_t>(t)];
    ch.removed.assign(rules.size(), 0);
    ch.unevaluable.assign(rules.size(), 0);
    Assignment a(m);
    size_t begin = total * static_cast<size_t>(t) / static_cast<size_t>(threads);
    size_t end = total * static_cast<size_t>(t + 1) / static_cast<size_t>(threads);
    std::vector<const Conjunct*> open;
    std::vector<int> idx(info.slots.size());
    ch.out.reserve(std::min<size_t>(end - begin, 1 << 16));
    for (size_t k = begin; k < end; ++k) {
      if ((k - begin) % 16 == 0 && Deadline::expired()) {
        ch.stoppedAt = static_cast<double>(k - begin) / static_cast<double>(end - begin);
        break;
      }
      size_t rest = k;
      for (size_t i = info.slots.size(); i-- > 0;) {
        idx[i] = static_cast<int>(rest % sizes[i]);
        rest /= sizes[i];
        a.choice[static_cast<size_t>(info.slots[i])] = idx[i];
      }
      open.clear();
      bool dead = false;
      for (size_t r = 0; r < rules.size() && !dead; ++r) {
        Truth t = rules[r].test ? rules[r].test(ev, a) : truthOf(ev.eval(*rules[r].conjunct->expr, a));
        if (t == Truth::False) {
          ch.removed[r] += 1;
          dead = true;
        } else if (t == Truth::Unknown) {
          if (rules[r].conjunct && rules[r].conjunct->freedom)
            open.push_back(rules[r].conjunct);
          else {
            ch.removed[r] += 1; // cannot be evaluated: counted, and said in a note
            ch.unevaluable[r] += 1;
            dead = true;
          }
        }
      }
      if (dead) continue;
      // A candidate is made for the combinations its rules leave (a third of them, or fewer).
      Candidate c;
      c.idx = idx;
      if (!open.empty()) {
        Verdict v = decide(ev, a, open, info.freedoms);
        if (v == Verdict::Infeasible) {
          ch.jointRemoved += 1;
          continue;
        }
        c.undecided = v == Verdict::Undecided;
        if (narrow && !c.undecided)
          for (int f : info.freedoms)
            c.box.push_back(feasibleSpan(ev, a, open, f));
      }
      Value r = ev.derived(s, Q::Ratio, a);
      if (!r.exact) continue;
      c.ratio = *r.exact;
      c.r = r.lo;
      ch.out.push_back(std::move(c));
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
    pool.emplace_back(work, t);
  work(0);
  for (auto& th : pool)
    th.join();

  return collect(chunks, rules, info.ir->name, static_cast<double>(total));
}

} // namespace gbx::rt
