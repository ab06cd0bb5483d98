// The Python module shadow_oracle (docs/python.md): the public C++ API
// (include/shadow_oracle/shadow_oracle.h) with numpy arrays for images. Long calls run on a worker
// thread with the GIL released while this thread waits, looks for Ctrl-C every 50 ms and passes
// progress to the caller's callback: a KeyboardInterrupt cancels the work within a tile of it and
// leaves nothing behind.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "shadow_oracle/shadow_oracle.h"

namespace py = pybind11;
namespace so = shadow_oracle;

namespace {

// A plane as a (height, width) float32 array that owns the vector it was moved from: no copy.
py::array_t<float> planeArray(std::vector<float>&& plane, int width, int height) {
    auto* owned = new std::vector<float>(std::move(plane));
    py::capsule free(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    return py::array_t<float>(
        {py::ssize_t(height), py::ssize_t(width)},
        {py::ssize_t(width) * py::ssize_t(sizeof(float)), py::ssize_t(sizeof(float))},
        owned->data(), free);
}

// Every channel by its EXR name, in the image's order.
py::dict imageDict(so::Image&& image) {
    py::dict out;
    for (size_t i = 0; i < image.names.size(); ++i)
        out[py::str(image.names[i])] =
            planeArray(std::move(image.planes[i]), image.width, image.height);
    return out;
}

// A 2-D float array (any float dtype, any strides) as a plane of `width` x `height`.
std::vector<float> planeFrom(const py::handle& object, const std::string& what, int width,
                             int height) {
    const py::array array = py::array::ensure(object);
    if (!array) throw py::type_error(what + ": expected a numpy array");
    if (array.dtype().kind() != 'f')
        throw py::type_error(what + ": expected a float array, got dtype " +
                             std::string(py::str(array.dtype())));
    if (array.ndim() != 2 || (width >= 0 && (array.shape(0) != height || array.shape(1) != width)))
        throw py::value_error(what + ": expected shape (" + std::to_string(height) + ", " +
                              std::to_string(width) + "), got " +
                              std::string(py::str(array.attr("shape"))));
    const auto f = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
    return std::vector<float>(f.data(), f.data() + f.size());
}

// Runs `work` on a worker thread; this thread, which holds the GIL only while it looks, checks for
// Ctrl-C and calls `progress(stage, done, total)` every 50 ms. Returns work's result or raises.
template <typename Result>
Result interruptible(const std::function<Result(const so::ProgressCallback&)>& work,
                     const py::object& progress) {
    std::atomic<bool> cancel{false};
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::optional<so::ProgressUpdate> latest;
    std::optional<Result> result;
    std::exception_ptr error;
    const so::ProgressCallback callback = [&](const so::ProgressUpdate& u) {
        std::lock_guard lock(mutex);
        latest = u;
        return !cancel.load();
    };
    std::thread worker([&] {
        try {
            result.emplace(work(callback));
        } catch (...) {
            error = std::current_exception();
        }
        std::lock_guard lock(mutex);
        done = true;
        finished.notify_all();
    });
    const auto stop = [&] {
        cancel = true;
        py::gil_scoped_release release;
        worker.join();
    };
    for (;;) {
        std::optional<so::ProgressUpdate> update;
        {
            py::gil_scoped_release release;
            std::unique_lock lock(mutex);
            finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; });
            if (done) break;
            update.swap(latest);
        }
        if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt (or another handler's exception)
            stop();
            throw py::error_already_set();
        }
        if (update && !progress.is_none()) {
            try {
                const py::object go = progress(update->stage, update->done, update->total);
                if (!go.is_none() && !go.cast<bool>()) cancel = true;
            } catch (...) {
                stop();
                throw;
            }
        }
    }
    worker.join();
    if (error) std::rethrow_exception(error);
    // The last update (a stage's completion, or all of a run shorter than one wait).
    if (latest && !progress.is_none()) progress(latest->stage, latest->done, latest->total);
    return std::move(*result);
}

