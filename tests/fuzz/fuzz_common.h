// Shared by the libFuzzer harnesses (docs/fuzzing.md): a per-process scratch folder for readers
// that take files, and the one rule of every harness: InputError is the documented answer to a bad
// input, anything else (another exception, a crash, a sanitizer report) is a finding.
#pragma once

#include <sys/types.h>
#include <unistd.h>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/scene.h"

namespace so::fuzz {

// Created on first use under $TMPDIR (or /tmp) as so-fuzz-PID-XXXXXX, reused for every input of
// this process and removed at exit. libFuzzer ends some runs with _Exit, skipping atexit, so the
// folders of processes that no longer exist are removed here too.
inline void removeStaleScratchDirs(const std::filesystem::path& tmp) {
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(tmp, ec)) {
        const std::string name = e.path().filename().string();
        if (name.rfind("so-fuzz-", 0) != 0) continue;
        const long pid = std::strtol(name.c_str() + 8, nullptr, 10);
        if (pid > 0 && kill(pid_t(pid), 0) != 0 && errno == ESRCH)
            std::filesystem::remove_all(e.path(), ec);
    }
}

inline const std::filesystem::path& scratchDir() {
    static const std::filesystem::path dir = [] {
        const char* env = std::getenv("TMPDIR");
        const std::string tmp = env && *env ? env : "/tmp";
        removeStaleScratchDirs(tmp);
        std::string pattern = tmp + "/so-fuzz-" + std::to_string(getpid()) + "-XXXXXX";
        if (!mkdtemp(pattern.data())) {
            std::perror("so-fuzz: mkdtemp");
            std::abort();
        }
        std::atexit([] {
            std::error_code ec;
            std::filesystem::remove_all(scratchDir(), ec);
        });
        return std::filesystem::path(pattern);
    }();
    return dir;
}

inline void writeFile(const std::filesystem::path& path, std::string_view bytes) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) {
        std::fprintf(stderr, "so-fuzz: cannot write %s\n", path.c_str());
        std::abort();
    }
}

// Limits small enough that no input can make a reader allocate more than a few hundred MB.
inline LoadLimits fuzzLimits() {
    LoadLimits l;
    l.maxFileBytes = 1 << 20;
    l.maxTotalBytes = 4 << 20;
    l.maxTrianglesPerMesh = 1 << 16;
    l.maxMeshes = 1 << 10;
    l.maxTotalTriangles = 1 << 18;
    l.maxImageSide = 1024;
    l.maxImagePixels = 1 << 20;
    l.maxTotalImagePixels = 1 << 21;
    l.maxNodeDepth = 32;
    l.maxLights = 16;
    return l;
}

// Runs `body`; an InputError is expected and swallowed. Any other exception is reported and
// aborts, so libFuzzer records the input as a crash.
template <class F>
void expectOnlyInputErrors(F&& body) {
    try {
        body();
    } catch (const InputError&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "so-fuzz: FINDING: exception other than InputError: %s\n", e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "so-fuzz: FINDING: unknown exception\n");
        std::abort();
    }
}

}  // namespace so::fuzz
