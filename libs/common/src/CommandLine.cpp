#include "daep/common/CommandLine.h"

#include <CLI/CLI.hpp>
#include <iostream>

#include "daep/common/AppMain.h"
#include "daep/common/BuildInfo.h"
#include "daep/common/Error.h"

namespace daep {
namespace {

constexpr const char* kCommonOptions =
    "Every daep app also takes --version (print the version, commit and libraries) and\n"
    "--debug (errors keep their full text, e.g. MRPT's call stacks).\n";

}  // namespace

struct CommandLine::Impl {
    /** An option's text, checked and stored by its converter once all arguments are read. */
    struct Deferred {
        std::string text;
        CLI::Option* option = nullptr;
        std::function<void(const std::string&)> convert;
    };

    std::string app;
    std::string usage;
    CLI::App cli;
    std::vector<std::unique_ptr<Deferred>> deferred;
    std::vector<std::string>* positionals = nullptr;
    std::vector<std::string> given;
    std::size_t minPositionals = 0, maxPositionals = 0;
    std::string positionalsWhat;
    bool help = false, version = false, debug = false;

    Impl(std::string appName, std::string usageText)
        : app(std::move(appName)), usage(std::move(usageText)), cli(usage, app) {
        cli.set_help_flag();  // --help prints the app's own usage text
        cli.allow_extras();   // reported by check() as one line naming the argument
        cli.add_flag("-h,--help", help);
        cli.add_flag("--version", version);
        cli.add_flag("--debug", debug);
        cli.add_option("_positionals", given)->expected(0, -1);
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw InputError(app + ": " + what + " (see " + app + " --help)");
    }

    void checkExtras() const {
        const auto extras = cli.remaining();
        if (extras.empty())
            return;
        const std::string& first = extras.front();
        fail((first.size() > 1 && first[0] == '-' ? "unknown option " : "unexpected argument ") +
             first);
    }

    void checkPositionals() const {
        if (given.size() > maxPositionals)
            fail("unexpected argument " + given[maxPositionals]);
        if (given.size() < minPositionals)
            fail("expected " + positionalsWhat + " (got " + std::to_string(given.size()) +
                 (given.size() == 1 ? " argument)" : " arguments)"));
        if (positionals)
            *positionals = given;
    }
};

CommandLine::CommandLine(std::string app, std::string usage)
    : impl_(std::make_unique<Impl>(std::move(app), std::move(usage))) {}

CommandLine::~CommandLine() = default;

CommandLine& CommandLine::option(const std::string& names,
                                 std::function<void(const std::string&)> convert) {
    auto d = std::make_unique<Impl::Deferred>();
    d->option = impl_->cli.add_option(names, d->text)
                    ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
    d->convert = std::move(convert);
    impl_->deferred.push_back(std::move(d));
    return *this;
}

CommandLine& CommandLine::option(const std::string& names, std::string& into) {
    return option(names, [&into](const std::string& text) { into = text; });
}

CommandLine& CommandLine::number(const std::string& names, double& into) {
    const std::string flag = names.substr(names.find_last_of(',') + 1);
    return option(
        names, [&into, flag](const std::string& text) { into = parseNumber(flag, text.c_str()); });
}

CommandLine& CommandLine::integer(const std::string& names, int& into) {
    const std::string flag = names.substr(names.find_last_of(',') + 1);
    return option(names, [&into, flag](const std::string& text) {
        std::size_t used = 0;
        try {
            into = std::stoi(text, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != text.size())
            throw InputError(flag + ": '" + text + "' is not a whole number");
    });
}

CommandLine& CommandLine::repeated(const std::string& names, std::vector<std::string>& into) {
    impl_->cli.add_option(names, into)
        ->expected(1)
        ->allow_extra_args(false)  // "--set a=1 CONFIG": CONFIG is not a second value
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
    return *this;
}

CommandLine& CommandLine::flag(const std::string& names, bool& into) {
    impl_->cli.add_flag(names, into);
    return *this;
}

CommandLine& CommandLine::positionals(std::vector<std::string>& into, std::size_t min,
                                      std::size_t max, std::string what) {
    impl_->positionals = &into;
    impl_->minPositionals = min;
    impl_->maxPositionals = max;
    impl_->positionalsWhat = std::move(what);
    return *this;
}

bool CommandLine::parse(int argc, const char* const* argv) {
    Impl& m = *impl_;
    try {
        m.cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        m.fail(errorText(std::string(e.what())));
    }
    setDebugErrors(m.debug);
    if (m.help) {
        std::cout << m.usage << kCommonOptions;
        return false;
    }
    if (m.version) {
        std::cout << versionText(m.app.substr(0, m.app.find(' ')));
        return false;
    }
    m.checkExtras();
    for (const auto& d : m.deferred)
        if (d->option->count() > 0)
            d->convert(d->text);
    m.checkPositionals();
    return true;
}

}  // namespace daep
