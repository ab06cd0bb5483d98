"""shadow-oracle: ground-truth shadows, and the techniques people ship graded against them.

    import shadow_oracle as so
    scene = so.load_scene("scenes/contact_box.scene.json")
    oracle = so.trace(scene, width=256, height=256)
    pcf = so.render(scene, "pcf", kernel=5, width=256, height=256)
    metrics = so.compare(scene, oracle, techniques=["pcf:kernel=5"])

Images are numpy arrays (height, width), row 0 at the top; errors raise shadow_oracle.Error
(a ValueError) with the command line's one-line message. docs/python.md has the whole story.
"""

from ._shadow_oracle import (  # noqa: F401
    API_VERSION,
    Cancelled,
    Error,
    Render,
    Scene,
    Trace,
    __version__,
    compare,
    export_scene,
    load_scene,
    make_scene,
    read_exr,
    render,
    techniques,
    trace,
    trace_options,
    write_exr,
    write_render_output,
    write_trace_output,
)

__all__ = [
    "API_VERSION",
    "Cancelled",
    "Error",
    "Render",
    "Scene",
    "Trace",
    "compare",
    "export_scene",
    "load_scene",
    "make_scene",
    "read_exr",
    "render",
    "techniques",
    "trace",
    "trace_options",
    "write_exr",
    "write_render_output",
    "write_trace_output",
]
