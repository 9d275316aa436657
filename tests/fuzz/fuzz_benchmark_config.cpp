// The benchmark ini with --set overrides, expanded into its runs.
// Input: the benchmark file, then optionally a line "--set" and one override per line.
// The experiment it names is looked up next to it: experiment.ini exists there.
#include <cstdint>

#include "FuzzSupport.h"
#include "daep/eval/BenchmarkConfig.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string experiment =
        daep::fuzz::writeScratch("experiment.ini", "[experiment]\nworld = tiny_room\n");
    const auto parts = daep::fuzz::splitParts(data, size, "--set");
    std::vector<std::string> overrides;
    for (std::size_t i = 1; i < parts.size(); ++i)
        for (const auto& line : daep::fuzz::lines(parts[i]))
            overrides.push_back(line);
    const std::string path = daep::fuzz::writeScratch("benchmark.ini", parts[0]);
    daep::fuzz::expectOnlyInputErrors([&] {
        const auto config = daep::eval::loadBenchmarkConfig(path, overrides);
        for (const auto& run : config.expand())
            run.id();
    });
    return 0;
}
