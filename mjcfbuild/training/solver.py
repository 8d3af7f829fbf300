"""The training variant's constraint solver settings, chosen for the device it will run on.

The fastest settings differ between a GPU and a CPU, measured with the same scenes
(docs/benchmarks.md, "MuJoCo Warp"):

- **gpu** (the default: training runs thousands of worlds on GPUs): Newton, 1 iteration and
  5 line-search iterations, the settings of MuJoCo Menagerie's ``*_mjx.xml`` variants and
  MuJoCo Playground. On an NVIDIA H200 at 8192 worlds, the full models with Newton ran 1.5 to
  2.8 times faster than the same robots' variants, and mjlab's models, under CG with 2
  iterations (the stages were not timed; MuJoCo Warp's CG runs a tiled kernel per world and a
  back-substitution through the mass matrix that Newton does not).
- **cpu** (MuJoCo Warp on a CPU): CG, 2 iterations and 4 line-search iterations. On a 2-core
  CPU at 512 worlds go1's variant ran 2.2 times its full model with these and 1.9 times with
  the GPU's, g1's 2.4 against 1.7: CG does not factorize a Hessian at each iteration.

Either way the robot does the same at home (the variant's check stands and holds it in Warp).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

Device = Literal["gpu", "cpu"]


@dataclass(frozen=True)
class SolverSettings:
    """MuJoCo's ``<option>`` solver settings: the solver (lower case) and its iteration caps."""

    solver: str  # cg or newton
    iterations: int
    ls_iterations: int


DEVICE_DEFAULTS: dict[str, SolverSettings] = {
    "gpu": SolverSettings("newton", 1, 5),
    "cpu": SolverSettings("cg", 2, 4),
}


def solver_settings(
    device: str,
    solver: str | None = None,
    iterations: int | None = None,
    ls_iterations: int | None = None,
) -> SolverSettings:
    """The settings for ``device``, with any the user gave in place of its defaults."""
    default = DEVICE_DEFAULTS[device]
    return SolverSettings(
        solver=solver or default.solver,
        iterations=iterations if iterations is not None else default.iterations,
        ls_iterations=ls_iterations if ls_iterations is not None else default.ls_iterations,
    )
