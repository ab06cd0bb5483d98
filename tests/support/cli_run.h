// Running the `shadow-oracle` binary (SO_CLI_PATH) from a test, as a user does, and reading what it
// wrote: shared by the CLI, tile and sweep tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace so::test {

struct RunResult {
    int exitCode = -1;  // 128 + the signal when one ended it
    std::string stdoutText;
    std::string stderrText;
};

inline std::string readBytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// Runs `shadow-oracle ARGS`, its standard output and error kept apart.
inline RunResult run(const std::string& args) {
    const std::filesystem::path base =
        std::filesystem::temp_directory_path() / ("so_cli_run_" + std::to_string(::getpid()));
    const std::string out = base.string() + ".out", err = base.string() + ".err";
    const int status =
        std::system((std::string(SO_CLI_PATH) + " " + args + " > " + out + " 2> " + err).c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.stdoutText = readBytes(out);
    r.stderrText = readBytes(err);
    std::filesystem::remove(out);
    std::filesystem::remove(err);
    return r;
}

// Runs `shadow-oracle ARGS`: its exit code, and its standard output then error in `output`.
inline int runMerged(const std::string& args, std::string* output) {
    const RunResult r = run(args);
    *output = r.stdoutText + r.stderrText;
    return r.exitCode;
}

}  // namespace so::test
