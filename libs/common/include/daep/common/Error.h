#pragma once

#include <exception>
#include <stdexcept>
#include <string>

namespace daep {

/** Bad user input (config, world file, command line). The message names the file, line or key. */
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/** --debug: error texts keep everything an exception says (MRPT's call stacks included). */
void setDebugErrors(bool on);
bool debugErrors();

/**
 * What to tell the user about an exception: one line. MRPT exceptions carry a header, the
 * throw location and a call stack in what(); this keeps the text before them and MRPT's own
 * message. With debugErrors() the whole text, unchanged. Use it wherever an exception becomes
 * text (stderr, summary.json's end_reason, logs).
 */
std::string errorText(const std::exception& e);
std::string errorText(const std::string& what);

}  // namespace daep
