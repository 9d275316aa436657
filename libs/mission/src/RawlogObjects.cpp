#include "RawlogObjects.h"

#include <mrpt/io/CStream.h>
#include <mrpt/obs/CAction.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>

namespace daep::mission {
namespace {

// MRPT's object format: a lead byte (bit 7 set: the current format; clear: the format before
// MRPT 0.5.5, followed by three zero bytes), the class name (the lead byte's low 7 bits give
// its length), the serialization version (one byte, or four in the old format, none for a
// "nullptr"), the object's data, and an end flag (current format only).
constexpr unsigned char kCurrentFormat = 0x80;
constexpr unsigned char kEndFlag = 0x88;
constexpr std::size_t kLongestClassName = 120;

/** The rawlog with a look-ahead: bytes can be looked at before MRPT reads them. */
class PeekingStream : public mrpt::io::CStream {
public:
    explicit PeekingStream(mrpt::io::CStream& source) : source_(source) {}

    /** The next n bytes, not consumed; fewer at the end of the file. */
    const std::string& peek(std::size_t n) {
        while (ahead_.size() < n) {
            char chunk[256];
            const std::size_t got = source_.Read(chunk, std::min(sizeof chunk, n - ahead_.size()));
            if (got == 0)
                break;
            ahead_.append(chunk, got);
        }
        return ahead_;
    }

    /** The next n bytes, consumed. */
    std::string take(std::size_t n) {
        if (peek(n).size() < n)
            throw TruncatedObject("the file ends inside an object");
        std::string bytes = ahead_.substr(0, n);
        ahead_.erase(0, n);
        return bytes;
    }

    size_t Read(void* buffer, size_t count) override {
        const std::size_t fromAhead = std::min(count, ahead_.size());
        std::memcpy(buffer, ahead_.data(), fromAhead);
        ahead_.erase(0, fromAhead);
        if (fromAhead == count)
            return count;
        return fromAhead + source_.Read(static_cast<char*>(buffer) + fromAhead, count - fromAhead);
    }
    size_t Write(const void*, size_t) override { return 0; }
    uint64_t Seek(int64_t, mrpt::io::CStream::TSeekOrigin) override {
        throw std::logic_error("a rawlog is read forward only");
    }
    uint64_t getTotalBytesCount() const override { return source_.getTotalBytesCount(); }
    uint64_t getPosition() const override { return source_.getPosition() - ahead_.size(); }

private:
    mrpt::io::CStream& source_;
    std::string ahead_;
};

template <typename T>
T littleEndian(const std::string& bytes) {
    T value{};
    static_assert(sizeof(T) <= 8);
    std::memcpy(&value, bytes.data(), sizeof(T));  // MRPT's byte order on the x86/ARM it runs on
    return value;
}

struct ObjectHeader {
    std::string className;
    bool currentFormat = true;
    unsigned version = 0;
    std::size_t bytes = 0;  ///< its length in the file
};

/** The header of the next object, not consumed; nothing at the end of the file. */
std::optional<ObjectHeader> peekHeader(PeekingStream& in) {
    const std::string& lead = in.peek(1);
    if (lead.empty())
        return std::nullopt;
    ObjectHeader h;
    h.currentFormat = (static_cast<unsigned char>(lead[0]) & kCurrentFormat) != 0;
    const std::size_t nameLength = static_cast<unsigned char>(lead[0]) & 0x7f;
    const std::size_t nameAt = h.currentFormat ? 1 : 4;
    if (!h.currentFormat && in.peek(4).find_first_not_of('\0', 1) != std::string::npos)
        throw MalformedObject("is no MRPT object: its header has neither MRPT format");
    if (nameLength > kLongestClassName)
        throw MalformedObject("is no MRPT object: its class name would be " +
                              std::to_string(nameLength) + " characters long");
    const std::string& bytes = in.peek(nameAt + nameLength);
    if (bytes.size() < nameAt + nameLength)
        throw TruncatedObject("the file ends inside an object header");
    h.className = bytes.substr(nameAt, nameLength);
    const std::size_t versionBytes = !h.currentFormat ? 4 : h.className == "nullptr" ? 0 : 1;
    h.bytes = nameAt + nameLength + versionBytes;
    const std::string& header = in.peek(h.bytes);
    if (header.size() < h.bytes)
        throw TruncatedObject("the file ends inside an object header");
    if (h.currentFormat) {
        h.version = versionBytes == 0 ? 0 : static_cast<unsigned char>(header[h.bytes - 1]);
    } else {
        const auto version = littleEndian<std::int32_t>(header.substr(h.bytes - 4));
        if (version < 0 || version >= 255)
            throw MalformedObject("is a " + printable(h.className) + " of serialization version " +
                                  std::to_string(version));
        h.version = static_cast<unsigned>(version);
    }
    return h;
}

const mrpt::rtti::TRuntimeClassId& knownClass(const ObjectHeader& h) {
    if (h.className == "nullptr")
        throw MalformedObject("is a null object");
    const auto* id = mrpt::rtti::findRegisteredClass(h.className);
    if (id == nullptr)
        throw MalformedObject("is of class '" + printable(h.className) +
                              "', which MRPT does not know");
    return *id;
}

bool isCreatable(const mrpt::rtti::TRuntimeClassId& id, const mrpt::rtti::TRuntimeClassId* base) {
    return id.derivedFrom(base) && id.ptrCreateObject;
}

}  // namespace

std::string printable(const std::string& text) {
    std::string out;
    for (const char c : text)
        out += (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) ? '?'
                                                                                              : c;
    return out;
}

struct RawlogObjects::Impl {
    PeekingStream in;
    using Observations = std::vector<std::shared_ptr<mrpt::obs::CObservation>>;

