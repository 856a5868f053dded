#pragma once
// What the ranks exchange is numbers (par::map's results): a record written as doubles and
// read back in the same order. Values one by one, lists after their length, counts as two
// 32-bit halves (exact in a double whatever their size). A short record reads as zeros.
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

namespace gbx::rt::par {

class NumbersOut {
public:
  void put(double x) { v_.push_back(x); }
  void count(unsigned long long c) {
    put(static_cast<double>(c >> 32));
    put(static_cast<double>(c & 0xFFFFFFFFull));
  }
  template <class List>
  void list(const List& x) {
    put(static_cast<double>(x.size()));
    for (auto e : x) put(static_cast<double>(e));
  }
  std::vector<double> take() { return std::move(v_); }

private:
  std::vector<double> v_;
};

class NumbersIn {
public:
  explicit NumbersIn(const std::vector<double>& v) : v_(v) {}
  double next() { return at_ < v_.size() ? v_[at_++] : 0.0; }
  unsigned long long count() {
    auto hi = static_cast<unsigned long long>(next());
    return hi << 32 | static_cast<unsigned long long>(next());
  }
  template <class T>
  void list(std::vector<T>& x) {
    x.resize(static_cast<size_t>(next()));
    for (auto& e : x) e = static_cast<T>(next());
  }

private:
  const std::vector<double>& v_;
  size_t at_ = 0;
};

} // namespace gbx::rt::par
