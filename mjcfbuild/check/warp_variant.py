"""The training variant proven in MuJoCo Warp, against the full model.

Both scenes are loaded in MuJoCo Warp (on the CPU unless told otherwise) and a batch of worlds
is stepped from home with noise on ``ctrl``: the state must stay finite. The figures a training
user chooses by - collision geoms, the geom pairs Warp's collision pass checks, and steps per
second of the batch - are measured for both. Then the variant must do what the full model is
built to do: a floating robot that can stand holds home's ``ctrl`` for 5 s without tilting or
sinking past the check's limits, a fixed robot holds home for 1 s within the hold tolerance.
"""

from __future__ import annotations

import contextlib
import os
import sys
import time
from collections.abc import Iterator
from dataclasses import dataclass, field

from mjcfbuild.check.warp import load_warp
from mjcfbuild.errors import CheckError
from mjcfbuild.mjstopped import SimulationStopped, simulating


@dataclass(frozen=True)
class WarpFigures:
    """One scene in MuJoCo Warp: its size, and its throughput on a batch."""

    collision_geoms: int
    contact_pairs: int  # geom pairs Warp's collision pass checks (after filtering)
    worlds: int
    steps: int
    seconds: float
    finite: bool
    nconmax: int = 0  # contacts allocated per world (Warp's put_data)
    njmax: int = 0  # constraint rows allocated per world

    @property
    def steps_per_second(self) -> float:
        """World-steps per second of wall time."""
        return self.worlds * self.steps / self.seconds if self.seconds > 0 else 0.0

    def to_dict(self) -> dict:
        """A JSON-friendly form."""
        return {**self.__dict__, "steps_per_second": self.steps_per_second}


@dataclass
class VariantProof:
    """The variant against the full model in MuJoCo Warp."""

    full: WarpFigures
    variant: WarpFigures
    behaviour: str  # what the variant did at home, in words
    failures: list[str] = field(default_factory=list)

    @property
    def passes(self) -> bool:
        """Whether the variant ran finite and did what the full model does."""
        return not self.failures

    def lines(self, device: str = "cpu") -> list[str]:
        """The report's lines."""
        rows = [
            f"  training variant in MuJoCo Warp ({device}, {self.variant.worlds} worlds, "
            f"{self.variant.steps} steps with noise on ctrl):",
            f"    {'':8} {'collision geoms':>16} {'contact pairs':>14} {'steps/s':>10}",
        ]
        for name, figures in (("full", self.full), ("variant", self.variant)):
            rows.append(
                f"    {name:8} {figures.collision_geoms:>16} {figures.contact_pairs:>14} "
                f"{figures.steps_per_second:>10.0f}"
            )
        rows.append(f"    {self.behaviour}")
        return rows


GPU_WORLDS = 4096  # a GPU is measured at a training batch: 64 worlds would leave it idle


def gpu_device() -> tuple[str, str] | None:
    """MuJoCo Warp's first CUDA device and its name where this machine has one, else None."""
    _, wp = load_warp()
    if not wp.is_cuda_available():
        return None
    return "cuda:0", str(wp.get_device("cuda:0").name)


@contextlib.contextmanager
def quiet_stdout() -> Iterator[None]:
    """Standard output (the file descriptor) sent nowhere: MuJoCo Warp's kernels print a line
    per world whenever a step stops at the solver's iteration cap, which the variant's bound
    makes routine, and printing them would be what is timed."""
    import ctypes

    sys.stdout.flush()
    libc = ctypes.CDLL(None)
    saved = os.dup(1)
    with open(os.devnull, "wb") as null:
        os.dup2(null.fileno(), 1)
        try:
            yield
        finally:
            libc.fflush(None)
            os.dup2(saved, 1)
            os.close(saved)


def collision_geoms(model) -> int:
    """Geoms that take part in contacts: by contype/conaffinity or an explicit pair."""
    import numpy as np

    masks = (model.geom_contype != 0) | (model.geom_conaffinity != 0)
    paired = np.zeros(model.ngeom, dtype=bool)
    paired[model.pair_geom1] = True
    paired[model.pair_geom2] = True
    return int(np.count_nonzero(masks | paired))


