"""The processed ``mujoco_inputs``: one typed model per tag, from manifest to model.

Each class is the whole of one tag: its fields (validated once, by pydantic, whether they come
from robot.yaml's ``mujoco_inputs`` or a ``<processed_inputs>`` element; robot.yaml's schema is
generated from them), how the reference converter's XML names them, how two places giving the
same item combine, and how the item is applied to the model tree. :data:`PROCESSED_INPUTS` is
the registry every reader and writer goes through; a new tag is a class here, its entry there,
and its list in ``manifest.models.MujocoInputs``.

Where an item was given (``inputs.xml:12``, ``robot.yaml mujoco_inputs.cameras[0]``) travels
with it as :attr:`ProcessedInput.origin`, outside the fields, so it is in no schema.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar, Self

from pydantic import BaseModel, ConfigDict, Field, PrivateAttr, ValidationError, model_validator
from pydantic_core import PydanticCustomError

from mjcfbuild.errors import InputError

if TYPE_CHECKING:
    from mjcfbuild.inputs.apply import ModelTarget

# A MuJoCo attribute's value as robot.yaml can write it; applied as MJCF text (see mjcf_text).
Attribute = str | float | int | bool


# A key a model validator found missing (one that only some items need), by its written name.
MISSING_KEY = "missing_key"


def _missing_key(why: str, key: str) -> PydanticCustomError:
    return PydanticCustomError(
        MISSING_KEY, "{why}, and '{key}' is missing", {"why": why, "key": key}
    )


def mjcf_text(value: object) -> str:
    """A value as MJCF attribute text: booleans as true/false, sequences space-separated."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return " ".join(mjcf_text(v) for v in value)
    return str(value)


