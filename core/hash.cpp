#include "core/hash.h"

#include <cstdio>
#include <fstream>
#include <new>
#include <vector>

#include <xxhash.h>

#include "core/error.h"

namespace so {

struct ContentHasher::State {
    XXH3_state_t* xxh = XXH3_createState();
    ~State() { XXH3_freeState(xxh); }
};

ContentHasher::ContentHasher() : state_(std::make_unique<State>()) {
    if (!state_->xxh) throw std::bad_alloc();  // XXH3_createState only fails to allocate
    XXH3_128bits_reset(state_->xxh);
}
ContentHasher::~ContentHasher() = default;

void ContentHasher::add(std::string_view bytes) {
    // Length first, so that ("ab","c") and ("a","bc") hash differently.
    uint64_t n = bytes.size();
    XXH3_128bits_update(state_->xxh, &n, sizeof n);
    XXH3_128bits_update(state_->xxh, bytes.data(), bytes.size());
}

void ContentHasher::addFile(const std::filesystem::path& path, const std::string& name) {
    add(name);
    std::ifstream in(path, std::ios::binary);
    if (!in) throwInputError(path.string(), "", "cannot be read for hashing");
    std::vector<char> buf(1 << 16);
    uint64_t total = 0;
    XXH3_state_t* fileState = XXH3_createState();
    XXH3_128bits_reset(fileState);
    while (in) {
        in.read(buf.data(), std::streamsize(buf.size()));
        std::streamsize got = in.gcount();
        if (got <= 0) break;
        XXH3_128bits_update(fileState, buf.data(), size_t(got));
        total += uint64_t(got);
    }
    XXH128_hash_t h = XXH3_128bits_digest(fileState);
    XXH3_freeState(fileState);
    XXH3_128bits_update(state_->xxh, &total, sizeof total);
    XXH3_128bits_update(state_->xxh, &h, sizeof h);
}

static std::string toHex(XXH128_hash_t h) {
    char buf[33];
    std::snprintf(buf, sizeof buf, "%016llx%016llx", (unsigned long long)h.high64,
                  (unsigned long long)h.low64);
    return buf;
}

std::string ContentHasher::hex() const {
    return toHex(XXH3_128bits_digest(state_->xxh));
}

std::string hashBytes(std::string_view bytes) {
    return toHex(XXH3_128bits(bytes.data(), bytes.size()));
}

}  // namespace so