    explicit Impl(mrpt::io::CStream& file) : in(file) {}

    /** One element of a container: an object of a creatable subclass of base, called kind. */
    mrpt::serialization::CSerializable::Ptr readElement(const std::string& container,
                                                        const mrpt::rtti::TRuntimeClassId* base,
                                                        const std::string& kind) {
        const auto h = peekHeader(in);
        if (!h)
            throw TruncatedObject("the file ends inside a " + container);
        if (h->className == "nullptr" || !isCreatable(knownClass(*h), base))
            throw MalformedObject("is a " + container + " holding a " + printable(h->className) +
                                  " where " + kind + " must be");
        return mrpt::serialization::archiveFrom(in).ReadObject();
    }

    std::uint32_t elementCount() { return littleEndian<std::uint32_t>(in.take(4)); }

    void expectEndFlag(const ObjectHeader& h, const std::string& container) {
        if (h.currentFormat && static_cast<unsigned char>(in.take(1)[0]) != kEndFlag)
            throw MalformedObject("is a " + container + " without an end flag after its elements");
    }

    void readSensoryFrame(const ObjectHeader& h, Observations& out) {
        if (h.version > 2)
            throw MalformedObject("is a CSensoryFrame of serialization version " +
                                  std::to_string(h.version) + ", which MRPT 2.5 cannot read");
        in.take(h.bytes);
        if (h.version < 2)
            in.take(4);  // an ID, dropped in version 2
        std::optional<mrpt::Clock::time_point> frameStamp;
        if (h.version == 0)  // one timestamp for all observations
            frameStamp = mrpt::Clock::time_point(
                mrpt::Clock::duration(littleEndian<std::int64_t>(in.take(8))));
        for (std::uint32_t i = 0, n = elementCount(); i < n; ++i) {
            auto o = std::dynamic_pointer_cast<mrpt::obs::CObservation>(
                readElement("CSensoryFrame", CLASS_ID(mrpt::obs::CObservation), "an observation"));
            if (frameStamp)
                o->timestamp = *frameStamp;
            out.push_back(std::move(o));
        }
        expectEndFlag(h, "CSensoryFrame");
    }

    void readActionCollection(const ObjectHeader& h,
                              std::vector<std::shared_ptr<mrpt::obs::CAction>>* actions) {
        if (h.version != 0)
            throw MalformedObject("is a CActionCollection of serialization version " +
                                  std::to_string(h.version) + ", which MRPT 2.5 cannot read");
        in.take(h.bytes);
        for (std::uint32_t i = 0, n = elementCount(); i < n; ++i) {
            auto action = std::dynamic_pointer_cast<mrpt::obs::CAction>(
                readElement("CActionCollection", CLASS_ID(mrpt::obs::CAction), "an action"));
            if (actions)
                actions->push_back(std::move(action));
        }
        expectEndFlag(h, "CActionCollection");
    }

    void readObservation(const ObjectHeader& h, const mrpt::rtti::TRuntimeClassId& id,
                         Observations& out) {
        if (!isCreatable(id, CLASS_ID(mrpt::obs::CObservation)))
            throw MalformedObject("is a " + printable(h.className) +
                                  ", which a rawlog does not hold (observations, CSensoryFrame "
                                  "and CActionCollection)");
        out.push_back(std::dynamic_pointer_cast<mrpt::obs::CObservation>(
            mrpt::serialization::archiveFrom(in).ReadObject()));
    }
};

RawlogObjects::RawlogObjects(mrpt::io::CStream& file) : impl_(std::make_unique<Impl>(file)) {}

RawlogObjects::~RawlogObjects() = default;

bool RawlogObjects::readNext(std::vector<std::shared_ptr<mrpt::obs::CObservation>>& observations,
                             std::vector<std::shared_ptr<mrpt::obs::CAction>>* actions) {
    const auto h = peekHeader(impl_->in);
    if (!h)
        return false;
    const auto& id = knownClass(*h);
    if (&id == CLASS_ID(mrpt::obs::CSensoryFrame))
        impl_->readSensoryFrame(*h, observations);
    else if (&id == CLASS_ID(mrpt::obs::CActionCollection))
        impl_->readActionCollection(*h, actions);
    else
        impl_->readObservation(*h, id, observations);
    return true;
}

}  // namespace daep::mission
