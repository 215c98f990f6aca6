#pragma once
// Position of an entry in a compressed sparse pattern (CSR or CSC index arrays).
#include <algorithm>

namespace pcr {

/// Index into the value array of the entry (major, minor) of a compressed pattern - (row, col) of a
/// row-major matrix, (col, row) of a column-major one - whose minor indices are sorted within each
/// major one; -1 when the pattern has no such entry.
inline int compressed_index(const int* outer, const int* inner, int major, int minor) {
  const int* begin = inner + outer[major];
  const int* end = inner + outer[major + 1];
  const int* at = std::lower_bound(begin, end, minor);
  return at != end && *at == minor ? static_cast<int>(at - inner) : -1;
}

}  // namespace pcr
