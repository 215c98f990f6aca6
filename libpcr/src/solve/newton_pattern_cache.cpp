// Process-wide cache of Newton pattern analyses (newton_pattern_cache.hpp).
#include "newton_pattern_cache.hpp"

#include <algorithm>
#include <deque>
#include <mutex>

namespace pcr {
namespace {

// Bounds: a few structures (a program solves a handful of discretisations), and about 32 bytes kept per
// Jacobian nonzero (the key's column indices, the value map, J_free's indices and values, the structured
// LU's slots): at most 2^21 nonzeros in all, ~64 MB; a pattern above a quarter of that is not kept.
constexpr size_t kMaxEntries = 32;
constexpr long kMaxStoredNonzeros = 2L << 20;

struct Entry {
  std::vector<int> outer, inner, reduced_column, column_groups;
  NewtonLinearSolver linear_solver{};
  std::shared_ptr<const NewtonPatternAnalysis> analysis;
};

class Registry {
 public:
  std::shared_ptr<const NewtonPatternAnalysis> find(const NewtonPatternKey& key) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Entry& e : entries_)
      if (matches(e, key)) return e.analysis;
    return nullptr;
  }
  void keep(Entry entry) {
    std::lock_guard<std::mutex> lock(mutex_);
    stored_nonzeros_ += static_cast<long>(entry.inner.size());
    entries_.push_back(std::move(entry));
    while (!entries_.empty() && (entries_.size() > kMaxEntries || stored_nonzeros_ > kMaxStoredNonzeros)) {
      stored_nonzeros_ -= static_cast<long>(entries_.front().inner.size());
      entries_.pop_front();
    }
  }

 private:
  // Sizes first, then the index arrays (std::equal on ints: a memcmp, stopping at the first difference).
  static bool matches(const Entry& e, const NewtonPatternKey& key) {
    const int rows = static_cast<int>(key.J.outerSize()), nonzeros = static_cast<int>(key.J.nonZeros());
    return e.linear_solver == key.linear_solver && e.outer.size() == static_cast<size_t>(rows) + 1 &&
           e.inner.size() == static_cast<size_t>(nonzeros) && e.reduced_column == key.reduced_column &&
           e.column_groups == key.column_groups &&
           std::equal(e.outer.begin(), e.outer.end(), key.J.outerIndexPtr()) &&
           std::equal(e.inner.begin(), e.inner.end(), key.J.innerIndexPtr());
  }
  std::mutex mutex_;
  std::deque<Entry> entries_;
  long stored_nonzeros_ = 0;
};

Registry& registry() {
  static Registry r;  // thread-safe initialisation (C++11)
  return r;
}

}  // namespace

std::shared_ptr<const NewtonPatternAnalysis> find_newton_pattern(const NewtonPatternKey& key) {
  if (!key.J.isCompressed()) return nullptr;
  return registry().find(key);
}

void keep_newton_pattern(const NewtonPatternKey& key, const NewtonPatternAnalysis& analysis) {
  if (!key.J.isCompressed() || key.J.nonZeros() > kMaxStoredNonzeros / 4) return;
  Entry e;
  e.outer.assign(key.J.outerIndexPtr(), key.J.outerIndexPtr() + key.J.outerSize() + 1);
  e.inner.assign(key.J.innerIndexPtr(), key.J.innerIndexPtr() + key.J.nonZeros());
  e.reduced_column = key.reduced_column;
  e.column_groups = key.column_groups;
  e.linear_solver = key.linear_solver;
  e.analysis = std::make_shared<const NewtonPatternAnalysis>(analysis);
  registry().keep(std::move(e));
}

}  // namespace pcr
