#include "daep/common/Error.h"

#include <atomic>
#include <sstream>

namespace daep {
namespace {

std::atomic<bool> g_debugErrors{false};

constexpr const char* kMrptHeader = "==== MRPT exception ====";
constexpr const char* kMrptMessage = "Message:";
constexpr const char* kMrptLocation = "Location:";
constexpr const char* kMrptNested = "Original exception:";

std::string trimmed(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first == std::string::npos)
        return "";
    return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

std::string firstNonEmptyLine(const std::string& text) {
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (!trimmed(line).empty())
            return trimmed(line);
    return "";
}

/** The innermost "Message:" of an MRPT exception text (nested ones come later), on one line. */
std::string innermostMrptMessage(const std::string& text) {
    const auto at = text.rfind(kMrptMessage);
    if (at == std::string::npos)
        return "";
    const auto begin = at + std::string(kMrptMessage).size();
    auto end = text.find(kMrptLocation, begin);
    end = std::min(end, text.find(kMrptNested, begin));
    std::istringstream in(text.substr(begin, end == std::string::npos ? end : end - begin));
    std::string joined;
    for (std::string line; std::getline(in, line);)
        if (!trimmed(line).empty())
            joined += (joined.empty() ? "" : " ") + trimmed(line);
    return joined;
}

}  // namespace

void setDebugErrors(bool on) {
    g_debugErrors = on;
}

bool debugErrors() {
    return g_debugErrors;
}

std::string errorText(const std::string& what) {
    if (debugErrors())
        return trimmed(what);
    const auto header = what.find(kMrptHeader);
    if (header == std::string::npos)
        return firstNonEmptyLine(what);
    const std::string before = firstNonEmptyLine(what.substr(0, header));
    const std::string message = innermostMrptMessage(what);
    if (before.empty())
        return message.empty() ? "MRPT exception" : message;
    return message.empty() ? before : before + " " + message;
}

std::string errorText(const std::exception& e) {
    return errorText(std::string(e.what()));
}

}  // namespace daep
