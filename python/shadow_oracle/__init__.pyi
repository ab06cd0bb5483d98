# Type stubs of the shadow_oracle module (python/module.cpp); docs/python.md.
from typing import Any, Callable, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str
API_VERSION: int

class Error(ValueError):
    """Bad input or a failure of the machinery; the message is the command line's one line."""

class Cancelled(Error):
    """A progress callback returned False."""

class Scene:
    @property
    def path(self) -> str: ...
    @property
    def hash(self) -> str: ...
    @property
    def lights(self) -> list[dict[str, Any]]: ...
    @property
    def effects(self) -> list[str]: ...
    @property
    def camera_size(self) -> Tuple[int, int]: ...
    @property
    def triangles(self) -> int: ...
    @property
    def warnings(self) -> list[str]: ...
    @property
    def frames(self) -> int: ...
    @property
    def fps(self) -> float: ...
    def at_frame(self, k: int) -> Scene: ...

class Trace:
    @property
    def images(self) -> dict[str, npt.NDArray[np.float32]]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def stats(self) -> dict[str, Any]: ...
    @property
    def disagreements(self) -> int: ...
    @property
    def V(self) -> dict[str, npt.NDArray[np.float32]]: ...
    @property
    def stderr(self) -> dict[str, npt.NDArray[np.float32]]: ...
    @property
    def spp(self) -> dict[str, npt.NDArray[np.float32]]: ...
    @property
    def P(self) -> npt.NDArray[np.float32]: ...
    @property
    def N(self) -> npt.NDArray[np.float32]: ...
    def __getitem__(self, name: str) -> npt.NDArray[np.float32]: ...

class Render:
    @property
    def images(self) -> dict[str, npt.NDArray[np.float32]]: ...
    @property
    def V(self) -> dict[str, npt.NDArray[np.float32]]: ...
    @property
    def frame_ms(self) -> float: ...
    @property
    def stats(self) -> dict[str, Any]: ...

ProgressFn = Callable[[str, int, int], Optional[bool]]
Mesh = Tuple[npt.ArrayLike, npt.ArrayLike]
ImageArg = Union[npt.NDArray[np.floating[Any]], Mapping[str, npt.NDArray[np.floating[Any]]]]

def load_scene(path: str) -> Scene: ...
def make_scene(
    meshes: Sequence[Mesh],
    lights: Sequence[Mapping[str, Any]],
    camera: Optional[Mapping[str, Any]] = None,
    effects: Optional[Sequence[str]] = None,
) -> Scene: ...
def export_scene(
    scene: Scene, out_dir: str, width: int = 0, height: int = 0, threads: int = 0
) -> str: ...
def trace(
    scene: Scene,
    *,
    # BEGIN trace-options (generated: scripts/update-docs)
    width: int = 0,
    height: int = 0,
    threads: int = 0,
    seed: int = 0,
    target_error: float = 0.01,
    agreement_target: float = 0.01,
    max_spp: int = 16384,
    spp: int = 0,
    verify: int = 0,
    penumbra: str = "auto",
    exact_pixels: str = "penumbra",
    bound_target: float = 1e-06,
    bound_max_sides: int = 4096,
    # END trace-options
    points: Optional[str] = None,
    progress: Optional[ProgressFn] = None,
) -> Trace: ...
def render(
    scene: Scene,
    technique: str,
    *,
    width: int = 0,
    height: int = 0,
    # BEGIN raster-options (generated: scripts/update-docs)
    frames: int = 9,
    warmup: int = 2,
    # END raster-options
    converge: int = 0,
    **parameters: Union[float, int, str, bool],
) -> Render: ...
def techniques() -> dict[str, Any]: ...
def trace_options() -> dict[str, Any]: ...
def compare(
    scene: Scene,
    oracle: Trace,
    images: Optional[Mapping[str, ImageArg]] = None,
    *,
    techniques: Sequence[str] = (),
    # BEGIN compare-options (generated: scripts/update-docs)
    boundary_radius: int = 2,
    # END compare-options
    # BEGIN raster-options (generated: scripts/update-docs)
    frames: int = 9,
    warmup: int = 2,
    # END raster-options
    progress: Optional[ProgressFn] = None,
    out_dir: Optional[str] = None,
    report: bool = True,
) -> dict[str, Any]: ...
def write_trace_output(
    scene: Scene, trace: Trace, out_dir: str, *, previews: bool = True
) -> list[str]: ...
def write_render_output(
    scene: Scene, render: Render, out_dir: str, *, previews: bool = True
) -> list[str]: ...
def read_exr(path: str) -> dict[str, npt.NDArray[np.float32]]: ...
def write_exr(
    path: str,
    channels: Mapping[str, npt.ArrayLike],
    attributes: Mapping[str, str] = ...,
) -> None: ...