class ProcessedInput(BaseModel):
    """One item of ``processed_inputs`` (the base of every tag's model)."""

    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)

    xml_tag: ClassVar[str]  # the reference converter's element
    manifest_key: ClassVar[str]  # its list in robot.yaml's mujoco_inputs
    # XML attribute -> field, for the attributes the XML form names differently or at all.
    xml_fields: ClassVar[dict[str, str]]
    # Whether the element's other attributes are MuJoCo attributes (else they are refused).
    xml_attributes: ClassVar[bool] = False
    _origin: str = PrivateAttr("")

    @property
    def origin(self) -> str:
        """Where the item was given, for messages: ``file:line`` or a robot.yaml key path."""
        return self._origin

    def given_at(self, origin: str) -> Self:
        """This item, given at ``origin``."""
        copy = self.model_copy()
        copy._origin = origin
        return copy

    def identity(self) -> str:
        """What makes two items of this tag 'the same thing' when inputs are combined."""
        raise NotImplementedError

    def describe(self) -> str:
        """How the item is named in messages."""
        return f"{self.xml_tag} '{self.identity()}'"

    @classmethod
    def combine(cls, items: list[Self], warnings: list[str]) -> list[Self]:
        """Items given lowest precedence first, as one list: the last of each identity wins
        and every clash is a warning naming both places."""
        chosen: dict[str, Self] = {}
        for item in items:
            name = item.identity()
            if name in chosen:
                warnings.append(
                    f"{item.describe()} given in {chosen[name].origin} and {item.origin}; "
                    f"using the one in {item.origin}"
                )
            chosen[name] = item
        return list(chosen.values())

    def apply(self, target: ModelTarget) -> None:
        """Apply the item to the model tree (nothing, for a tag that acts elsewhere)."""

    @classmethod
    def from_xml(cls, element: Any, label: str) -> Self:
        """The item an lxml element of :attr:`xml_tag` gives; defects are errors at its line."""
        values: dict[str, object] = {}
        extra: dict[str, str] = {}
        for key, value in element.attrib.items():
            if key in cls.xml_fields:
                values[cls.xml_fields[key]] = value.strip()
            elif cls.xml_attributes:
                extra[str(key)] = str(value)
            else:
                raise InputError(
                    cls._unknown_attribute(str(key)),
                    file=label,
                    line=element.sourceline,
                    hint=f"known attributes: {', '.join(sorted(cls.xml_fields))}",
                )
        values = cls.xml_values(values)
        if cls.xml_attributes:
            values["attributes"] = extra
        try:
            item = cls.model_validate(values)
        except ValidationError as error:
            raise InputError(cls._xml_message(error), file=label, line=element.sourceline) from None
        origin = f"{label}:{element.sourceline}" if element.sourceline else label
        return item.given_at(origin)

    @classmethod
    def _unknown_attribute(cls, name: str) -> str:
        """The error for an attribute the tag does not have, with the closest it has (its
        robot.yaml key counts: ``mesh`` for ``mesh_name``)."""
        from mjcfbuild.sources.packages import did_you_mean

        attributes = {field: attribute for attribute, field in cls.xml_fields.items()}
        alias = attributes.get(name)
        guess = f"; did you mean '{alias}'?" if alias else did_you_mean(name, set(cls.xml_fields))
        return f"<{cls.xml_tag}> has no attribute '{name}'{guess}"

    @classmethod
    def key_aliases(cls) -> dict[str, str]:
        """The XML form's names of the fields it names otherwise (``ref_site``: ``link``),
        so that robot.yaml's errors can point from one to the other."""
        return {
            attribute: field for attribute, field in cls.xml_fields.items() if attribute != field
        }

    @classmethod
    def xml_values(cls, values: dict[str, object]) -> dict[str, object]:
        """The field values read from XML, adjusted where the XML form means something else."""
        return values

    @classmethod
    def _xml_message(cls, error: ValidationError) -> str:
        from mjcfbuild.schema_errors import describe_error

        first = error.errors()[0]
        names = {field: attribute for attribute, field in cls.xml_fields.items()}
        field = str(first["loc"][0]) if first["loc"] else ""
        if first["type"] == "missing":
            return f"<{cls.xml_tag}> needs a '{names.get(field, field)}' attribute"
        if first["type"] == MISSING_KEY:
            return f"<{cls.xml_tag}> needs a '{first.get('ctx', {})['key']}' attribute"
        if field == "attributes":
            return f"<{cls.xml_tag}> sets no attribute"
        if field:
            return f"<{cls.xml_tag}> {names.get(field, field)}: {describe_error(first, None)}"
        return f"<{cls.xml_tag}>: {describe_error(first, None)}"

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready form: the tag, the fields and the origin."""
        return {"tag": self.xml_tag, **self.model_dump(mode="json"), "origin": self.origin}


class CameraInput(ProcessedInput):
    """A camera at a link, which is a ROS optical frame (+z forward, +y down)."""

    xml_tag = "camera"
    manifest_key = "cameras"
    xml_fields = {"name": "name", "site": "link"}
    # fovy, mode and resolution of the XML form stay MuJoCo attributes, applied as written.
    xml_attributes = True

    name: str = Field(min_length=1)
    link: str = Field(min_length=1, description="The link (or site) the camera sits at.")
    fovy: float | None = Field(None, gt=0, lt=180, description="Vertical field of view (degrees).")
    mode: str | None = Field(None, description="MuJoCo camera mode, for example 'fixed'.")
    resolution: tuple[int, int] | None = Field(None, description="Width and height in pixels.")
    attributes: dict[str, Attribute] = Field(
        default_factory=dict, description="Any other MuJoCo camera attribute."
    )

    def identity(self) -> str:
        """Cameras are the same when their names are."""
        return self.name

    def mjcf_attributes(self) -> dict[str, str]:
        """The camera's MuJoCo attributes as text, the typed fields over ``attributes``."""
        result = {key: mjcf_text(value) for key, value in self.attributes.items()}
        for key in ("fovy", "mode", "resolution"):
            value = getattr(self, key)
            if value is not None:
                result[key] = mjcf_text(value)
        return result

    def apply(self, target: ModelTarget) -> None:
        """A ``<camera>`` at the link, turned from the optical frame to MuJoCo's."""
        target.add_camera(self.name, self.link, self.mjcf_attributes(), self.origin)


class LidarInput(ProcessedInput):
    """A planar lidar: rangefinders from min_angle to max_angle about the link's +z axis."""

    xml_tag = "lidar"
    manifest_key = "lidars"
    xml_fields = {
        "sensor_name": "sensor_name",
        "ref_site": "link",
        "min_angle": "min_angle",
        "max_angle": "max_angle",
        "angle_increment": "angle_increment",
    }

    sensor_name: str = Field(
        min_length=1, description="Name of the rangefinder sites (<name>-00, <name>-01, ...)."
    )
    link: str = Field(min_length=1, description="The lidar frame: +z up, first ray along +x.")
    min_angle: float = Field(allow_inf_nan=False)
    max_angle: float = Field(allow_inf_nan=False)
    angle_increment: float = Field(gt=0, allow_inf_nan=False)

    @model_validator(mode="after")
    def _ordered(self) -> LidarInput:
        if self.max_angle < self.min_angle:
            raise ValueError("max_angle is below min_angle")
        from mjcfbuild.inputs.frames import ray_count

        rays = ray_count(self.min_angle, self.max_angle, self.angle_increment)
        if rays > MOST_RAYS:
            raise ValueError(
                f"{rays} rays from min_angle to max_angle by angle_increment; at most "
                f"{MOST_RAYS} (a real planar lidar has a few thousand)"
            )
        return self

    def identity(self) -> str:
        """Lidars are the same when their sensor names are."""
        return self.sensor_name

    def apply(self, target: ModelTarget) -> None:
        """A body at the link holding a ``<replicate>`` of rangefinder sites, one per ray."""
        target.add_lidar(
            self.sensor_name,
            self.link,
            (self.min_angle, self.max_angle, self.angle_increment),
            self.origin,
        )


