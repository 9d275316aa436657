#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace daep {

/**
 * The command line of a daep app, parsed by CLI11 (kept out of this header: it is large).
 * Every app gets the same --help (prints the app's usage text), --version (versionText) and
 * --debug (errors keep their full text, MRPT's call stacks included). Bad arguments throw
 * InputError with one line that names the option.
 */
class CommandLine {
public:
    /** `app` names the program in messages ("daep-world reach"); `usage` is printed by --help. */
    CommandLine(std::string app, std::string usage);
    ~CommandLine();
    CommandLine(const CommandLine&) = delete;
    CommandLine& operator=(const CommandLine&) = delete;

    /** An option with a value, e.g. names "-o,--out"; given twice, the last one counts. */
    CommandLine& option(const std::string& names, std::string& into);
    /** An option whose value `convert` checks and stores; it throws InputError when bad. */
    CommandLine& option(const std::string& names, std::function<void(const std::string&)> convert);
    /** A number option; a value that is not a number is an InputError naming the option. */
    CommandLine& number(const std::string& names, double& into);
    /** A whole-number option; a value that is not a whole number is an InputError. */
    CommandLine& integer(const std::string& names, int& into);
    /** An option that may be given many times, every value kept in order (e.g. --set). */
    CommandLine& repeated(const std::string& names, std::vector<std::string>& into);
    /** A flag without a value. */
    CommandLine& flag(const std::string& names, bool& into);
    /** The arguments that are not options, in order; parse() checks how many. */
    CommandLine& positionals(std::vector<std::string>& into, std::size_t min, std::size_t max,
                             std::string what);

    /**
     * Parses argv[1..argc). Returns false when the app has nothing more to do (--help or
     * --version printed); throws InputError on bad arguments. --debug turns on
     * setDebugErrors(true).
     */
    bool parse(int argc, const char* const* argv);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep
