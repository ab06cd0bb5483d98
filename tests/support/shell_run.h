// The tests that drive third-party programs (Blender; scripts/cycles-compare) run shell commands
// and read what they print.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace so::test {

struct Shell {
    int rc = -1;
    std::string out;  // stdout and stderr together
};

// `command` through /bin/sh; rc is its exit status (128 + the signal where one ended it), -1 where
// it could not start.
inline Shell shell(const std::string& command) {
    Shell r;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.out.append(buffer, n);
    const int status = ::pclose(pipe);
    r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return r;
}

// `s` as one word for /bin/sh.
inline std::string quote(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

}  // namespace so::test
