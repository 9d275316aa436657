// The streaming rawlog reader (the observations and the actions / sensory-frames formats,
// plain or gzip'ed), read to the end as a rawlog replay does.
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cstdint>

#include "FuzzSupport.h"
#include "RawlogReader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = daep::fuzz::writeScratch(
        "fuzz.rawlog", std::string(reinterpret_cast<const char*>(data), size));
    daep::fuzz::expectOnlyInputErrors([&] {
        daep::mission::RawlogReader reader(path, "", "DRONE_POSE");
        daep::mission::RawlogFrame frame;
        while (reader.next(frame)) {
            const auto& range = frame.depth->rangeImage;
            if (range.cols() != static_cast<int>(frame.depth->cameraParams.ncols))
                continue;
        }
    });
    return 0;
}
