#include "daep/common/Types.h"

#include <cmath>

namespace daep {

double wrapAngle(double a) {
    a = std::remainder(a, 2.0 * M_PI);
    return a <= -M_PI ? a + 2.0 * M_PI : a;
}

}  // namespace daep
