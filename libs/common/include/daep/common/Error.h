#pragma once

#include <stdexcept>
#include <string>

namespace daep {

/** Bad user input (config, world file, command line). The message names the file, line or key. */
class InputError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace daep
