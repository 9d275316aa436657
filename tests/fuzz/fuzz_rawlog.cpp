// The streaming rawlog reader (the observations and the actions / sensory-frames formats,
// plain or gzip'ed), read to the end as a rawlog replay does.
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cstdint>
#include <cstdlib>
#include <new>

#include "FuzzSupport.h"
#include "RawlogReader.h"

// MRPT 2.5's deserializer trusts the length fields of the file: a few corrupt bytes make it
// allocate and zero up to 4 GB for one string before it meets the end of the file (found by
// this target). A release build then reports the truncated rawlog after that detour; ASan's
// operator new aborts instead of throwing. So here an allocation beyond any object of a fuzz
// input throws std::bad_alloc, as a machine without the memory would, and fuzzing goes on.
constexpr std::size_t kMaxAllocation = std::size_t(64) << 20;

void* operator new(std::size_t size) {
    void* p = size <= kMaxAllocation ? std::malloc(size) : nullptr;
    if (p == nullptr)
        throw std::bad_alloc();
    return p;
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}

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
