#pragma once
// A small cache per thread of the last results of a pure function, by exact key: the same
// design is rated, or its loaded mesh tabulated, once however many quantities read it.
#include <cstddef>
#include <map>
#include <utility>

namespace gbx::rt {

// At most `Capacity` results: past it the cache starts again.
template <class K, class V, size_t Capacity = 64> class Recent {
public:
  const V* find(const K& k) const {
    auto it = map_.find(k);
    return it == map_.end() ? nullptr : &it->second;
  }
  const V& put(K k, V v) {
    if (map_.size() >= Capacity) map_.clear();
    return map_.insert_or_assign(std::move(k), std::move(v)).first->second;
  }

private:
  std::map<K, V> map_;
};

} // namespace gbx::rt
