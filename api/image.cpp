// The API's images and EXR files.
#include <algorithm>

#include "api/api_internal.h"
#include "core/tool_info.h"

namespace shadow_oracle {

bool Image::has(const std::string& name) const {
    return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<float>& Image::channel(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return planes[size_t(it - names.begin())];
    std::string there;
    for (const std::string& n : names) there += (there.empty() ? "" : ", ") + n;
    throw Error("image: no channel \"" + so::printable(name, 60) + "\" (it has " +
                so::printable(there, 400) + ")");
}

std::vector<float>& Image::add(const std::string& name, float fill) {
    if (has(name)) throw Error("image: channel \"" + so::printable(name, 60) + "\" exists already");
    names.push_back(name);
    planes.emplace_back(size_t(std::max(width, 0)) * size_t(std::max(height, 0)), fill);
    return planes.back();
}

namespace detail {

Image toApi(so::ChannelImage&& image) {
    Image out;
    out.width = image.width();
    out.height = image.height();
    out.names = image.names();
    out.planes = image.releasePlanes();
    return out;
}

so::ChannelImage fromApi(const Image& image) {
    if (image.width < 0 || image.height < 0 || image.names.size() != image.planes.size())
        throw Error("image: " + std::to_string(image.names.size()) + " names for " +
                    std::to_string(image.planes.size()) + " planes, or a negative size");
    so::ChannelImage out(image.width, image.height);
    const size_t pixels = size_t(image.width) * size_t(image.height);
    for (size_t i = 0; i < image.names.size(); ++i) {
        if (image.planes[i].size() != pixels)
            throw Error("image: channel \"" + so::printable(image.names[i], 60) + "\" has " +
                        std::to_string(image.planes[i].size()) + " values, not " +
                        std::to_string(image.width) + " x " + std::to_string(image.height));
        if (out.has(image.names[i]))
            throw Error("image: channel \"" + so::printable(image.names[i], 60) + "\" twice");
        std::copy(image.planes[i].begin(), image.planes[i].end(), out.addChannel(image.names[i]));
    }
    return out;
}

so::ProgressCallback toLibrary(const ProgressCallback& callback) {
    if (!callback) return {};
    return [callback](const so::ProgressUpdate& u) {
        return callback(ProgressUpdate{u.stage, u.done, u.total});
    };
}

}  // namespace detail

std::string version() {
    return so::toolVersionString();
}

Image readExr(const std::string& path) {
    return detail::translated([&] { return detail::toApi(so::readExr(path)); });
}

void writeExr(const std::string& path, const Image& image,
              const std::map<std::string, std::string>& attributes) {
    detail::translated([&] {
        const so::ChannelImage lib = detail::fromApi(image);
        so::writeExr(path, lib, so::ExrAttributes(attributes.begin(), attributes.end()));
    });
}

}  // namespace shadow_oracle