std::string jsonDumps(const py::object& object) {
    return py::module_::import("json").attr("dumps")(object).cast<std::string>();
}

py::object jsonLoads(const std::string& text) {
    return py::module_::import("json").attr("loads")(text);
}

// meshes: a list of (vertices (N, 3), triangles (M, 3)) pairs.
std::vector<so::Mesh> meshesFrom(const py::list& meshes) {
    std::vector<so::Mesh> out;
    for (size_t m = 0; m < meshes.size(); ++m) {
        const std::string what = "meshes[" + std::to_string(m) + "]";
        const py::tuple pair = meshes[m].cast<py::tuple>();
        if (pair.size() != 2) throw py::value_error(what + ": expected (vertices, triangles)");
        const py::array v = py::array::ensure(pair[0]);
        const py::array t = py::array::ensure(pair[1]);
        if (!v || v.ndim() != 2 || v.shape(1) != 3 ||
            (v.dtype().kind() != 'f' && v.dtype().kind() != 'i'))
            throw py::value_error(what + ": vertices must be a numeric array of shape (N, 3)");
        if (!t || t.ndim() != 2 || t.shape(1) != 3 ||
            (t.dtype().kind() != 'i' && t.dtype().kind() != 'u'))
            throw py::value_error(what + ": triangles must be an integer array of shape (M, 3)");
        const auto vd = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(v);
        const auto td = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(t);
        so::Mesh mesh;
        mesh.name = what;
        mesh.positions.assign(vd.data(), vd.data() + vd.size());
        for (py::ssize_t i = 0; i < td.size(); ++i) {
            const int64_t index = td.data()[i];
            if (index < 0 || index > int64_t(UINT32_MAX))
                throw py::value_error(what + ": triangle index " + std::to_string(index) +
                                      " out of range");
            mesh.triangles.push_back(uint32_t(index));
        }
        out.push_back(std::move(mesh));
    }
    return out;
}

// What trace() returns: the images as arrays, the statistics as oracle.json's "stats".
struct PyTrace {
    so::TraceResult result;  // its image moved out into `images`
    py::dict images;
    int width = 0, height = 0;
    std::vector<std::string> lights;
};

// NAME.<kind> of every light that has one, by light name.
py::dict lightPlanes(const py::dict& images, const std::vector<std::string>& lights,
                     const std::string& kind) {
    py::dict out;
    for (const std::string& light : lights) {
        const py::str key(light + "." + kind);
        if (images.contains(key)) out[py::str(light)] = images[key];
    }
    return out;
}

// P.x, P.y, P.z (or N.*) as one (height, width, 3) array.
py::object vectorPlanes(const py::dict& images, const std::string& name) {
    py::list planes;
    for (const char* axis : {".X", ".Y", ".Z"}) planes.append(images[py::str(name + axis)]);
    return py::module_::import("numpy").attr("stack")(planes, py::arg("axis") = -1);
}

std::vector<std::string> lightNames(const so::Scene& scene) {
    std::vector<std::string> names;
    for (const so::LightInfo& l : scene.lights()) names.push_back(l.name);
    return names;
}

void bindImages(py::module_& m) {
    m.def(
        "read_exr", [](const std::string& path) { return imageDict(so::readExr(path)); },
        py::arg("path"),
        "Every channel of an EXR as a dict of (height, width) float32 arrays by channel name.");
    m.def(
        "write_exr",
        [](const std::string& path, const py::dict& channels,
           const std::map<std::string, std::string>& attributes) {
            so::Image image;
            image.width = image.height = -1;
            for (const auto& [name, array] : channels) {
                const std::string key = py::str(name);
                const py::array a = py::array::ensure(array);
                if (!a || a.ndim() != 2)
                    throw py::value_error("channel " + key + ": expected a 2-D float array");
                if (image.width < 0) {
                    image.height = int(a.shape(0));
                    image.width = int(a.shape(1));
                }
                image.names.push_back(key);
                image.planes.push_back(
                    planeFrom(array, "channel " + key, image.width, image.height));
            }
            if (image.names.empty()) throw py::value_error("write_exr: no channels");
            py::gil_scoped_release release;
            so::writeExr(path, image, attributes);
        },
        py::arg("path"), py::arg("channels"),
        py::arg("attributes") = std::map<std::string, std::string>{},
        "Writes (height, width) float arrays as 32-bit float channels, ZIP-compressed "
        "(docs/exr-channels.md).");
}

