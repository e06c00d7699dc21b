#pragma once
// The ranked vote of the pose verification (thesis 5.1.2 "Selection" and 5.1.3): every
// criterion is turned into ranks (1 = best, ties share the rank) and the candidate with the
// lowest rank sum wins. No weights or thresholds, only the natural order of each criterion.

#include <cstddef>
#include <vector>

namespace rangefit {

// rank[i] = 1 + number of values strictly better than values[i] (smaller, or larger when
// larger_is_better).
std::vector<int> ranks(const std::vector<double>& values, bool larger_is_better = false);

// A candidate combination: one hypothesis index per part and its rank sum.
struct VoteCandidate {
  std::vector<std::size_t> hypothesis;  // per part, index into that part's hypotheses
  int rank_sum = 0;
};

}  // namespace rangefit
