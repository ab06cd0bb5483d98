#include "core/gltf_extensions.h"

#include <algorithm>
#include <set>

namespace so::gltf_detail {

namespace {

// Read by the loader: what each changes is in docs/scene-format.md.
bool isRead(const std::string& name) {
    static const std::set<std::string> read = {
        "KHR_lights_punctual",     "KHR_texture_transform", "KHR_draco_mesh_compression",
        "EXT_meshopt_compression", "KHR_mesh_quantization", "EXT_texture_webp"};
    return read.count(name) > 0;
}

// Material extensions that change how a surface is shaded but not where it is: coverage comes from
// the core material's alphaMode, alphaCutoff and base colour alpha, which these leave alone, so a
// file requiring one still has exactly the shadows it describes. Two KHR_materials_ extensions do
// change coverage and are not in this set: KHR_materials_pbrSpecularGlossiness (alpha from its
// own diffuse factor and texture) and KHR_materials_variants (other materials, other alphaModes).
bool isShadingOnly(const std::string& name) {
    return name.rfind("KHR_materials_", 0) == 0 && name != "KHR_materials_pbrSpecularGlossiness" &&
           name != "KHR_materials_variants";
}

std::vector<std::string> names(const Context& ctx, const Json& doc, const char* key) {
    std::vector<std::string> out;
    const Json* list = member(doc, key);
    if (!list) return out;
    if (!list->is_array()) fail(ctx, key, "not an array");
    for (size_t i = 0; i < list->size(); ++i) {
        if (!(*list)[i].is_string()) fail(ctx, idx(key, i), "not a string");
        out.push_back((*list)[i].get<std::string>());
    }
    return out;
}

}  // namespace

GltfExtensions checkExtensions(const Context& ctx, const Json& doc) {
    const std::vector<std::string> used = names(ctx, doc, "extensionsUsed");
    const std::vector<std::string> required = names(ctx, doc, "extensionsRequired");
    for (const std::string& name : required)
        if (!isRead(name) && !isShadingOnly(name))
            fail(ctx, "extensionsRequired", "unsupported extension " + printable(name, 80));
    GltfExtensions ext;
    std::set<std::string> ignored;
    for (const std::string& name : used) {
        if (name == "KHR_mesh_quantization") ext.meshQuantization = true;
        if (!isRead(name)) ignored.insert(printable(name, 80));
    }
    // A required extension is used by definition, even where extensionsUsed forgets it.
    for (const std::string& name : required) {
        if (name == "KHR_mesh_quantization") ext.meshQuantization = true;
        if (!isRead(name)) ignored.insert(printable(name, 80));
    }
    ext.ignored.assign(ignored.begin(), ignored.end());
    return ext;
}

}  // namespace so::gltf_detail