# Each ray is a rangefinder site the model carries and casts at every step.
MOST_RAYS = 20_000


class DecomposeInput(ProcessedInput):
    """Decompose a mesh with CoACD (the reference converter's decompose_mesh)."""

    xml_tag = "decompose_mesh"
    manifest_key = "decompose"
    xml_fields = {"mesh_name": "mesh", "threshold": "threshold"}

    mesh: str = Field(min_length=1, description="Mesh file name, stem or mjcfbuild mesh name.")
    threshold: float = Field(0.05, gt=0, le=1)

    def identity(self) -> str:
        """Decompositions are the same when their meshes are."""
        return self.mesh

    # Not applied to the model tree: it becomes a collision rule (collision.settings).


class ModifyInput(ProcessedInput):
    """Attributes to set on a generated element: by type and name, or a geom by mesh and class."""

    model_config = ConfigDict(extra="forbid", frozen=True, populate_by_name=True)

    xml_tag = "modify_element"
    manifest_key = "modify"
    xml_fields = {"type": "type", "name": "name", "mesh": "mesh", "class": "geom_class"}
    xml_attributes = True

    type: str = Field(pattern=r"^[a-z_]+$", description="MJCF element: joint, body, geom, ...")
    name: str | None = None
    mesh: str | None = Field(None, description="For geoms: the mesh (name or file stem).")
    geom_class: str | None = Field(None, alias="class", description="For geoms: the class.")
    attributes: dict[str, Attribute] = Field(min_length=1)

    @model_validator(mode="after")
    def _target(self) -> ModifyInput:
        if self.type == "geom" and not (self.mesh and self.geom_class):
            raise _missing_key(
                "a geom is found by 'mesh' and 'class'", "class" if self.mesh else "mesh"
            )
        if self.type != "geom" and not self.name:
            raise _missing_key(f"a {self.type} is found by 'name'", "name")
        return self

    @classmethod
    def xml_values(cls, values: dict[str, object]) -> dict[str, object]:
        """The XML form names a geom by mesh and class only, anything else by name only."""
        if values.get("type") == "geom":
            ignored: tuple[str, ...] = ("name",)
        else:
            ignored = ("mesh", "geom_class")
        return {key: value for key, value in values.items() if key not in ignored}

    def identity(self) -> str:
        """The element modified (attributes are combined one by one, see :meth:`combine`)."""
        return self.describe()

    def describe(self) -> str:
        """How the target is named in messages."""
        if self.type == "geom":
            return f"geom with mesh '{self.mesh}' and class '{self.geom_class}'"
        return f"{self.type} '{self.name}'"

    @classmethod
    def combine(cls, items: list[Self], warnings: list[str]) -> list[Self]:
        """Every item, applied in order so the later (higher) value wins; an attribute set in
        two places is a warning naming both."""
        seen: dict[tuple, Self] = {}
        for item in items:
            for attribute in item.attributes:
                key = (item.type, item.name, item.mesh, item.geom_class, attribute)
                if key in seen:
                    warnings.append(
                        f"{item.describe()} {attribute} set in {seen[key].origin} and "
                        f"{item.origin}; using the value from {item.origin}"
                    )
                seen[key] = item
        return items

    def apply(self, target: ModelTarget) -> None:
        """The attributes set on every element the item finds (none found is an error); a
        range they leave reversed is an error at the item's line."""
        from mjcfbuild.inputs.apply import refuse_reversed_ranges

        attributes = {key: mjcf_text(value) for key, value in self.attributes.items()}
        for element in target.modify_targets(self):
            for key, value in attributes.items():
                element.set(key, value)
            refuse_reversed_ranges(element, self.origin)


# Every processed tag, in the order inputs are combined and applied.
PROCESSED_INPUTS: tuple[type[ProcessedInput], ...] = (
    CameraInput,
    LidarInput,
    DecomposeInput,
    ModifyInput,
)


def processed_tag(tag: str) -> type[ProcessedInput] | None:
    """The model of the XML element ``tag``, None if it is no processed input."""
    return next((kind for kind in PROCESSED_INPUTS if kind.xml_tag == tag), None)


def processed_from_dict(data: dict[str, Any]) -> ProcessedInput:
    """An item from :meth:`ProcessedInput.to_dict`."""
    kind = processed_tag(data["tag"])
    if kind is None:
        raise ValueError(f"no processed input <{data['tag']}>")
    fields = {key: value for key, value in data.items() if key not in ("tag", "origin")}
    return kind.model_validate(fields).given_at(data["origin"])
