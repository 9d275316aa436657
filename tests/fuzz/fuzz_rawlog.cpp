// The streaming rawlog reader (the observations and the actions / sensory-frames formats,
// plain or gzip'ed), read to the end as a rawlog replay does.
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <malloc.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <new>

#include "FuzzSupport.h"
#include "RawlogReader.h"

// MRPT 2.5's deserializer trusts the sizes and counts in the file: a few corrupt bytes make it
// allocate (and zero) up to 4 GB for one string, or billions of elements for a
// CActionCollection (now unpacked by our reader), before it meets the end of the file (both
// found by this target). ASan's
// operator new aborts instead of throwing, and a release build may exhaust memory. Here, while
// an input is read, large allocations beyond a budget far above what a fuzz input's objects
// need throw std::bad_alloc (the reader turns it into an InputError), so fuzzing goes on to our
// code. Small ones are always granted: a corrupt size asks for megabytes or more, while the
// small blocks of MRPT's exception text (its call stack) must not fail once a large read has
// spent the budget, where a throw terminates.
constexpr std::size_t kAllocationBudget = std::size_t(64) << 20;
constexpr std::size_t kAlwaysGranted = std::size_t(1) << 20;
bool readingInput = false;
/**
 * Bytes allocated while reading the input and not freed yet. Counting what is live, not all
 * that was ever allocated, keeps a long but sane input from running out of budget at an
 * arbitrary allocation (such as inside MRPT's exception text, where a throw terminates).
 */
std::size_t liveForInput = 0;

// Every unaligned form is replaced, so that each allocation is freed by its own kind.
void* boundedAllocation(std::size_t size) noexcept {
    const bool overBudget =
        liveForInput >= kAllocationBudget || size > kAllocationBudget - liveForInput;
    if (readingInput && size >= kAlwaysGranted && overBudget) {
        readingInput = false;  // one refusal unwinds MRPT; the error message may allocate
        return nullptr;
    }
    void* p = std::malloc(size == 0 ? 1 : size);
    if (p != nullptr && readingInput)
        liveForInput += malloc_usable_size(p);
    return p;
}
void release(void* p) noexcept {
    if (p != nullptr && readingInput)
        liveForInput -= std::min(liveForInput, malloc_usable_size(p));
    std::free(p);
}
void* throwingAllocation(std::size_t size) {
    if (void* p = boundedAllocation(size))
        return p;
    throw std::bad_alloc();
}

void* operator new(std::size_t size) {
    return throwingAllocation(size);
}
void* operator new[](std::size_t size) {
    return throwingAllocation(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    return boundedAllocation(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
    return boundedAllocation(size);
}
void operator delete(void* p) noexcept {
    release(p);
}
void operator delete[](void* p) noexcept {
    release(p);
}
void operator delete(void* p, std::size_t) noexcept {
    release(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    release(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
    release(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
    release(p);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = daep::fuzz::writeScratch(
        "fuzz.rawlog", std::string(reinterpret_cast<const char*>(data), size));
    // MRPT's aligned blocks (images, point vectors) the reader refuses past the same budget.
    daep::mission::RawlogReader::setLargestReadBlock(kAllocationBudget);
    readingInput = true;
    liveForInput = 0;
    daep::fuzz::expectOnlyInputErrors([&] {
        daep::mission::RawlogReader reader(path, "", "DRONE_POSE");
        daep::mission::RawlogFrame frame;
        while (reader.next(frame)) {
            const auto& range = frame.depth->rangeImage;
            if (range.cols() != static_cast<int>(frame.depth->cameraParams.ncols))
                continue;
        }
    });
    readingInput = false;
    return 0;
}
