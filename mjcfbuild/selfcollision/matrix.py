"""The collision matrix, computed the way MoveIt's Setup Assistant does it.

Every pair of bodies that both have collision geometry gets a verdict: ``adjacent`` (joined by
one joint, counting links welded together as one), ``home`` (touching at the home pose),
``always`` (touching in at least 95% of seeded random configurations), ``never`` (touching in
none of them), or ``sometimes``. The first three are excluded by default; ``never`` on request;
pairs from an SRDF are excluded with the SRDF's reason; ``keep`` pairs are never excluded.
"""

from __future__ import annotations

from dataclasses import dataclass

EXCLUDED_BY_DEFAULT = ("adjacent", "home", "always")
# MoveIt's Setup Assistant calls a pair "always in collision" from this fraction of samples on.
ALWAYS_FRACTION = 0.95


@dataclass(frozen=True)
class PairVerdict:
    """One body pair: why it is (or is not) excluded, and how often it touched in samples."""

    body1: str
    body2: str
    reason: str
    fraction: float
    exclude: bool

    def to_dict(self) -> dict:
        """A JSON-friendly form (by hand: ``asdict`` took a fifth of g1's matrix step)."""
        return {
            "body1": self.body1,
            "body2": self.body2,
            "reason": self.reason,
            "fraction": self.fraction,
            "exclude": self.exclude,
        }


@dataclass(frozen=True)
class MatrixSettings:
    """How the matrix is sampled and which verdicts become excludes."""

    samples: int = 1000
    seed: int = 0
    exclude_never: bool = False


def collision_matrix(model, home_qpos, settings: MatrixSettings) -> list[PairVerdict]:
    """A verdict for every pair of colliding bodies of ``model`` (no floor in it)."""
    import mujoco
    import numpy as np

    colliding = sorted(
        {
            int(model.geom_bodyid[g])
            for g in range(model.ngeom)
            if model.geom_contype[g] or model.geom_conaffinity[g]
        }
    )
    if len(colliding) < 2:
        return []
    # Every collision geom meets every other; only excludes already in the model stay.
    model.geom_contype[:] = np.where(model.geom_contype | model.geom_conaffinity, 1, 0)
    model.geom_conaffinity[:] = model.geom_contype
    adjacent = _adjacent_pairs(model)
    data = mujoco.MjData(model)
    at_home = _touching(model, data, home_qpos)
    counts: dict[tuple[int, int], int] = {}
    rng = np.random.default_rng(settings.seed)
    for qpos in _samples(model, rng, settings.samples):
        for pair in _touching(model, data, qpos):
            counts[pair] = counts.get(pair, 0) + 1

    def name(body: int) -> str:
        return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, body) or "world"

    verdicts = []
    for index, first in enumerate(colliding):
        for second in colliding[index + 1 :]:
            pair = (first, second)
            fraction = counts.get(pair, 0) / settings.samples
            if pair in adjacent:
                reason = "adjacent"
            elif pair in at_home:
                reason = "home"
            elif fraction >= ALWAYS_FRACTION:
                reason = "always"
            elif fraction == 0:
                reason = "never"
            else:
                reason = "sometimes"
            exclude = reason in EXCLUDED_BY_DEFAULT or (
                reason == "never" and settings.exclude_never
            )
            verdicts.append(PairVerdict(name(first), name(second), reason, fraction, exclude))
    return verdicts


def needs_exclude(model, verdict: PairVerdict) -> bool:
    """Whether MuJoCo's own filter leaves this pair to a ``<contact><exclude>``.

    MuJoCo never collides bodies welded together, nor a body with its parent's weld group,
    unless one of them is welded to the world (a fixed base's root is).
    """
    import mujoco

    ids = [
        mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, b)
        for b in (verdict.body1, verdict.body2)
    ]
    if min(ids) < 0:
        return True
    weld1, weld2 = (int(model.body_weldid[b]) for b in ids)
    if weld1 == weld2:
        return False
    parent1 = int(model.body_weldid[model.body_parentid[weld1]])
    parent2 = int(model.body_weldid[model.body_parentid[weld2]])
    return not (weld1 and weld2 and (weld1 == parent2 or weld2 == parent1))


def _adjacent_pairs(model) -> set[tuple[int, int]]:
    """Body pairs in the same welded group, or in groups one (non-free) joint apart."""
    import mujoco

    weld = [int(w) for w in model.body_weldid]
    groups: dict[int, list[int]] = {}
    for body in range(model.nbody):
        groups.setdefault(weld[body], []).append(body)
    linked = set()
    for root in groups:
        if root == 0:
            continue
        free = any(
            model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE
            for j in range(
                model.body_jntadr[root], model.body_jntadr[root] + model.body_jntnum[root]
            )
        )
        if not free:
            linked.add((weld[model.body_parentid[root]], root))
    pairs = set()
    for members in groups.values():
        for a in members:
            for b in members:
                if a < b:
                    pairs.add((a, b))
    for parent_group, child_group in linked:
        for a in groups[parent_group]:
            for b in groups[child_group]:
                pairs.add((min(a, b), max(a, b)))
    return pairs


def _touching(model, data, qpos) -> set[tuple[int, int]]:
    """The body pairs in contact (or overlapping) at ``qpos``."""
    import mujoco
    import numpy as np

    data.qpos[:] = qpos
    mujoco.mj_kinematics(model, data)
    mujoco.mj_collision(model, data)
    if not data.ncon:
        return set()
    contacts = data.contact
    touching = ~(contacts.dist > 0)
    first = model.geom_bodyid[contacts.geom1[touching]]
    second = model.geom_bodyid[contacts.geom2[touching]]
    apart = first != second
    low = np.minimum(first, second)[apart].tolist()
    high = np.maximum(first, second)[apart].tolist()
    return set(zip(low, high, strict=True))


def _samples(model, rng, count: int):
    """``count`` random configurations (rows): limited joints uniform in range, unlimited
    hinges in +-pi, mimic followers where their equality puts them, everything else at
    qpos0. The numbers are drawn row by row, joint by joint, as one draw per joint would."""
    import mujoco
    import numpy as np

    addresses, lows, highs = [], [], []
    for joint in range(model.njnt):
        kind = mujoco.mjtJoint(model.jnt_type[joint])
        if kind not in (mujoco.mjtJoint.mjJNT_HINGE, mujoco.mjtJoint.mjJNT_SLIDE):
            continue
        if model.jnt_limited[joint]:
            low, high = model.jnt_range[joint]
        elif kind == mujoco.mjtJoint.mjJNT_HINGE:
            low, high = -np.pi, np.pi
        else:
            continue
        addresses.append(model.jnt_qposadr[joint])
        lows.append(low)
        highs.append(high)
    qpos = np.tile(model.qpos0, (count, 1))
    if addresses:
        qpos[:, addresses] = rng.uniform(lows, highs, size=(count, len(addresses)))
    for equality in range(model.neq):
        if model.eq_type[equality] != mujoco.mjtEq.mjEQ_JOINT or model.eq_obj2id[equality] < 0:
            continue
        follower = model.jnt_qposadr[model.eq_obj1id[equality]]
        leader = model.jnt_qposadr[model.eq_obj2id[equality]]
        coefficients = model.eq_data[equality]
        qpos[:, follower] = coefficients[0] + coefficients[1] * qpos[:, leader]
    return qpos
