#include "cli/sequence_frames.h"

#include "cli/output.h"
#include "core/error.h"
#include "core/scene_pose.h"

namespace so {

int frameNumber(const std::string& text, const std::string& whole, const char* flag,
                const char* form) {
    if (text.empty() || text.size() > 9 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        throwInputError("command line", flag, "\"" + printable(whole, 40) + "\" is not " + form);
    return std::stoi(text);
}

std::pair<int, int> sequenceFrameRange(const Scene& scene, const std::string& scenePath,
                                       const std::string& frame, const std::string& frames) {
    const bool one = !frame.empty();
    const char* flag = one ? "--frame" : "--frames";
    if (one && !frames.empty())
        throwInputError("command line", "--frame", "cannot be used with --frames");
    if (!scene.sequence)
        throwInputError(scenePath, "sequence",
                        std::string("the scene has no sequence (scene_format 5) for ") + flag);
    std::pair<int, int> range;
    if (one) {
        range.first = range.second = frameNumber(frame, frame, flag, "K (e.g. 8)");
    } else {
        const size_t colon = frames.find(':');
        const char* form = "A:B (e.g. 0:15)";
        if (colon == std::string::npos)
            throwInputError("command line", flag,
                            "\"" + printable(frames, 40) + "\" is not " + form);
        range = {frameNumber(frames.substr(0, colon), frames, flag, form),
                 frameNumber(frames.substr(colon + 1), frames, flag, form)};
        if (range.first > range.second)
            throwInputError("command line", flag, "A must not be after B in A:B");
    }
    if (range.second >= scene.sequence->frames)
        throwInputError("command line", flag,
                        "frame " + std::to_string(range.second) + " is past the sequence's " +
                            std::to_string(scene.sequence->frames) + " frames (0 to " +
                            std::to_string(scene.sequence->frames - 1) + ")");
    return range;
}

std::optional<Scene> sceneAtFrameOption(const Scene& scene, const std::string& scenePath,
                                        const std::string& frame) {
    if (frame.empty()) return std::nullopt;
    const int k = sequenceFrameRange(scene, scenePath, frame, "").first;
    return sceneAtTime(scene, sequenceTime(*scene.sequence, k));
}

}  // namespace so
