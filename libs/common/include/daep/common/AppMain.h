#pragma once

#include <functional>
#include <string>

namespace daep {

/**
 * Runs an app's body with the exit codes every daep tool shares: what the body returns, 1 on
 * bad input (InputError), 2 on any other failure; the message goes to stderr as one line
 * "error: ..." (errorText: the full text with --debug).
 */
int runApp(const std::function<int()>& body);

/** A command-line number; throws InputError naming the flag when `text` is not one. */
double parseNumber(const std::string& flag, const char* text);

}  // namespace daep
