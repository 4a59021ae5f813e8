#pragma once
// Rows of pairs found by one search per point, in parallel, independent of the thread count: the
// points are cut into fixed chunks, each chunk's pairs go to its own buffer in point order, and
// count[p] says how many are p's (the contact list, the renewed gas family). The caller turns the
// counts into row offsets and copies each chunk's buffer to its rows.
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/parallel.hpp"

namespace ballista::pd {

struct ChunkedRows {
  std::vector<std::vector<std::pair<std::int32_t, double>>> found;  ///< per chunk: (other end, value)
  std::vector<Index> count;                                        ///< pairs of each point
};

/// search(p, buf) appends point p's pairs to buf (and may reorder what it appended). Into `r`,
/// reusing its buffers' capacity (a search repeated every few steps maps no new pages).
template <class Search>
void chunked_rows(Index n, Index chunk, Search&& search, ChunkedRows& r) {
  const Index nchunk = (n + chunk - 1) / chunk;
  r.found.resize(static_cast<size_t>(nchunk));
  r.count.resize(static_cast<size_t>(n));  // every entry is written below
  for_each_chunk(nchunk, [&](Index c) {
    auto& buf = r.found[c];
    buf.clear();
    for (Index p = c * chunk; p < std::min(n, (c + 1) * chunk); ++p) {
      const size_t first = buf.size();
      search(p, buf);
      r.count[p] = static_cast<Index>(buf.size() - first);
    }
  });
}

}  // namespace ballista::pd