void bindScene(py::module_& m) {
    py::class_<so::Scene>(m, "Scene", "A loaded scene: immutable, shareable between threads.")
        .def_property_readonly("path", &so::Scene::path)
        .def_property_readonly("hash", &so::Scene::hash)
        .def_property_readonly(
            "lights",
            [](const so::Scene& s) {
                py::list out;
                for (const so::LightInfo& l : s.lights())
                    out.append(py::dict(py::arg("name") = l.name, py::arg("type") = l.type,
                                        py::arg("area") = l.area));
                return out;
            })
        .def_property_readonly("effects", &so::Scene::effects)
        .def_property_readonly("camera_size", &so::Scene::cameraSize)
        .def_property_readonly("triangles", &so::Scene::triangles)
        .def_property_readonly("warnings", &so::Scene::warnings)
        .def_property_readonly("frames", &so::Scene::frames,
                               "the sequence's frame count (0 without a sequence)")
        .def_property_readonly("fps", &so::Scene::fps, "the sequence's frames per second")
        .def(
            "at_frame",
            [](const so::Scene& s, int k) {
                py::gil_scoped_release release;
                return s.atFrame(k);
            },
            py::arg("k"), "The scene posed at frame k of its sequence (t = k / fps).")
        .def("__repr__", [](const so::Scene& s) {
            return "<shadow_oracle.Scene " + (s.path().empty() ? "in memory" : s.path()) + ", " +
                   std::to_string(s.triangles()) + " triangles, " +
                   std::to_string(s.lights().size()) + " lights>";
        });
    m.def(
        "load_scene",
        [](const std::string& path) {
            py::gil_scoped_release release;
            return so::Scene::load(path);
        },
        py::arg("path"), "A scene file (.json, docs/scene-format.md) or a bare .gltf / .glb.");
    m.def(
        "make_scene",
        [](const py::list& meshes, const py::list& lights, const py::object& camera,
           const py::object& effects) {
            py::dict description;
            description["lights"] = lights;
            if (!camera.is_none()) description["camera"] = camera;
            if (!effects.is_none()) description["effects"] = effects;
            const std::vector<so::Mesh> list = meshesFrom(meshes);
            const std::string text = jsonDumps(description);
            py::gil_scoped_release release;
            return so::Scene::fromMeshes(list, text);
        },
        py::arg("meshes"), py::arg("lights"), py::arg("camera") = py::none(),
        py::arg("effects") = py::none(),
        "A scene from arrays: meshes as (vertices (N, 3), triangles (M, 3)) pairs in world "
        "space, lights and camera as the scene format's dicts, effects as its list.");
    m.def(
        "export_scene",
        [](const so::Scene& scene, const std::string& outDir, int width, int height, int threads) {
            py::gil_scoped_release release;
            return so::exportScene(scene, outDir, width, height, threads);
        },
        py::arg("scene"), py::arg("out_dir"), py::arg("width") = 0, py::arg("height") = 0,
        py::arg("threads") = 0,
        "`shadow-oracle export` (docs/export.md): out_dir gets scene.glb, scene.scene.json, "
        "view.json and gbuffer.exr for the view at width x height (0: the scene camera's). "
        "Returns the glb's path.");
}

