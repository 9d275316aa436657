#include <gtest/gtest.h>

#include "daep/common/Error.h"
#include "daep/common/IniText.h"

using daep::InputError;
using daep::parseIniText;

namespace {
std::string errorOf(const std::string& text) {
    try {
        parseIniText(text, "f.ini");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(IniText, KeepsSectionsEntriesAndTheirLines) {
    const auto ini = parseIniText(
        "# comment\n[a]\nx = 1\n  ; indented comment\ny=two words  # inline\n\n[b]  # note\n"
        "[c]\nz = a#b\n",
        "f.ini");
    ASSERT_EQ(ini.sections.size(), 3u);
    EXPECT_EQ(ini.sections[1].name, "b");
    EXPECT_EQ(ini.sections[1].line, 7);
    ASSERT_EQ(ini.entries.size(), 3u);
    EXPECT_EQ(ini.entries[0].section, "a");
    EXPECT_EQ(ini.entries[0].line, 3);
    EXPECT_EQ(ini.entries[1].value, "two words");
    EXPECT_EQ(ini.entries[2].section, "c");
    EXPECT_EQ(ini.entries[2].value, "a#b");  // '#' not after a blank is part of the value
}

TEST(IniText, MalformedLinesNameSourceAndLine) {
    EXPECT_EQ(errorOf("[a\n"), "f.ini:1: malformed section header '[a'");
    EXPECT_EQ(errorOf("[a]\nnovalue\n"), "f.ini:2: expected 'key = value', got 'novalue'");
    EXPECT_EQ(errorOf("x = 1\n"), "f.ini:1: key outside any [section]");
    EXPECT_EQ(errorOf("[a]\n = 1\n"), "f.ini:2: empty key");
}

TEST(IniText, MissingFileIsNamed) {
    try {
        daep::readTextFile("/nonexistent/x.ini");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()), "/nonexistent/x.ini: cannot open file");
    }
}
