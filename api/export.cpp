// The API's `export` (docs/export.md): the folder written by export/export_folder.h.
#include "api/api_internal.h"
#include "raster_compare/export/export_folder.h"

namespace shadow_oracle {

std::string exportScene(const Scene& scene, const std::string& outDir, int width, int height,
                        int threads) {
    return detail::translated([&] {
        so::OracleOptions oracle;
        oracle.width = width;
        oracle.height = height;
        oracle.threads = threads;
        const so::Scene& s = scene.data().scene;
        const std::string path = s.path.empty() ? "(scene in memory)" : s.path.string();
        return so::exportScene(s, path, oracle, outDir).glb.string();
    });
}

}  // namespace shadow_oracle
