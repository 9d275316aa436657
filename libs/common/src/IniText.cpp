#include "daep/common/IniText.h"

#include <fstream>
#include <sstream>

#include "daep/common/Error.h"

namespace daep {
namespace {

/** Strips a trailing "  # comment" (a '#' or ';' preceded by white space). */
std::string stripComment(const std::string& s) {
    for (std::size_t i = 1; i < s.size(); ++i)
        if ((s[i] == '#' || s[i] == ';') && (s[i - 1] == ' ' || s[i - 1] == '\t'))
            return s.substr(0, i);
    return s;
}

}  // namespace

std::string trimBlanks(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos)
        return {};
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

IniText parseIniText(const std::string& text, const std::string& source) {
    IniText out;
    std::istringstream in(text);
    std::string raw, section;
    for (int lineNo = 1; std::getline(in, raw); ++lineNo) {
        const std::string line = trimBlanks(stripComment(raw));
        if (line.empty() || line[0] == '#' || line[0] == ';')
            continue;
        const std::string where = source + ":" + std::to_string(lineNo) + ": ";
        if (line.front() == '[') {
            if (line.back() != ']')
                throw InputError(where + "malformed section header '" + line + "'");
            section = trimBlanks(line.substr(1, line.size() - 2));
            out.sections.push_back({section, lineNo});
            continue;
        }
        const auto eq = line.find('=');
        if (eq == std::string::npos)
            throw InputError(where + "expected 'key = value', got '" + line + "'");
        if (section.empty())
            throw InputError(where + "key outside any [section]");
        const std::string key = trimBlanks(line.substr(0, eq));
        if (key.empty())
            throw InputError(where + "empty key");
        out.entries.push_back({section, key, trimBlanks(line.substr(eq + 1)), lineNo});
    }
    return out;
}

std::string readTextFile(const std::string& path) {
    std::ifstream f(path);
    if (!f)
        throw InputError(path + ": cannot open file");
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace daep
