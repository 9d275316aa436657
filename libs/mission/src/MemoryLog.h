#pragma once

#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace daep::mission {

/** The process's resident set now and at its peak, in MB (Linux: /proc/self/statm, getrusage). */
struct MemoryUse {
    double rssMb = 0.0;
    double peakRssMb = 0.0;
};

MemoryUse currentMemoryUse();

/**
 * memory.csv: the process's memory beside the map's size every `every` seconds of exploration,
 * so a long run shows whether memory stops growing once the map does. Rows are flushed as they
 * are written (an interrupted soak keeps its curve). every = 0 writes no file.
 */
class MemoryLog {
public:
    MemoryLog(const std::string& path, double every);
    ~MemoryLog();
    MemoryLog(const MemoryLog&) = delete;
    MemoryLog& operator=(const MemoryLog&) = delete;

    bool enabled() const { return file_ != nullptr; }
    /** Whether a row is due at exploration time t. */
    bool due(double t) const;
    /** Writes the row due (time = its scheduled time) and schedules the next. */
    void addDue(double knownVolumeM3, std::size_t mapNodes);
    /** The final row at exploration time t, unless a row was written at t already. */
    void addFinal(double t, double knownVolumeM3, std::size_t mapNodes);

    /**
     * memory.png: the resident set over time beside the known volume scaled to the peak
     * resident set (both should level off together). Needs two rows or more; else nothing.
     */
    void writePlot(const std::string& path, const std::string& title) const;

private:
    void write(double t, double knownVolumeM3, std::size_t mapNodes);

    std::FILE* file_ = nullptr;
    double every_ = 0.0;
    double next_ = 0.0;
    double last_ = -1.0;
    std::vector<double> times_, rssMb_, knownM3_;
};

}  // namespace daep::mission