def measure(
    scene_path: str, worlds: int = 64, steps: int = 100, noise: float = 0.1, device: str = "cpu"
) -> WarpFigures:
    """Step ``worlds`` copies of the scene from home for ``steps`` steps, each world's ctrl
    home's plus uniform noise of ``noise`` times the half range, and time the steps (after
    one step that compiles or loads Warp's kernels)."""
    import mujoco
    import numpy as np

    mjw, wp = load_warp()
    model = mujoco.MjModel.from_xml_path(scene_path)
    try:
        with simulating(f"{steps + 1} steps of each world on MuJoCo's CPU (Warp's sizes)"):
            data = _home(model)
            ctrl = noisy_ctrl(model, data, worlds, noise)
            nconmax, njmax = sizes(model, data, ctrl, steps + 1)
    except SimulationStopped as stop:
        raise CheckError(stop.line, file=scene_path) from None
    with wp.ScopedDevice(device):
        try:
            warp_model = mjw.put_model(model)
        except Exception as exc:  # Warp names the unsupported feature
            raise CheckError(
                f"MuJoCo Warp refuses the model: {str(exc).strip().splitlines()[0]}",
                file=scene_path,
            ) from None
        warp_data = mjw.put_data(model, data, nworld=worlds, nconmax=nconmax, njmax=njmax)
        if model.nu:
            warp_data.ctrl.assign(wp.array(ctrl.astype(np.float32), dtype=float))
        with quiet_stdout():
            mjw.step(warp_model, warp_data)
            wp.synchronize()
            started = time.perf_counter()
            for _ in range(steps):
                mjw.step(warp_model, warp_data)
            wp.synchronize()
            seconds = time.perf_counter() - started
        qpos = warp_data.qpos.numpy()
        pairs = int(warp_model.nxn_geom_pair_filtered.shape[0])
    finite = bool(np.all(np.isfinite(qpos)))
    return WarpFigures(
        collision_geoms(model), pairs, worlds, steps, seconds, finite, nconmax, njmax
    )


def noisy_ctrl(model, data, worlds: int, noise: float):
    """Each world's ctrl: home's plus uniform noise of ``noise`` times the half range
    (seeded, so every run and every model draws the same)."""
    import numpy as np

    low, high = model.actuator_ctrlrange[:, 0], model.actuator_ctrlrange[:, 1]
    limited = model.actuator_ctrllimited.astype(bool)
    half = np.where(limited, (high - low) / 2, 1.0)
    rng = np.random.default_rng(0)
    ctrl = data.ctrl + noise * half * rng.uniform(-1, 1, size=(worlds, model.nu))
    return np.where(limited, np.clip(ctrl, low, high), ctrl)


SIZING_WORLDS = 4  # worlds rolled out in MuJoCo (C) to size Warp's contact and row buffers
SIZING_MARGIN = 2  # buffers this many times the most seen


def sizes(model, data, ctrl, steps: int) -> tuple[int, int]:
    """Contacts and constraint rows to allocate per world in Warp: twice the most that
    the first SIZING_WORLDS worlds reach in MuJoCo (C) over the same steps with the same
    ctrl, and at least 8 contacts and 16 rows. Warp launches its contact and solver
    kernels over the whole allocation (its defaults, 48 contacts and 64 rows for these
    robots, are sized for any model), so every scene measured is sized by this one rule:
    the figures compare the models, not the allocations."""
    import mujoco

    most_contacts, most_rows = data.ncon, data.nefc
    for world in range(min(SIZING_WORLDS, len(ctrl))):
        rollout = mujoco.MjData(model)
        rollout.qpos[:], rollout.qvel[:], rollout.act[:] = data.qpos, data.qvel, data.act
        rollout.mocap_pos[:], rollout.mocap_quat[:] = data.mocap_pos, data.mocap_quat
        rollout.ctrl[:] = ctrl[world]
        for _ in range(steps):
            mujoco.mj_step(model, rollout)
            most_contacts = max(most_contacts, rollout.ncon)
            most_rows = max(most_rows, rollout.nefc)
    return max(8, SIZING_MARGIN * most_contacts), max(16, SIZING_MARGIN * most_rows)


def _home(model):
    import mujoco

    data = mujoco.MjData(model)
    key = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_KEY, "home")
    if key >= 0:
        mujoco.mj_resetDataKeyframe(model, data, key)
    mujoco.mj_forward(model, data)
    return data


