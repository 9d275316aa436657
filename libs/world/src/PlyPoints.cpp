#include "PlyPoints.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "daep/common/Error.h"

namespace daep::world {
namespace {

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Property {
    std::string name;
    int size = 0;     ///< bytes of the value (binary)
    char kind = 'f';  ///< 'i' signed, 'u' unsigned, 'f' floating
    bool isList = false;
    int countSize = 0;  ///< list: bytes of the count
    char countKind = 'u';
};

struct Element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    Format format = Format::Ascii;
    std::vector<Element> elements;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what);
}

/** Size and kind of a PLY scalar type name, or nullopt. */
std::optional<std::pair<int, char>> scalarType(const std::string& t) {
    static const std::pair<const char*, std::pair<int, char>> kTypes[] = {
        {"char", {1, 'i'}},  {"int8", {1, 'i'}},    {"uchar", {1, 'u'}},  {"uint8", {1, 'u'}},
        {"short", {2, 'i'}}, {"int16", {2, 'i'}},   {"ushort", {2, 'u'}}, {"uint16", {2, 'u'}},
        {"int", {4, 'i'}},   {"int32", {4, 'i'}},   {"uint", {4, 'u'}},   {"uint32", {4, 'u'}},
        {"float", {4, 'f'}}, {"float32", {4, 'f'}}, {"double", {8, 'f'}}, {"float64", {8, 'f'}}};
    for (const auto& [name, type] : kTypes)
        if (t == name)
            return type;
    return std::nullopt;
}

Property parseProperty(std::istringstream& words, const std::string& path, int line) {
    Property p;
    std::string type;
    words >> type;
    const auto where = " on header line " + std::to_string(line);
    if (type == "list") {
        std::string countType, valueType;
        words >> countType >> valueType >> p.name;
        const auto count = scalarType(countType), value = scalarType(valueType);
        if (!count || !value || count->second == 'f')
            fail(path, "bad list property" + where);
        p.isList = true;
        std::tie(p.countSize, p.countKind) = *count;
        std::tie(p.size, p.kind) = *value;
        return p;
    }
    words >> p.name;
    const auto value = scalarType(type);
    if (!value || p.name.empty())
        fail(path, "unknown property type '" + type + "'" + where);
    std::tie(p.size, p.kind) = *value;
    return p;
}

Format parseFormat(const std::string& name, const std::string& path) {
    if (name == "ascii")
        return Format::Ascii;
    if (name == "binary_little_endian")
        return Format::BinaryLittle;
    if (name == "binary_big_endian")
        return Format::BinaryBig;
    fail(path, "unknown PLY format '" + name + "'");
}

Header readHeader(std::istream& in, const std::string& path) {
    std::string line;
    if (!std::getline(in, line) || line.substr(0, 3) != "ply" ||
        line.find_first_not_of(" \r", 3) != std::string::npos)
        fail(path, "not a PLY file (the first line is not 'ply')");
    Header h;
    bool formatSeen = false;
    for (int n = 2; std::getline(in, line); ++n) {
        if (!line.empty() && line.back() == '\r')
            line.pop_back();
        std::istringstream words(line);
        std::string key;
        words >> key;
        if (key == "end_header") {
            if (!formatSeen)
                fail(path, "the PLY header has no 'format' line");
            return h;
        }
        if (key == "format") {
            std::string name;
            words >> name;
            h.format = parseFormat(name, path);
            formatSeen = true;
        } else if (key == "element") {
            Element e;
            words >> e.name >> e.count;
            if (words.fail())
                fail(path, "bad element line " + std::to_string(n) + " of the PLY header");
            h.elements.push_back(e);
        } else if (key == "property") {
            if (h.elements.empty())
                fail(path, "a property before any element on header line " + std::to_string(n));
            h.elements.back().properties.push_back(parseProperty(words, path, n));
        } else if (key != "comment" && key != "obj_info" && !key.empty()) {
            fail(path, "unknown PLY header line " + std::to_string(n) + " '" + line + "'");
        }
    }
    fail(path, "the PLY header has no 'end_header'");
}

