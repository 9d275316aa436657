#pragma once

#include <string>
#include <vector>

namespace daep {

/** One `key = value` line of an ini file, with the line it came from. */
struct IniEntry {
    std::string section, key, value;
    int line = 0;
};

struct IniSectionHeader {
    std::string name;
    int line = 0;
};

struct IniText {
    std::vector<IniSectionHeader> sections;  ///< in file order, repeats included
    std::vector<IniEntry> entries;           ///< in file order
};

/**
 * Strict ini reading that keeps line numbers for error messages: `[section]` headers and
 * `key = value` lines; full-line comments start with '#' or ';', and a '#' or ';' after white
 * space starts an inline comment. Malformed lines throw InputError("source:line: ...").
 */
IniText parseIniText(const std::string& text, const std::string& source);

/** The whole file; throws InputError("path: cannot open file"). */
std::string readTextFile(const std::string& path);

/** Without leading and trailing blanks (space, tab, CR). */
std::string trimBlanks(const std::string& s);

}  // namespace daep
