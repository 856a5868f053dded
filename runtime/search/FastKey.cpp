#include "search/FastKey.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace gbx::rt {

namespace {

using ir::Op;

std::optional<double> constantOf(const ir::Expr& e) {
  if (e.op != Op::Const || !e.type.isNumber()) return std::nullopt;
  double v = e.value.toDouble();
  return std::isfinite(v) ? std::optional<double>(v) : std::nullopt;
}

using Iv = std::pair<double, double>;
constexpr double kInf = INFINITY;

Iv mulIv(Iv a, Iv b) {
  double p[4] = {a.first * b.first, a.first * b.second, a.second * b.first, a.second * b.second};
  double lo = p[0], hi = p[0];
  for (double x : p) {
    if (std::isnan(x)) return {-kInf, kInf};
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  return {lo, hi};
}

Iv powIv(Iv a, int n) {
  if (n == 0) return {1, 1};
  if (n < 0) {
    Iv p = powIv(a, -n);
    if (p.first <= 0 && p.second >= 0) return {-kInf, kInf};
    return mulIv({1, 1}, {1 / p.second, 1 / p.first});
  }
  if (n % 2 == 1) return {std::pow(a.first, n), std::pow(a.second, n)};
  double lo = a.first <= 0 && a.second >= 0 ? 0 : std::min(std::fabs(a.first), std::fabs(a.second));
  double hi = std::max(std::fabs(a.first), std::fabs(a.second));
  return {std::pow(lo, n), std::pow(hi, n)};
}

} // namespace

// ---- RatioFn ------------------------------------------------------------------------------

bool RatioFn::emit(const ir::Expr& e) {
  if (code_.size() > 256) return false;
  auto unary = [&](K k) {
    if (e.args.size() != 1 || !e.args[0] || !emit(*e.args[0])) return false;
    code_.push_back({k});
    return true;
  };
  auto fold = [&](K k) {
    if (e.args.empty()) return false;
    for (size_t i = 0; i < e.args.size(); ++i) {
      if (!e.args[i] || !emit(*e.args[i])) return false;
      if (i > 0) code_.push_back({k});
    }
    return true;
  };
  switch (e.op) {
  case Op::Const: {
    auto c = constantOf(e);
    if (!c) return false;
    code_.push_back(
        {K::Const, *c, 0, e.value.isRational() ? std::optional<Rational>(e.value.rational()) : std::nullopt});
    return true;
  }
  case Op::Quantity:
    if (e.ref.owner != ir::QuantityRef::Gearbox || e.ref.key != Q::Ratio) return false;
    code_.push_back({K::Ratio});
    return true;
  case Op::Neg: return unary(K::Neg);
  case Op::Add: return fold(K::Add);
  case Op::Sub: return e.args.size() == 1 ? unary(K::Neg) : fold(K::Sub);
  case Op::Mul: return fold(K::Mul);
  case Op::Div: return fold(K::Div);
  case Op::Pow: {
    if (e.args.size() != 2 || !e.args[1]) return false;
    auto n = constantOf(*e.args[1]);
    if (!n || *n != std::round(*n) || std::fabs(*n) > 64 || !emit(*e.args[0])) return false;
    code_.push_back({K::PowI, 0, static_cast<int>(*n)});
    return true;
  }
  case Op::Call:
    switch (e.fn) {
    case cat::Fn::Abs: return unary(K::Abs);
    case cat::Fn::Sqrt: return unary(K::Sqrt);
    case cat::Fn::Min: return fold(K::Min);
    case cat::Fn::Max: return fold(K::Max);
    default: return false;
    }
  default: return false;
  }
}

std::optional<RatioFn> RatioFn::compile(const ir::Expr& e) {
  RatioFn f;
  if (!f.emit(e)) return std::nullopt;
  // `abs(ratio - c)`, the usual ranking by closeness to a target: evaluated without the
  // interpreter (the same operations, so the same numbers).
  const auto& c = f.code_;
  f.absDiff_ = c.size() == 4 && c[0].k == K::Ratio && c[1].k == K::Const && c[2].k == K::Sub && c[3].k == K::Abs;
  if (f.absDiff_) f.target_ = c[1].c;
  return f;
}

double RatioFn::at(double r) const {
  if (absDiff_) return std::fabs(r - target_);
  std::array<double, 64> st;
  size_t n = 0;
  for (const Node& x : code_) {
    if (n + 1 >= st.size()) return NAN;
    switch (x.k) {
    case K::Const: st[n++] = x.c; break;
    case K::Ratio: st[n++] = r; break;
    case K::Neg: st[n - 1] = -st[n - 1]; break;
    case K::Abs: st[n - 1] = std::fabs(st[n - 1]); break;
    case K::Sqrt: st[n - 1] = std::sqrt(st[n - 1]); break;
    case K::PowI: st[n - 1] = std::pow(st[n - 1], x.n); break;
    case K::Add: --n, st[n - 1] += st[n]; break;
    case K::Sub: --n, st[n - 1] -= st[n]; break;
    case K::Mul: --n, st[n - 1] *= st[n]; break;
    case K::Div: --n, st[n - 1] /= st[n]; break;
    case K::Min: --n, st[n - 1] = std::min(st[n - 1], st[n]); break;
    case K::Max: --n, st[n - 1] = std::max(st[n - 1], st[n]); break;
    }
  }
  return n == 1 ? st[0] : NAN;
}

std::optional<Rational> RatioFn::exactAt(const Rational& ratio) const {
  using units::i128;
  struct Frac {
    i128 n, d; // d > 0, not reduced
  };
  // Parts below 2^62: a product of two, or a sum of two such products, fits 128 bits.
  const i128 cap = static_cast<i128>(1) << 62;
  auto ok = [&](const Frac& f) { return f.n < cap && f.n > -cap && f.d < cap; };
  auto reduced = [&](Frac& f) {
    if (ok(f)) return true;
    Rational r = Rational::make(f.n, f.d);
    f = {r.num(), r.den()};
    return ok(f);
  };
  std::array<Frac, 64> st;
  size_t n = 0;
  auto less = [](const Frac& a, const Frac& b) { return a.n * b.d < b.n * a.d; };
  for (const Node& x : code_) {
    if (n + 1 >= st.size()) return std::nullopt;
    switch (x.k) {
    case K::Const:
      if (!x.exact) return std::nullopt;
      st[n++] = {x.exact->num(), x.exact->den()};
      break;
    case K::Ratio: st[n++] = {ratio.num(), ratio.den()}; break;
    case K::Neg: st[n - 1].n = -st[n - 1].n; break;
    case K::Abs: st[n - 1].n = st[n - 1].n < 0 ? -st[n - 1].n : st[n - 1].n; break;
    case K::Sqrt: return std::nullopt;
    case K::PowI: {
      Frac b = st[n - 1], r{1, 1};
      int e = x.n < 0 ? -x.n : x.n;
      for (int i = 0; i < e; ++i) {
        r = {r.n * b.n, r.d * b.d};
        if (!reduced(r)) return std::nullopt;
      }
      if (x.n < 0) {
        if (r.n == 0) return std::nullopt;
        r = r.n < 0 ? Frac{-r.d, -r.n} : Frac{r.d, r.n};
      }
      st[n - 1] = r;
      break;
    }
    case K::Add:
    case K::Sub: {
      --n;
      Frac a = st[n - 1], b = st[n];
      st[n - 1] = {x.k == K::Add ? a.n * b.d + b.n * a.d : a.n * b.d - b.n * a.d, a.d * b.d};
      break;
    }
    case K::Mul: --n, st[n - 1] = {st[n - 1].n * st[n].n, st[n - 1].d * st[n].d}; break;
    case K::Div: {
      --n;
      Frac a = st[n - 1], b = st[n];
      if (b.n == 0) return std::nullopt;
      st[n - 1] = b.n < 0 ? Frac{-a.n * b.d, a.d * -b.n} : Frac{a.n * b.d, a.d * b.n};
      break;
    }
    case K::Min: --n, st[n - 1] = less(st[n], st[n - 1]) ? st[n] : st[n - 1]; break;
    case K::Max: --n, st[n - 1] = less(st[n - 1], st[n]) ? st[n] : st[n - 1]; break;
    }
    if (!reduced(st[n - 1])) return std::nullopt;
  }
  if (n != 1) return std::nullopt;
  return Rational::make(st[0].n, st[0].d);
}

std::pair<double, double> RatioFn::overProgram(double lo, double hi) const {
  // Uninitialised: the join asks this a million times, and zeroing 64 pairs each time cost
  // more than the program.
  union Stack {
    Stack() {}
    Iv v[64];
  } stack;
  Iv* st = stack.v;
  constexpr size_t depth = 64;
  size_t n = 0;
  for (const Node& x : code_) {
    if (n + 1 >= depth) return {-kInf, kInf};
    switch (x.k) {
    case K::Const: st[n++] = {x.c, x.c}; break;
    case K::Ratio: st[n++] = {lo, hi}; break;
    case K::Neg: st[n - 1] = {-st[n - 1].second, -st[n - 1].first}; break;
    case K::Abs: {
      auto [a, b] = st[n - 1];
      st[n - 1] = a >= 0 ? Iv{a, b} : b <= 0 ? Iv{-b, -a} : Iv{0, std::max(-a, b)};
      break;
    }
    case K::Sqrt:
      st[n - 1] = {std::sqrt(std::max(st[n - 1].first, 0.0)), std::sqrt(std::max(st[n - 1].second, 0.0))};
      break;
    case K::PowI: st[n - 1] = powIv(st[n - 1], x.n); break;
    case K::Add: --n, st[n - 1] = {st[n - 1].first + st[n].first, st[n - 1].second + st[n].second}; break;
    case K::Sub: --n, st[n - 1] = {st[n - 1].first - st[n].second, st[n - 1].second - st[n].first}; break;
    case K::Mul: --n, st[n - 1] = mulIv(st[n - 1], st[n]); break;
    case K::Div: {
      --n;
      auto d = st[n];
      st[n - 1] = d.first <= 0 && d.second >= 0 ? Iv{-kInf, kInf} : mulIv(st[n - 1], {1 / d.second, 1 / d.first});
      break;
    }
    case K::Min:
      --n, st[n - 1] = {std::min(st[n - 1].first, st[n].first), std::min(st[n - 1].second, st[n].second)};
      break;
    case K::Max:
      --n, st[n - 1] = {std::max(st[n - 1].first, st[n].first), std::max(st[n - 1].second, st[n].second)};
      break;
    }
  }
  if (n != 1 || std::isnan(st[0].first) || std::isnan(st[0].second)) return {-kInf, kInf};
  return st[0];
}

// ---- FastKey ------------------------------------------------------------------------------

namespace {

void terms(const Model& m, const ir::Expr& e, double coef, std::vector<std::pair<const ir::Expr*, double>>& out,
           int depth) {
  auto arg = [&](size_t i) -> const ir::Expr& { return *e.args[i]; };
  bool argsOk = std::all_of(e.args.begin(), e.args.end(), [](const ir::ExprPtr& a) { return a != nullptr; });
  if (depth < 64 && argsOk) switch (e.op) {
    case Op::Add:
      for (size_t i = 0; i < e.args.size(); ++i)
        terms(m, arg(i), coef, out, depth + 1);
      return;
    case Op::Sub:
      if (e.args.size() == 1) {
        terms(m, arg(0), -coef, out, depth + 1);
        return;
      }
      for (size_t i = 0; i < e.args.size(); ++i)
        terms(m, arg(i), i == 0 ? coef : -coef, out, depth + 1);
      return;
    case Op::Neg: terms(m, arg(0), -coef, out, depth + 1); return;
    case Op::Mul:
      if (e.args.size() == 2) {
        if (auto c = constantOf(arg(0))) return terms(m, arg(1), coef * *c, out, depth + 1);
        if (auto c = constantOf(arg(1))) return terms(m, arg(0), coef * *c, out, depth + 1);
      }
      break;
    case Op::Div:
      if (e.args.size() == 2)
        if (auto c = constantOf(arg(1)); c && *c != 0) return terms(m, arg(0), coef / *c, out, depth + 1);
      break;
    case Op::Let:
      if (e.let >= 0 && static_cast<size_t>(e.let) < m.gearbox.lets.size() &&
          m.gearbox.lets[static_cast<size_t>(e.let)].expr)
        return terms(m, *m.gearbox.lets[static_cast<size_t>(e.let)].expr, coef, out, depth + 1);
      break;
    default: break;
    }
  out.push_back({&e, coef});
}

} // namespace

std::optional<FastKey> FastKey::build(const Evaluator& ev, const ir::Expr& e, bool maximise,
                                      const std::vector<size_t>& candidates, const ReadsOf& reads, const Place& place) {
  const Model& m = ev.model();
  FastKey k;
  k.tableOf_.assign(candidates.size(), -1);
  std::vector<std::pair<const ir::Expr*, double>> leaves;
  terms(m, e, maximise ? -1.0 : 1.0, leaves, 0);
  for (const auto& [leaf, coef] : leaves) {
    if (auto f = RatioFn::compile(*leaf)) {
      k.ratio_.emplace_back(coef, std::move(*f));
      continue;
    }
    Reads r = reads(*leaf);
    if (r.other || r.stages.size() > 1) return std::nullopt;
    if (r.stages.empty()) {
      Value v = ev.eval(*leaf, Assignment(m));
      if (!v.isNumber() || v.lo != v.hi) return std::nullopt;
      k.constant_ += coef * v.lo;
      continue;
    }
    int s = *r.stages.begin();
    if (s < 0 || static_cast<size_t>(s) >= candidates.size()) return std::nullopt;
    if (k.tableOf_[static_cast<size_t>(s)] < 0) {
      k.tableOf_[static_cast<size_t>(s)] = static_cast<int>(k.tables_.size());
      k.tables_.push_back({s, std::vector<double>(candidates[static_cast<size_t>(s)], 0.0), 0});
    }
    Table& t = k.tables_[static_cast<size_t>(k.tableOf_[static_cast<size_t>(s)])];
    Assignment a(m);
    for (size_t c = 0; c < t.g.size(); ++c) {
      place(a, s, c);
      Value v = ev.eval(*leaf, a);
      // Where the evaluator has no number the whole key is infinite, whatever the sign.
      t.g[c] = v.isNumber() && v.lo == v.hi && std::isfinite(t.g[c]) ? t.g[c] + coef * v.lo : INFINITY;
    }
  }
  double magnitude = std::fabs(k.constant_);
  for (auto& t : k.tables_) {
    t.least = t.g.empty() ? 0.0 : *std::min_element(t.g.begin(), t.g.end());
    double most = 0;
    for (double x : t.g)
      if (std::isfinite(x)) most = std::max(most, std::fabs(x));
    magnitude += most;
  }
  k.rounding_ = 1e-12 * magnitude * static_cast<double>(k.tables_.size() + 2);
  return k;
}

// ---- RangeMin -----------------------------------------------------------------------------

RangeMin::RangeMin(const std::vector<double>& v) {
  levels_.push_back(v);
  for (size_t w = 1; 2 * w <= v.size(); w *= 2) {
    const auto& prev = levels_.back();
    std::vector<double> next(prev.size() - w);
    for (size_t i = 0; i < next.size(); ++i)
      next[i] = std::min(prev[i], prev[i + w]);
    levels_.push_back(std::move(next));
  }
}

double RangeMin::least(size_t from, size_t to) const {
  size_t len = to - from, lvl = 0;
  while ((size_t{2} << lvl) <= len)
    ++lvl;
  const auto& L = levels_[lvl];
  return std::min(L[from], L[to - (size_t{1} << lvl)]);
}

} // namespace gbx::rt