def behaviour(scene_path: str, hold_tolerance: float, device: str = "cpu") -> tuple[str, str]:
    """What the scene's robot does in MuJoCo Warp holding home's ctrl from home: (a line for
    the report, a failure or '')."""
    import math

    import mujoco
    import numpy as np

    from mjcfbuild.check.control import TEST_SECONDS
    from mjcfbuild.control.stand_test import STAND_SECONDS, STAND_SINK, STAND_TILT
    from mjcfbuild.control.standing import stance

    mjw, wp = load_warp()
    model = mujoco.MjModel.from_xml_path(scene_path)
    data = _home(model)
    roots = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
    floating = bool(roots)
    if floating and not stance(model, data).can_stand:
        return f"stands only under a controller: {stance(model, data).why_not()}", ""
    seconds = STAND_SECONDS if floating else TEST_SECONDS
    hinges = [
        model.jnt_qposadr[j]
        for j in range(model.njnt)
        if int(model.jnt_type[j])
        in (int(mujoco.mjtJoint.mjJNT_HINGE), int(mujoco.mjtJoint.mjJNT_SLIDE))
    ]
    home = data.qpos.copy()
    steps = round(seconds / model.opt.timestep)
    every = max(1, round(0.02 / model.opt.timestep))  # look every 20 ms of simulated time
    tilt = sink = worst = 0.0
    root = model.jnt_bodyid[roots[0]] if floating else 0
    height = float(data.xpos[root][2])
    with wp.ScopedDevice(device), quiet_stdout():
        warp_model = mjw.put_model(model)
        warp_data = mjw.put_data(model, data, nworld=1)
        for step in range(1, steps + 1):
            mjw.step(warp_model, warp_data)
            if step % every and step != steps:
                continue
            qpos = warp_data.qpos.numpy()[0]
            if not np.all(np.isfinite(qpos)):
                return "the state became not finite", "the state became not finite at home"
            if hinges:
                worst = max(worst, float(np.max(np.abs(qpos[hinges] - home[hinges]))))
            if floating:
                address = model.jnt_qposadr[roots[0]]
                quat = qpos[address + 3 : address + 7]
                up = 1 - 2 * (quat[1] ** 2 + quat[2] ** 2) / float(np.dot(quat, quat))
                tilt = max(tilt, math.acos(max(-1.0, min(1.0, up))))
                sink = max(sink, height - float(qpos[address + 2]))
    if floating:
        line = (
            f"stands at home for {seconds:g} s: base tilted {tilt:.3f} rad, sank "
            f"{sink * 1000:.1f} mm, joints within {worst:.3g} of home"
        )
        fails = tilt > STAND_TILT or sink > STAND_SINK * max(height, 0.0) + 0.01
        return line, (f"the training variant does not stand: {line}" if fails else "")
    line = f"holds home for {seconds:g} s: joints within {worst:.3g} of home"
    fails = worst > hold_tolerance
    return line, (f"the training variant does not hold home: {line}" if fails else "")


def prove_variant(
    full_scene: str,
    variant_scene: str,
    hold_tolerance: float,
    worlds: int = 64,
    steps: int = 100,
    device: str = "cpu",
) -> VariantProof:
    """The variant against the full model: both measured, the variant's behaviour checked."""
    full = measure(full_scene, worlds, steps, device=device)
    variant = measure(variant_scene, worlds, steps, device=device)
    line, failure = behaviour(variant_scene, hold_tolerance, device)
    proof = VariantProof(full, variant, line)
    if not variant.finite:
        proof.failures.append(
            f"the training variant's state is not finite after {steps} steps of {worlds} "
            "worlds with noise on ctrl"
        )
    if failure:
        proof.failures.append(failure)
    return proof


def prove_on_gpu(
    full_scene: str,
    variant_scene: str,
    hold_tolerance: float,
    device: str,
    name: str,
    worlds: int = GPU_WORLDS,
) -> tuple[dict, list[str]]:
    """The variant proven on a GPU as on the CPU: the record ``check --warp`` keeps and the
    failures, each naming the GPU. An error there (out of memory, the driver) is a failure
    too, so the CPU's result is never lost to it."""
    try:
        proof = prove_variant(full_scene, variant_scene, hold_tolerance, worlds, device=device)
    except Exception as exc:  # whatever the device raises, said in one line
        detail = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        failure = f"MuJoCo Warp failed on {name}: {detail}"
        return {"device": name, "error": failure, "failures": [failure]}, [failure]
    print("\n".join(proof.lines(f"{device}, {name}")))
    record = {
        "device": name,
        "full": proof.full.to_dict(),
        "variant": proof.variant.to_dict(),
        "behaviour": proof.behaviour,
        "failures": proof.failures,
    }
    return record, [f"on {name}: {failure}" for failure in proof.failures]
