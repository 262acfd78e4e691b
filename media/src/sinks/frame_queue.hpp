#pragma once
// Bounded hand-off of frames from the render thread to encoder threads, recycling buffers so
// steady-state writing allocates nothing.

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

#include "base/image.hpp"

namespace tumble::media::detail {

class FrameQueue {
 public:
  struct Item {
    std::size_t index = 0;
    std::vector<std::uint8_t> rgba;
  };

  explicit FrameQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  /// Copies a frame in, waiting while the queue is full. Returns false once closed.
  bool push(const Image& frame, std::size_t index) {
    std::vector<std::uint8_t> buffer;
    {
      std::unique_lock lock(mutex_);
      not_full_.wait(lock, [&] { return closed_ || queued_.size() < capacity_; });
      if (closed_) return false;
      if (!spare_.empty()) {
        buffer = std::move(spare_.back());
        spare_.pop_back();
      }
    }
    buffer.assign(frame.rgba.begin(), frame.rgba.end());
    {
      std::lock_guard lock(mutex_);
      if (closed_) return false;
      queued_.push_back({index, std::move(buffer)});
    }
    not_empty_.notify_one();
    return true;
  }

  /// Moves a frame's pixels in without copying, waiting while the queue is full; `rgba` gets a
  /// recycled buffer back (unspecified contents; empty until one is spare). False once closed.
  bool push_taking(std::vector<std::uint8_t>& rgba, std::size_t index) {
    {
      std::unique_lock lock(mutex_);
      not_full_.wait(lock, [&] { return closed_ || queued_.size() < capacity_; });
      if (closed_) return false;
      std::vector<std::uint8_t> spare;
      if (!spare_.empty()) {
        spare = std::move(spare_.back());
        spare_.pop_back();
      }
      queued_.push_back({index, std::move(rgba)});
      rgba = std::move(spare);
    }
    not_empty_.notify_one();
    return true;
  }

  /// Takes the oldest frame, waiting for one. Returns false when closed and drained.
  bool pop(Item& item) {
    std::unique_lock lock(mutex_);
    not_empty_.wait(lock, [&] { return closed_ || !queued_.empty(); });
    if (queued_.empty()) return false;
    item = std::move(queued_.front());
    queued_.pop_front();
    not_full_.notify_one();
    return true;
  }

  /// Returns a consumed buffer for reuse.
  void recycle(std::vector<std::uint8_t>&& buffer) {
    std::lock_guard lock(mutex_);
    if (spare_.size() < capacity_ + 2) spare_.push_back(std::move(buffer));
  }

  /// No more pushes; consumers drain what is queued, then pop() returns false.
  void close() {
    {
      std::lock_guard lock(mutex_);
      closed_ = true;
    }
    not_empty_.notify_all();
    not_full_.notify_all();
  }

  /// Drops everything queued (on abort).
  void discard() {
    std::lock_guard lock(mutex_);
    queued_.clear();
  }

 private:
  std::mutex mutex_;
  std::condition_variable not_full_;
  std::condition_variable not_empty_;
  std::deque<Item> queued_;
  std::vector<std::vector<std::uint8_t>> spare_;
  std::size_t capacity_;
  bool closed_ = false;
};

}  // namespace tumble::media::detail
