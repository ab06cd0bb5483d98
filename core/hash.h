// Content hashes for cache keys and provenance: XXH3-128 (libxxhash) as 32 hex digits.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace so {

class ContentHasher {
  public:
    ContentHasher();
    ~ContentHasher();
    ContentHasher(const ContentHasher&) = delete;
    ContentHasher& operator=(const ContentHasher&) = delete;

    void add(std::string_view bytes);
    // Hashes the file's name (as given) and its bytes; throws InputError if it cannot be read.
    void addFile(const std::filesystem::path& path, const std::string& name);
    std::string hex() const;

  private:
    struct State;
    std::unique_ptr<State> state_;
};

std::string hashBytes(std::string_view bytes);

}  // namespace so
