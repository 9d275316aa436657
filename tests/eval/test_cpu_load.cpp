#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <thread>

#include "daep/eval/CpuLoad.h"

namespace daep::eval {
namespace {

/** Waits (up to a minute, on however busy a machine) until every thread has worked a while. */
bool worked(const CpuLoad& load, long rounds) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    while (load.rounds() < rounds && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    return load.rounds() >= rounds;
}

TEST(CpuLoad, ThreadsWorkUntilDestroyed) {
    long before = 0;
    {
        const CpuLoad load(2);
        EXPECT_EQ(load.threads(), 2);
        ASSERT_TRUE(worked(load, 6));
        before = load.rounds();
    }  // the destructor stops and joins them: this returns at all
    EXPECT_GE(before, 6);
}

TEST(CpuLoad, NoThreadsIsNoLoadAndABadCountIsAnError) {
    const CpuLoad idle(0);
    EXPECT_EQ(idle.threads(), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    EXPECT_EQ(idle.rounds(), 0);
    EXPECT_THROW(CpuLoad(-1), std::invalid_argument);
    EXPECT_THROW(CpuLoad(100000), std::invalid_argument);
}

}  // namespace
}  // namespace daep::eval