void bindTrace(py::module_& m) {
    py::class_<PyTrace>(m, "Trace", "The oracle's result (trace()).")
        .def_property_readonly(
            "images", [](const PyTrace& t) { return t.images; },
            "Every channel of oracle.exr by name, (height, width) float32.")
        .def_property_readonly("width", [](const PyTrace& t) { return t.width; })
        .def_property_readonly("height", [](const PyTrace& t) { return t.height; })
        .def_property_readonly(
            "stats", [](const PyTrace& t) { return jsonLoads(t.result.statsJson); },
            "oracle.json's \"stats\" as a dict.")
        .def_property_readonly("disagreements",
                               [](const PyTrace& t) { return t.result.disagreements; })
        .def_property_readonly(
            "V", [](const PyTrace& t) { return lightPlanes(t.images, t.lights, "V"); },
            "Per light: the visibility V in [0, 1], by light name.")
        .def_property_readonly(
            "stderr", [](const PyTrace& t) { return lightPlanes(t.images, t.lights, "stderr"); },
            "Per sampled area light: V's standard error.")
        .def_property_readonly(
            "spp", [](const PyTrace& t) { return lightPlanes(t.images, t.lights, "spp"); },
            "Per sampled area light: the samples each pixel took.")
        .def_property_readonly(
            "P", [](const PyTrace& t) { return vectorPlanes(t.images, "P"); },
            "World-space positions, (height, width, 3).")
        .def_property_readonly(
            "N", [](const PyTrace& t) { return vectorPlanes(t.images, "N"); },
            "World-space normals, (height, width, 3).")
        .def("__getitem__", [](const PyTrace& t, const std::string& name) {
            const py::str key(name);
            if (!t.images.contains(key)) throw py::key_error(name);
            return t.images[key];
        });
    const so::TraceOptions kTrace;
    m.def(
        "trace",
        [](const so::Scene& scene, int width, int height, double targetError,
           double agreementTarget, int maxSpp, int spp, unsigned seed, int threads, int verify,
           const std::string& penumbra, const std::string& exactPixels,
           const std::optional<std::string>& points, const py::object& progress, double boundTarget,
           int boundMaxSides) {
            so::TraceOptions o;
            o.width = width;
            o.height = height;
            o.targetError = targetError;
            o.agreementTarget = agreementTarget;
            o.maxSpp = maxSpp;
            o.fixedSpp = spp;
            o.seed = seed;
            o.threads = threads;
            o.verify = verify;
            o.penumbra = penumbra;
            o.exactPixels = exactPixels;
            o.points = points.value_or("");
            o.boundTarget = boundTarget;
            o.boundMaxSides = boundMaxSides;
            PyTrace out;
            out.result = interruptible<so::TraceResult>(
                [&](const so::ProgressCallback& cb) {
                    so::TraceOptions withProgress = o;
                    withProgress.progress = cb;
                    return so::trace(scene, withProgress);
                },
                progress);
            out.width = out.result.image.width;
            out.height = out.result.image.height;
            out.lights = lightNames(scene);
            out.images = imageDict(std::move(out.result.image));
            return out;
        },
        // The keywords and defaults of TraceOptions (the trace option table's; tests/python
        // checks this signature and the .pyi stub against trace_options()).
        py::arg("scene"), py::kw_only(), py::arg("width") = kTrace.width,
        py::arg("height") = kTrace.height, py::arg("target_error") = kTrace.targetError,
        py::arg("agreement_target") = kTrace.agreementTarget, py::arg("max_spp") = kTrace.maxSpp,
        py::arg("spp") = kTrace.fixedSpp, py::arg("seed") = kTrace.seed,
        py::arg("threads") = kTrace.threads, py::arg("verify") = kTrace.verify,
        py::arg("penumbra") = kTrace.penumbra, py::arg("exact_pixels") = kTrace.exactPixels,
        py::arg("points") = py::none(), py::arg("progress") = py::none(),
        py::arg("bound_target") = kTrace.boundTarget,
        py::arg("bound_max_sides") = kTrace.boundMaxSides,
        "The oracle (`shadow-oracle trace`): exact hard shadows; penumbrae by penumbra=\"auto\" "
        "(default: per light, exact where a probe estimates it cheaper than sampling), "
        "\"exact\" (rect lights exactly, disk and sphere lights with a stated error), "
        "\"sampled\" (95% intervals) or \"both\". "
        "progress(stage, done, total) is called every 50 ms; return False to cancel.");
    m.def(
        "write_trace_output",
        [](const so::Scene& scene, const PyTrace& trace, const std::string& outDir, bool previews) {
            py::gil_scoped_release release;
            return so::writeTraceOutput(scene, trace.result, outDir, previews);
        },
        py::arg("scene"), py::arg("trace"), py::arg("out_dir"), py::kw_only(),
        py::arg("previews") = true,
        "`shadow-oracle trace`'s folder from a trace() result: oracle.exr, oracle.json and a "
        "NAME.png preview per light. Returns the paths written.");
}

