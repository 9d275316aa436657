#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

namespace daep::world {

/**
 * Redirects stderr (the file descriptor, so C and C++ streams alike) to a temporary file until
 * finish(): libfyaml (inside MRPT's parser) reports syntax errors with line:column only there,
 * and OctoMap prints its read errors there.
 */
class StderrCapture {
public:
    StderrCapture() {
        std::fflush(stderr);
        tmp_ = std::tmpfile();
        if (tmp_ != nullptr)
            saved_ = ::dup(STDERR_FILENO);
        if (saved_ >= 0)
            ::dup2(::fileno(tmp_), STDERR_FILENO);
    }
    ~StderrCapture() { finish(); }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;

    std::string finish() {
        std::string text;
        if (tmp_ == nullptr)
            return text;
        std::fflush(stderr);
        if (saved_ >= 0) {
            ::dup2(saved_, STDERR_FILENO);
            ::close(saved_);
        }
        std::rewind(tmp_);
        char buf[4096];
        for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, tmp_)) > 0;)
            text.append(buf, n);
        std::fclose(tmp_);
        tmp_ = nullptr;
        return text;
    }

private:
    std::FILE* tmp_ = nullptr;
    int saved_ = -1;
};

}  // namespace daep::world
