#include "core/process_clock.h"

#include <time.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

namespace so {

double processSeconds() {
    // /proc/self/stat: the command name (field 2) is in parentheses and may hold spaces, so the
    // fields are counted from the last ')'; starttime (field 22) is in clock ticks since boot.
    std::ifstream in("/proc/self/stat");
    std::string line;
    if (!std::getline(in, line)) return -1.0;
    const size_t close = line.rfind(')');
    if (close == std::string::npos) return -1.0;
    std::istringstream fields(line.substr(close + 2));
    std::string field;
    for (int i = 3; i < 22 && fields >> field; ++i) {
    }
    unsigned long long startTicks = 0;
    if (!(fields >> startTicks)) return -1.0;
    const long ticksPerSecond = sysconf(_SC_CLK_TCK);
    timespec now{};
    if (ticksPerSecond <= 0 || clock_gettime(CLOCK_BOOTTIME, &now) != 0) return -1.0;
    const double nowSeconds = double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
    return nowSeconds - double(startTicks) / double(ticksPerSecond);
}

}  // namespace so