// A technique's keyword settings as the command line writes them: numbers, names, booleans.
so::Parameters parametersFrom(const py::kwargs& kwargs) {
    so::Parameters out;
    for (const auto& [key, value] : kwargs) {
        std::string text;
        if (py::isinstance<py::bool_>(value))
            text = value.cast<bool>() ? "1" : "0";
        else if (py::isinstance<py::str>(value))
            text = value.cast<std::string>();
        else if (py::isinstance<py::int_>(value))
            text = py::str(value);
        else if (py::hasattr(value, "__float__"))  // floats, numpy scalars: the shortest repr
            text = py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
        else
            throw py::type_error("parameter " + std::string(py::str(key)) +
                                 ": expected a number, a name or a bool");
        out.emplace_back(py::str(key), text);
    }
    return out;
}

struct PyRender {
    so::RenderResult result;  // its image moved out into `images`
    py::dict images;
    std::vector<std::string> lights;
};

void bindRender(py::module_& m) {
    py::class_<PyRender>(m, "Render", "A technique's render (render()).")
        .def_property_readonly("images", [](const PyRender& r) { return r.images; })
        .def_property_readonly(
            "V", [](const PyRender& r) { return lightPlanes(r.images, r.lights, "V"); })
        .def_property_readonly(
            "frame_ms", [](const PyRender& r) { return r.result.frameMs; },
            "Median over the timed frames (llvmpipe's, where that is the GL).")
        .def_property_readonly(
            "stats", [](const PyRender& r) { return jsonLoads(r.result.statsJson); },
            "raster.json as a dict.");
    m.def(
        "render",
        [](const so::Scene& scene, const std::string& technique, int width, int height, int frames,
           int warmup, int converge, const py::kwargs& kwargs) {
            so::RenderOptions o{width, height, frames, warmup, converge};
            const so::Parameters parameters = parametersFrom(kwargs);
            PyRender out;
            out.result = interruptible<so::RenderResult>(
                [&](const so::ProgressCallback&) {
                    return so::render(scene, technique, parameters, o);
                },
                py::none());
            out.lights = lightNames(scene);
            out.images = imageDict(std::move(out.result.image));
            return out;
        },
        py::arg("scene"), py::arg("technique"), py::kw_only(), py::arg("width") = 0,
        py::arg("height") = 0, py::arg("frames") = so::RenderOptions{}.frames,
        py::arg("warmup") = so::RenderOptions{}.warmup,
        py::arg("converge") = so::RenderOptions{}.converge,
        "A built-in technique through the GL path, its parameters as keywords by the names of "
        "docs/techniques.md: render(scene, \"pcf\", kernel=5, pattern=\"poisson\").");
    m.def(
        "write_render_output",
        [](const so::Scene& scene, const PyRender& render, const std::string& outDir,
           bool previews) {
            py::gil_scoped_release release;
            return so::writeRenderOutput(scene, render.result, outDir, previews);
        },
        py::arg("scene"), py::arg("render"), py::arg("out_dir"), py::kw_only(),
        py::arg("previews") = true,
        "`shadow-oracle raster`'s folder from a render() result: raster.exr, raster.json and a "
        "NAME.png preview per light. Returns the paths written.");
    m.def(
        "techniques", [] { return jsonLoads(so::techniquesJson()); },
        "Every technique, its family and its parameter table (techniques --json).");
    m.def(
        "trace_options", [] { return jsonLoads(so::traceOptionsJson()); },
        "Every trace option: its keyword, type, default, range and the surfaces that take it "
        "(trace-options --json).");
}

