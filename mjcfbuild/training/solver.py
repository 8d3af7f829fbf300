"""The training variant's constraint solver settings, chosen for the device it will run on.

The device picks the solver, and the solver its iteration caps:

- **gpu** (the default: training runs thousands of worlds on GPUs): Newton with 1 iteration
  and 5 line-search iterations, the settings of MuJoCo Menagerie's ``*_mjx.xml`` variants and
  MuJoCo Playground (mjlab's velocity tasks train with Newton too). Not yet timed on a GPU
  with the variant; what moved the default there: on an NVIDIA H200 at 8192 worlds, the
  variants and mjlab's models under CG with 2 and 4 iterations ran 1.5 to 2.8 times slower
  than the full models under Newton (docs/benchmarks.md). The cause was not timed stage by
  stage.
- **cpu** (MuJoCo Warp on a CPU): CG with 2 iterations and 4 line-search iterations, measured
  fastest on a 2-core CPU at 512 worlds (go1's variant 2.2 times its full model against 1.9
  with Newton 1/5, g1's 2.4 against 1.7): CG does not factorize a Hessian at each iteration.

Either way the robot does the same at home (the variant's check stands and holds it in Warp).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class SolverSettings:
    """MuJoCo's ``<option>`` solver settings: the solver (lower case) and its iteration caps."""

    solver: str  # cg or newton
    iterations: int
    ls_iterations: int


DEVICE_SOLVER = {"gpu": "newton", "cpu": "cg"}
SOLVER_DEFAULTS = {"newton": SolverSettings("newton", 1, 5), "cg": SolverSettings("cg", 2, 4)}


def solver_settings(
    device: str,
    solver: str | None = None,
    iterations: int | None = None,
    ls_iterations: int | None = None,
) -> SolverSettings:
    """The settings for ``device``: its solver unless ``solver`` is given, that solver's
    iteration caps unless they are given."""
    default = SOLVER_DEFAULTS[solver or DEVICE_SOLVER[device]]
    return SolverSettings(
        solver=default.solver,
        iterations=iterations if iterations is not None else default.iterations,
        ls_iterations=ls_iterations if ls_iterations is not None else default.ls_iterations,
    )
