#pragma once
// Shared by the fuzz targets: scratch files for the parsers that read paths, inputs split into
// parts, and the oracle (bad input may only end in daep::InputError).

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "daep/common/Error.h"

namespace daep::fuzz {

/** One private directory per process, under $TMPDIR (or /tmp). */
inline const std::filesystem::path& scratchDir() {
    static const std::filesystem::path dir = [] {
        const char* tmp = std::getenv("TMPDIR");
        std::string tmpl = std::string(tmp && *tmp ? tmp : "/tmp") + "/daep-fuzz-XXXXXX";
        if (::mkdtemp(tmpl.data()) == nullptr) {
            std::perror("daep fuzz: mkdtemp");
            std::abort();
        }
        return std::filesystem::path(tmpl);
    }();
    return dir;
}

/** Writes `bytes` to scratchDir()/name and returns the path. */
inline std::string writeScratch(const std::string& name, const std::string& bytes) {
    const std::filesystem::path path = scratchDir() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    if (!out) {
        std::perror(("daep fuzz: cannot write " + path.string()).c_str());
        std::abort();
    }
    return path.string();
}

/** A unit cube as scratchDir()/cube.obj, for inputs that name a mesh file. */
inline std::string writeCubeMesh() {
    return writeScratch("cube.obj",
                        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                        "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                        "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n");
}

/** The input split at every line that is exactly `separator` (without the line break). */
inline std::vector<std::string> splitParts(const std::uint8_t* data, std::size_t size,
                                           const std::string& separator) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const std::string marker = "\n" + separator + "\n";
    std::vector<std::string> parts;
    std::size_t begin = 0;
    for (std::size_t at; (at = text.find(marker, begin)) != std::string::npos;) {
        parts.push_back(text.substr(begin, at + 1 - begin));
        begin = at + marker.size();
    }
    parts.push_back(text.substr(begin));
    return parts;
}

/** The lines of `text`, without their line breaks. */
inline std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::size_t begin = 0;
    while (begin < text.size()) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string::npos)
            end = text.size();
        out.push_back(text.substr(begin, end - begin));
        begin = end + 1;
    }
    return out;
}

/**
 * Runs `parse`; an InputError is the expected answer to bad input. Any other exception means
 * the user would get exit code 2 and a message that names no file or key: that is a finding.
 */
template <typename Parse>
void expectOnlyInputErrors(Parse&& parse) {
    try {
        parse();
    } catch (const daep::InputError&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "daep fuzz: exception other than InputError: %s\n", e.what());
        std::abort();
    }
}

}  // namespace daep::fuzz
