#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "daep/common/CommandLine.h"
#include "daep/common/Error.h"

namespace {

/** The options of a typical app, parsed from `args` (without the program name). */
struct Parsed {
    std::vector<std::string> sets, positionals;
    std::string out;
    double range = 5.0;
    int count = 3;
    bool quiet = false;
    bool proceed = false;
};

Parsed parse(std::vector<std::string> args) {
    args.insert(args.begin(), "daep-test");
    std::vector<const char*> argv;
    for (const auto& a : args)
        argv.push_back(a.c_str());
    Parsed p;
    daep::CommandLine cli("daep-test", "usage: daep-test CONFIG [options]\n");
    cli.repeated("--set", p.sets)
        .option("-o,--out", p.out)
        .number("--range", p.range)
        .integer("--count", p.count)
        .flag("-q,--quiet", p.quiet)
        .positionals(p.positionals, 1, 2, "CONFIG");
    p.proceed = cli.parse(static_cast<int>(argv.size()), argv.data());
    return p;
}

/** The InputError message parse() throws for `args`, or "" when it throws none. */
std::string errorOf(const std::vector<std::string>& args) {
    try {
        parse(args);
    } catch (const daep::InputError& e) {
        return e.what();
    }
    return "";
}

class CommandLineTest : public ::testing::Test {
protected:
    void TearDown() override { daep::setDebugErrors(false); }
};

}  // namespace

TEST_F(CommandLineTest, ReadsOptionsFlagsAndPositionalsInAnyOrder) {
    const auto p = parse({"--set", "a.b=1", "cfg.ini", "--out=dir", "--set=c.d=2", "-q", "--range",
                          "2.5", "--count", "7", "extra.csv"});
    EXPECT_TRUE(p.proceed);
    EXPECT_EQ(p.sets, (std::vector<std::string>{"a.b=1", "c.d=2"}));
    EXPECT_EQ(p.positionals, (std::vector<std::string>{"cfg.ini", "extra.csv"}));
    EXPECT_EQ(p.out, "dir");
    EXPECT_DOUBLE_EQ(p.range, 2.5);
    EXPECT_EQ(p.count, 7);
    EXPECT_TRUE(p.quiet);
    EXPECT_FALSE(daep::debugErrors());
}

TEST_F(CommandLineTest, DefaultsStayWhenOptionsAreAbsent) {
    const auto p = parse({"cfg.ini"});
    EXPECT_EQ(p.out, "");
    EXPECT_DOUBLE_EQ(p.range, 5.0);
    EXPECT_EQ(p.count, 3);
    EXPECT_FALSE(p.quiet);
}

TEST_F(CommandLineTest, HelpAndVersionStopWithoutCheckingTheRest) {
    testing::internal::CaptureStdout();
    EXPECT_FALSE(parse({"--help"}).proceed);
    const std::string help = testing::internal::GetCapturedStdout();
    EXPECT_EQ(help.rfind("usage: daep-test CONFIG [options]\n", 0), 0u) << help;
    EXPECT_NE(help.find("--version"), std::string::npos);
    EXPECT_NE(help.find("--debug"), std::string::npos);

    testing::internal::CaptureStdout();
    EXPECT_FALSE(parse({"--version"}).proceed);
    EXPECT_EQ(testing::internal::GetCapturedStdout().rfind("daep-test ", 0), 0u);
}

TEST_F(CommandLineTest, DebugTurnsOnFullErrorTexts) {
    EXPECT_TRUE(parse({"cfg.ini", "--debug"}).proceed);
    EXPECT_TRUE(daep::debugErrors());
}

TEST_F(CommandLineTest, BadArgumentsAreOneLineInputErrorsNamingTheArgument) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"cfg.ini", "--frobnicate"}, "unknown option --frobnicate"},
        {{"a", "b", "c"}, "unexpected argument c"},
        {{}, "expected CONFIG (got 0 arguments)"},
        {{"cfg.ini", "--range", "far"}, "--range: 'far' is not a number"},
        {{"cfg.ini", "--count", "2.5"}, "--count: '2.5' is not a whole number"},
        {{"cfg.ini", "--out"}, "--out"},
    };
    for (const auto& [args, expected] : cases) {
        const std::string message = errorOf(args);
        EXPECT_NE(message.find(expected), std::string::npos)
            << "'" << message << "' lacks '" << expected << "'";
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}
