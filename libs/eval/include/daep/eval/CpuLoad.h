#pragma once

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

namespace daep::eval {

/**
 * Keeps `threads` cores busy until destroyed: daep-benchmark --load N, so that runs with
 * planning_time = measured are tried on a loaded machine on purpose. Each thread works on a
 * buffer of its own larger than a core's L2 cache, so the load also contends for caches and
 * memory, as a neighbour's job would.
 */
class CpuLoad {
public:
    explicit CpuLoad(int threads);
    ~CpuLoad();
    CpuLoad(const CpuLoad&) = delete;
    CpuLoad& operator=(const CpuLoad&) = delete;

    int threads() const { return static_cast<int>(workers_.size()); }
    /** Work rounds done by all threads so far (each touches the whole buffer once). */
    long rounds() const { return rounds_.load(std::memory_order_relaxed); }

private:
    void work();

    std::atomic<bool> stop_{false};
    std::atomic<long> rounds_{0};
    std::atomic<std::uint64_t> checksum_{0};
    std::vector<std::thread> workers_;
};

}  // namespace daep::eval
