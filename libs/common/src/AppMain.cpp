#include "daep/common/AppMain.h"

#include <exception>
#include <iostream>

#include "daep/common/Error.h"

namespace daep {

int runApp(const std::function<int()>& body) {
    try {
        return body();
    } catch (const InputError& e) {
        std::cerr << "error: " << errorText(e) << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "error: " << errorText(e) << "\n";
        return 2;
    }
}

double parseNumber(const std::string& flag, const char* text) {
    try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == std::string(text).size())
            return v;
    } catch (const std::exception&) {
    }
    throw InputError(flag + ": '" + text + "' is not a number");
}

}  // namespace daep