bool hostIsLittleEndian() {
    const std::uint16_t one = 1;
    unsigned char first = 0;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

/** Reads values one at a time from the body, in either encoding. */
class BodyReader {
public:
    BodyReader(std::istream& in, Format format, const std::string& path)
        : in_(in), format_(format), path_(path) {}

    double value(int size, char kind) {
        if (format_ == Format::Ascii) {
            std::string word;
            if (!(in_ >> word))
                fail(path_, "the PLY data ends early (the file is truncated)");
            char* end = nullptr;
            const double v = std::strtod(word.c_str(), &end);  // also nan and inf
            if (*end != '\0')
                fail(path_, "'" + word + "' in the PLY data is not a number");
            return v;
        }
        unsigned char bytes[8];
        if (!in_.read(reinterpret_cast<char*>(bytes), size))
            fail(path_, "the PLY data ends early (the file is truncated)");
        if ((format_ == Format::BinaryLittle) != hostIsLittleEndian())
            std::reverse(bytes, bytes + size);
        return decode(bytes, size, kind);
    }

private:
    static double decode(const unsigned char* b, int size, char kind) {
        if (kind == 'f') {
            if (size == 4) {
                float f;
                std::memcpy(&f, b, 4);
                return f;
            }
            double d;
            std::memcpy(&d, b, 8);
            return d;
        }
        std::uint64_t u = 0;
        std::memcpy(&u, b, std::size_t(size));  // little-endian host after the swap above
        if (kind == 'u')
            return double(u);
        const int shift = 64 - 8 * size;
        return double(std::int64_t(u << shift) >> shift);
    }

    std::istream& in_;
    Format format_;
    const std::string& path_;
};

int indexOf(const Element& e, const std::string& name) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].name == name && !e.properties[i].isList)
            return int(i);
    return -1;
}

void skipElement(BodyReader& body, const Element& e) {
    for (std::uint64_t n = 0; n < e.count; ++n)
        for (const Property& p : e.properties) {
            const auto count = std::uint64_t(p.isList ? body.value(p.countSize, p.countKind) : 1);
            for (std::uint64_t k = 0; k < count; ++k)
                body.value(p.size, p.kind);
        }
}

std::vector<Eigen::Vector3d> readVertices(BodyReader& body, const Element& e,
                                          const std::array<int, 3>& xyz) {
    std::vector<Eigen::Vector3d> points;
    points.reserve(std::size_t(std::min<std::uint64_t>(e.count, 1'000'000)));
    std::vector<double> values(e.properties.size());
    for (std::uint64_t n = 0; n < e.count; ++n) {
        for (std::size_t i = 0; i < e.properties.size(); ++i) {
            const Property& p = e.properties[i];
            const auto count = std::uint64_t(p.isList ? body.value(p.countSize, p.countKind) : 1);
            for (std::uint64_t k = 0; k < count; ++k)
                values[i] = body.value(p.size, p.kind);
        }
        points.emplace_back(values[std::size_t(xyz[0])], values[std::size_t(xyz[1])],
                            values[std::size_t(xyz[2])]);
    }
    return points;
}

}  // namespace

std::vector<Eigen::Vector3d> readPlyPoints(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path, "cannot read the point cloud file");
    const Header h = readHeader(in, path);
    BodyReader body(in, h.format, path);
    for (const Element& e : h.elements) {
        if (e.name != "vertex") {
            skipElement(body, e);
            continue;
        }
        const std::array<int, 3> xyz = {indexOf(e, "x"), indexOf(e, "y"), indexOf(e, "z")};
        if (*std::min_element(xyz.begin(), xyz.end()) < 0)
            fail(path, "the PLY vertex element has no x, y and z properties");
        return readVertices(body, e, xyz);
    }
    fail(path, "the PLY file has no vertex element");
}

void writePlyPoints(const std::string& path, const std::vector<Eigen::Vector3f>& points,
                    const std::string& comment) {
    std::ofstream out(path, std::ios::binary);
    out << "ply\nformat binary_little_endian 1.0\ncomment " << comment << "\nelement vertex "
        << points.size() << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    for (const auto& p : points) {
        float xyz[3] = {p.x(), p.y(), p.z()};
        if (!hostIsLittleEndian())
            for (float& f : xyz)
                std::reverse(reinterpret_cast<char*>(&f), reinterpret_cast<char*>(&f) + 4);
        out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    }
    if (!out)
        throw std::runtime_error(path + ": cannot write the point cloud");
}

}  // namespace daep::world
