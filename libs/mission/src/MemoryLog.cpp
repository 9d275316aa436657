#include "MemoryLog.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>

#include "daep/eval/Plot.h"

namespace daep::mission {
namespace {

constexpr double kEps = 1e-9;
constexpr double kMb = 1024.0 * 1024.0;

double residentBytes() {
    std::ifstream statm("/proc/self/statm");
    long pagesTotal = 0, pagesResident = 0;
    if (!(statm >> pagesTotal >> pagesResident))
        return 0.0;
    return static_cast<double>(pagesResident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

double peakResidentBytes() {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) != 0)
        return 0.0;
    return 1024.0 * static_cast<double>(usage.ru_maxrss);  // Linux reports KiB
}

}  // namespace

MemoryUse currentMemoryUse() {
    MemoryUse m;
    m.rssMb = residentBytes() / kMb;
    m.peakRssMb = std::max(peakResidentBytes() / kMb, m.rssMb);
    return m;
}

MemoryLog::MemoryLog(const std::string& path, double every) : every_(every) {
    if (every <= 0)
        return;
    file_ = std::fopen(path.c_str(), "w");
    if (!file_)
        throw std::runtime_error("cannot write " + path);
    std::fputs("t,rss_mb,peak_rss_mb,known_volume_m3,map_nodes\n", file_);
}

MemoryLog::~MemoryLog() {
    if (file_)
        std::fclose(file_);
}

bool MemoryLog::due(double t) const {
    return file_ && t + kEps >= next_;
}

void MemoryLog::addDue(double knownVolumeM3, std::size_t mapNodes) {
    write(next_, knownVolumeM3, mapNodes);
    next_ += every_;
}

void MemoryLog::addFinal(double t, double knownVolumeM3, std::size_t mapNodes) {
    if (file_ && std::abs(t - last_) > kEps)
        write(t, knownVolumeM3, mapNodes);
}

void MemoryLog::write(double t, double knownVolumeM3, std::size_t mapNodes) {
    const MemoryUse m = currentMemoryUse();
    std::fprintf(file_, "%.3f,%.2f,%.2f,%.4f,%zu\n", t, m.rssMb, m.peakRssMb, knownVolumeM3,
                 mapNodes);
    std::fflush(file_);
    last_ = t;
    times_.push_back(t);
    rssMb_.push_back(m.rssMb);
    knownM3_.push_back(knownVolumeM3);
}

void MemoryLog::writePlot(const std::string& path, const std::string& title) const {
    if (times_.size() < 2)
        return;
    const double peakRss = *std::max_element(rssMb_.begin(), rssMb_.end());
    const double peakKnown = *std::max_element(knownM3_.begin(), knownM3_.end());
    std::vector<double> knownScaled;
    for (const double v : knownM3_)
        knownScaled.push_back(peakKnown > 0 ? v / peakKnown * peakRss : 0.0);
    eval::Plot plot(900, 420);
    plot.setTitle(title);
    plot.setXLabel("exploration time [s]");
    plot.setYLabel("resident set [MB]");
    plot.setYRange(0.0, 1.35 * std::max(peakRss, 1.0));  // headroom: the legend sits on top
    plot.addLine(times_, rssMb_, eval::seriesColor(0), "resident set (MB)");
    char knownLabel[128];
    std::snprintf(knownLabel, sizeof knownLabel,
                  "known volume, scaled (%.0f m^3 at the highest resident set sampled)", peakKnown);
    plot.addLine(times_, knownScaled, eval::seriesColor(1), knownLabel);
    plot.save(path);
}

}  // namespace daep::mission