// images: {label: array (one light) or {light name: array}}.
std::vector<so::ExternalImage> imagesFrom(const py::dict& images, const so::Scene& scene, int width,
                                          int height) {
    std::vector<so::ExternalImage> out;
    const std::vector<std::string> lights = lightNames(scene);
    for (const auto& [key, value] : images) {
        so::ExternalImage image;
        image.label = py::str(key);
        const std::string what = "image " + image.label;
        if (py::isinstance<py::dict>(value)) {
            const py::dict planes = value.cast<py::dict>();
            for (const std::string& light : lights) {
                if (!planes.contains(light))
                    throw py::value_error(what + ": no plane for light " + light);
                image.visibility.push_back(
                    planeFrom(planes[py::str(light)], what + "[" + light + "]", width, height));
            }
        } else {
            if (lights.size() != 1)
                throw py::value_error(what + ": the scene has " + std::to_string(lights.size()) +
                                      " lights: give {light name: array}");
            image.visibility.push_back(planeFrom(value, what, width, height));
        }
        out.push_back(std::move(image));
    }
    return out;
}

void bindCompare(py::module_& m) {
    m.def(
        "compare",
        [](const so::Scene& scene, const PyTrace& oracle, const py::object& images,
           const std::vector<std::string>& techniques, int boundaryRadius, int frames, int warmup,
           const py::object& progress, const std::optional<std::string>& outDir, bool report) {
            so::CompareOptions o;
            o.techniques = techniques;
            if (!images.is_none())
                o.images = imagesFrom(images.cast<py::dict>(), scene, oracle.width, oracle.height);
            o.boundaryRadius = boundaryRadius;
            o.frames = frames;
            o.warmup = warmup;
            const so::CompareResult r = interruptible<so::CompareResult>(
                [&](const so::ProgressCallback& cb) {
                    so::CompareOptions withProgress = o;
                    withProgress.progress = cb;
                    return so::compare(scene, oracle.result, withProgress);
                },
                progress);
            if (outDir) {
                py::gil_scoped_release release;
                so::writeCompareOutput(scene, oracle.result, r, *outDir, report);
            }
            return jsonLoads(r.metricsJson);
        },
        py::arg("scene"), py::arg("oracle"), py::arg("images") = py::none(), py::kw_only(),
        py::arg("techniques") = std::vector<std::string>{},
        py::arg("boundary_radius") = so::CompareOptions{}.boundaryRadius,
        py::arg("frames") = so::CompareOptions{}.frames,
        py::arg("warmup") = so::CompareOptions{}.warmup, py::arg("progress") = py::none(),
        py::arg("out_dir") = py::none(), py::arg("report") = true,
        "Judges renderers' images ({label: V array, or {light: V array}}) and built-in techniques "
        "(\"pcf:kernel=5\") against the oracle; returns metrics.json as a dict. With out_dir, "
        "also writes `shadow-oracle compare`'s folder there (metrics.json, the CSVs, a folder and "
        "an error EXR per row, and with report, report.html and oracle.exr).");
}

}  // namespace

PYBIND11_MODULE(_shadow_oracle, m) {
    m.doc() = "shadow-oracle: ground-truth shadows and the techniques graded against them.";
    m.attr("__version__") = so::version();
    m.attr("API_VERSION") = so::kApiVersion;
    static py::exception<so::Error> error(m, "Error", PyExc_ValueError);
    static py::exception<so::Cancelled> cancelled(m, "Cancelled", error.ptr());
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const so::Cancelled& e) {
            PyErr_SetString(cancelled.ptr(), e.what());
        } catch (const so::Error& e) {
            PyErr_SetString(error.ptr(), e.what());
        }
    });
    bindImages(m);
    bindScene(m);
    bindTrace(m);
    bindRender(m);
    bindCompare(m);
}
