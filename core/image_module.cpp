#include "core/image_module.h"

#include <dlfcn.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "core/error.h"

namespace so {

namespace {

// Owns one dlopen() reference.
class DlHandle {
  public:
    explicit DlHandle(void* handle) : handle_(handle) {}
    DlHandle(DlHandle&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
    DlHandle(const DlHandle&) = delete;
    DlHandle& operator=(const DlHandle&) = delete;
    DlHandle& operator=(DlHandle&&) = delete;
    ~DlHandle() {
        if (handle_) dlclose(handle_);
    }
    void* get() const { return handle_; }

  private:
    void* handle_;
};

struct LoadedModule {
    DlHandle handle;
    const SoImageModule* table;
};

std::string dlError() {
    const char* e = dlerror();
    return e ? e : "unknown dlopen error";
}

// The table of the module at `path`, or why not (in `why`).
std::optional<LoadedModule> tryLoad(const std::string& path, std::string& why) {
    // RTLD_LOCAL keeps OpenImageIO's symbols out of the global scope. RTLD_NODELETE keeps the code
    // mapped after dlclose(): the handle is released at exit, and unloading OpenImageIO then, with
    // its thread pool and static objects still alive, would be a crash waiting to happen.
    DlHandle handle(dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE));
    if (!handle.get()) {
        why = dlError();
        return std::nullopt;
    }
    auto entry = reinterpret_cast<SoImageModuleEntry>(dlsym(handle.get(), SO_IMAGE_MODULE_ENTRY));
    if (!entry) {
        why = path + ": no symbol " SO_IMAGE_MODULE_ENTRY;
        return std::nullopt;
    }
    const SoImageModule* table = entry();
    if (!table || table->abiVersion != SO_IMAGE_MODULE_ABI_VERSION) {
        why = path + ": interface version " + std::to_string(table ? table->abiVersion : 0) +
              ", not " + std::to_string(SO_IMAGE_MODULE_ABI_VERSION) + " (a stale build?)";
        return std::nullopt;
    }
    return LoadedModule{std::move(handle), table};
}

LoadedModule loadModule() {
    std::string tried;
    for (const std::string& path : imageModuleCandidates()) {
        std::string why;
        if (std::optional<LoadedModule> m = tryLoad(path, why)) return std::move(*m);
        tried += (tried.empty() ? "" : "; ") + why;
    }
    throwInputError("image module", "",
                    "cannot load OpenImageIO's image module, needed to read or write images (" +
                        printable(tried, 1000) +
                        "); build the so_image_oiio target or set SO_IMAGE_MODULE to its path");
}

}  // namespace

std::vector<std::string> imageModuleCandidates() {
    if (const char* env = std::getenv("SO_IMAGE_MODULE"); env && *env) return {env};
    namespace fs = std::filesystem;
    std::vector<std::string> paths;
    std::error_code ec;
    const auto besides = [&](const fs::path& file) {
        paths.push_back((file.parent_path() / SO_IMAGE_MODULE_FILE_NAME).string());
        // The build tree (core/ beside cli/ and api/) and an installed tree (bin/ beside lib/).
        paths.push_back(
            (file.parent_path().parent_path() / "core" / SO_IMAGE_MODULE_FILE_NAME).string());
        paths.push_back(
            (file.parent_path().parent_path() / "lib" / SO_IMAGE_MODULE_FILE_NAME).string());
    };
    // Beside the file that holds this code: a shared library's own folder (a Python module's,
    // whose process is python3, so that /proc/self/exe names the interpreter), or for code linked
    // into a program, the program (glibc names it by argv[0], which may lack its folder: then
    // /proc/self/exe, next, finds it).
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&imageModuleCandidates), &info) && info.dli_fname &&
        std::string_view(info.dli_fname).find('/') != std::string_view::npos) {
        const fs::path self = fs::weakly_canonical(info.dli_fname, ec);
        if (!ec) besides(self);
    }
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) besides(exe);
    paths.push_back(SO_IMAGE_MODULE_BUILD_PATH);
    // The build path is usually one of the first two: try each file once.
    std::vector<std::string> unique;
    for (const std::string& p : paths) {
        const fs::path canonical = fs::weakly_canonical(p, ec);
        const std::string key = ec ? p : canonical.string();
        if (std::find(unique.begin(), unique.end(), key) == unique.end()) unique.push_back(key);
    }
    return unique;
}

namespace {
std::atomic<const SoImageModule*> loadedTable{nullptr};
}  // namespace

const SoImageModule& imageModule() {
    // A function-local static is initialised once, thread-safely; if loading throws, the next
    // call tries again.
    static const LoadedModule module = loadModule();
    loadedTable.store(module.table, std::memory_order_release);
    return *module.table;
}

const SoImageModule* imageModuleIfLoaded() {
    return loadedTable.load(std::memory_order_acquire);
}

}  // namespace so
