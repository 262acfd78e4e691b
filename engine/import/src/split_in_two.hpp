#pragma once
// Running a loop over [0, count) on two threads when it is long enough to pay for the second.

#include <cstddef>
#include <thread>

namespace tumble::engine::detail {

/// Runs work(begin, end) over [0, count), split between two threads from 2^18 items on.
template <typename Work>
void split_in_two(std::size_t count, const Work& work) {
  if (count < (std::size_t{1} << 18)) return work(std::size_t{0}, count);
  std::thread helper(work, count / 2, count);
  work(std::size_t{0}, count / 2);
  helper.join();
}

}  // namespace tumble::engine::detail
