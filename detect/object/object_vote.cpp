#include "detect/object/object_vote.hpp"

#include <algorithm>

namespace rangefit {

std::vector<int> ranks(const std::vector<double>& values, bool larger_is_better) {
  std::vector<double> sorted = values;
  if (larger_is_better) {
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
  } else {
    std::sort(sorted.begin(), sorted.end());
  }
  std::vector<int> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto it = larger_is_better ? std::lower_bound(sorted.begin(), sorted.end(), values[i],
                                                        std::greater<>())
                                     : std::lower_bound(sorted.begin(), sorted.end(), values[i]);
    out[i] = 1 + static_cast<int>(it - sorted.begin());
  }
  return out;
}

}  // namespace rangefit
