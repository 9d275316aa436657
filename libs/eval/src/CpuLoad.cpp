#include "daep/eval/CpuLoad.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace daep::eval {
namespace {

constexpr std::size_t kBufferWords = std::size_t(1) << 19;  // 4 MB of 64-bit words
constexpr int kMaxThreads = 1024;

}  // namespace

CpuLoad::CpuLoad(int threads) {
    if (threads < 0 || threads > kMaxThreads)
        throw std::invalid_argument("CpuLoad: " + std::to_string(threads) + " threads");
    for (int i = 0; i < threads; ++i)
        workers_.emplace_back([this] { work(); });
}

CpuLoad::~CpuLoad() {
    stop_.store(true);
    for (std::thread& w : workers_)
        w.join();
}

void CpuLoad::work() {
    std::vector<std::uint64_t> buffer(kBufferWords, 1);
    std::uint64_t x = 0x9e3779b97f4a7c15ull;
    while (!stop_.load(std::memory_order_relaxed)) {
        for (std::size_t i = 0; i < buffer.size(); i += 8) {  // one word per cache line
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            buffer[(x >> 11) % buffer.size()] += x;
        }
        // The work leaves a trace others can read, so the compiler cannot drop it.
        checksum_.fetch_xor(buffer[x % buffer.size()], std::memory_order_relaxed);
        rounds_.fetch_add(1, std::memory_order_relaxed);
    }
}

}  // namespace daep::eval
