#include <gtest/gtest.h>

#include <mrpt/core/exceptions.h>

#include <stdexcept>
#include <string>

#include "daep/common/Error.h"

namespace {

void throwMrptError() {
    MRPT_START
    THROW_EXCEPTION("Expecting 0x00 00 00 while parsing old streaming header");
    MRPT_END
}

/** A real MRPT exception's what(): header, message, location, call stack. */
std::string mrptWhat() {
    try {
        throwMrptError();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

/** Turns debug texts off again whatever a test did. */
class ErrorText : public ::testing::Test {
protected:
    void TearDown() override { daep::setDebugErrors(false); }
};

}  // namespace

TEST_F(ErrorText, MrptExceptionBecomesItsMessageOnOneLine) {
    const std::string what = mrptWhat();
    ASSERT_NE(what.find("Call stack"), std::string::npos) << what;  // the text to tame
    const std::string text = daep::errorText(what);
    EXPECT_EQ(text, "Expecting 0x00 00 00 while parsing old streaming header");
}

TEST_F(ErrorText, KeepsOurPrefixBeforeAWrappedMrptText) {
    const std::string wrapped = "run.rawlog: not a readable MRPT rawlog (object 1): " + mrptWhat();
    EXPECT_EQ(daep::errorText(wrapped),
              "run.rawlog: not a readable MRPT rawlog (object 1): Expecting 0x00 00 00 while "
              "parsing old streaming header");
}

TEST_F(ErrorText, NestedMrptExceptionsGiveTheInnermostCause) {
    const std::string nested =
        "==== MRPT exception ====\nMessage:  Exception while parsing\n"
        "Original exception:\n" +
        mrptWhat() + "\nLocation: x.cpp:1: [f]\nCall stack backtrace:\n";
    EXPECT_EQ(daep::errorText(nested), "Expecting 0x00 00 00 while parsing old streaming header");
}

TEST_F(ErrorText, PlainMessagesKeepTheirFirstLine) {
    EXPECT_EQ(daep::errorText(std::runtime_error("cafe.ini:3: unknown key [x] y")),
              "cafe.ini:3: unknown key [x] y");
    EXPECT_EQ(daep::errorText("\n  first line  \nsecond line\n"), "first line");
}

TEST_F(ErrorText, DebugKeepsTheWholeText) {
    daep::setDebugErrors(true);
    const std::string what = mrptWhat();
    const std::string text = daep::errorText(what);
    EXPECT_NE(text.find("Call stack backtrace"), std::string::npos);
    EXPECT_NE(text.find("Location:"), std::string::npos);
}
