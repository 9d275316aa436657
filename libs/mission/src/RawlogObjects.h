#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrpt::io {
class CStream;
}
namespace mrpt::obs {
class CAction;
class CObservation;
}  // namespace mrpt::obs

namespace daep::mission {

/** The file ends inside an object. */
class TruncatedObject : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** Bytes that are no MRPT object, or an object of a class a rawlog cannot hold there. */
class MalformedObject : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** text with every byte outside printable ASCII (a corrupt file's class name) as '?'. */
std::string printable(const std::string& text);

/**
 * The top-level objects of an MRPT rawlog, one at a time, as the observations they carry. The
 * class of every object is checked before MRPT deserializes it: at the top level an
 * observation, a CSensoryFrame or a CActionCollection; inside those, an observation or an
 * action of a class that can be created. The two containers are unpacked here, element by
 * element: MRPT 2.5 casts an element of another class to a null pointer and then reads through
 * it (found by fuzz_rawlog), and it allocates the element count a corrupt file declares before
 * reading one element.
 */
class RawlogObjects {
public:
    explicit RawlogObjects(mrpt::io::CStream& file);
    ~RawlogObjects();
    RawlogObjects(const RawlogObjects&) = delete;
    RawlogObjects& operator=(const RawlogObjects&) = delete;

    /**
     * Reads the next object and appends its observations, and the actions of a
     * CActionCollection to `actions` when given; false at a clean end of the file. Throws
     * TruncatedObject, MalformedObject, or what MRPT throws for a corrupt observation.
     */
    bool readNext(std::vector<std::shared_ptr<mrpt::obs::CObservation>>& observations,
                  std::vector<std::shared_ptr<mrpt::obs::CAction>>* actions = nullptr);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep::mission
