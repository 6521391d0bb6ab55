#pragma once
/// @file
/// The map correction (T_map_odom) the publisher thread applies now, for a thread that places
/// something else in the map frame (the current sweep, sweep_publisher.h). One writer (the
/// publisher thread, real time), any readers: a sequence lock, so the writer never waits and a
/// reader retries the rare read that overlapped a write. Not valid until the publisher has
/// applied a correction (localizing: until the first relocalization).

#include <Eigen/Geometry>
#include <array>
#include <atomic>
#include <cstdint>

namespace swlio::daemon {

class CorrectionCell {
 public:
  /// Writer only.
  void Store(const Eigen::Isometry3d& T_map_odom) {
    const uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    for (size_t i = 0; i < 12; ++i)
      m_[i].store(T_map_odom.matrix()(static_cast<int>(i % 3), static_cast<int>(i / 3)),
                  std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }
  /// False (nothing written to *T) before the first Store.
  bool Load(Eigen::Isometry3d* T_map_odom) const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    uint64_t before = 0, after = 0;
    do {
      before = seq_.load(std::memory_order_acquire);
      for (size_t i = 0; i < 12; ++i)
        T.matrix()(static_cast<int>(i % 3), static_cast<int>(i / 3)) =
            m_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      after = seq_.load(std::memory_order_relaxed);
    } while ((before & 1) != 0 || before != after);
    if (before == 0) return false;
    *T_map_odom = T;
    return true;
  }

 private:
  std::atomic<uint64_t> seq_{0};             ///< odd while a write is under way; 0: never written
  std::array<std::atomic<double>, 12> m_{};  ///< the top 3×4 of the matrix, column-major
};

}  // namespace swlio::daemon
