// Scratch space per thread, kept between calls, that nests: a call re-entering the same code on
// the same thread (a restriction of a restriction: ReducedSystem over ReducedSystem) gets a level
// of its own instead of the buffers its caller is still reading. A level lives while its
// NestedScratch does; each Scratch type has its own levels.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

namespace sympathy::detail {

template <class Scratch>
class NestedScratch {
 public:
  NestedScratch() {
    auto& levels = pool();
    if (levels.size() <= depth()) levels.push_back(std::make_unique<Scratch>());
    scratch_ = levels[depth()++].get();
  }
  ~NestedScratch() { --depth(); }
  NestedScratch(const NestedScratch&) = delete;
  NestedScratch& operator=(const NestedScratch&) = delete;
  Scratch& operator*() const { return *scratch_; }
  Scratch* operator->() const { return scratch_; }

 private:
  static std::vector<std::unique_ptr<Scratch>>& pool() {
    thread_local std::vector<std::unique_ptr<Scratch>> levels;
    return levels;
  }
  static std::size_t& depth() {
    thread_local std::size_t d = 0;
    return d;
  }
  Scratch* scratch_;
};

}  // namespace sympathy::detail
