#include "daep/common/Sanitizers.h"

#if defined(__SANITIZE_ADDRESS__)
#define DAEP_LEAK_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(leak_sanitizer)
#define DAEP_LEAK_SANITIZER 1
#endif
#endif

#ifdef DAEP_LEAK_SANITIZER
#include <sanitizer/lsan_interface.h>
#endif

namespace daep {

void leakCheckBeforeDynamicTls() {
#ifdef DAEP_LEAK_SANITIZER
    static bool checked = false;
    if (!checked) {
        checked = true;
        __lsan_do_leak_check();
    }
#endif
}

}  // namespace daep
