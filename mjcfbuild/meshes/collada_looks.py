"""A COLLADA material's look: its colour (Phong, Lambert, Blinn or constant, with the spec's
transparency), its diffuse texture file and its glow (``<emission>``).

A MuJoCo material's emission is one number, a share of its own colour added to the lit one;
COLLADA's is a colour, which RViz adds as Ogre's self-illumination. The share that comes
closest to the colour is used, and a glow it cannot show (another hue, a texture) is noted.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from urllib.parse import unquote

from lxml import etree

from mjcfbuild.meshes.collada_xml import Reader, floats

RGBA = tuple[float, float, float, float]


@dataclass(frozen=True)
class MaterialLook:
    """What a material shows: a colour and a texture file, each where the file gives one."""

    rgba: RGBA | None = None
    texture: Path | None = None
    # The name the texture gives its texture coordinates (``<texture texcoord="UVMap">``): a
    # <bind_vertex_input> of the material's instance says which TEXCOORD set it is.
    texcoord: str | None = None
    emission: float | None = None  # MuJoCo's: a share of the colour it glows with
    notes: tuple[str, ...] = ()  # what the look cannot show, for warnings


NO_LOOK = MaterialLook()


def material_look(reader: Reader, material_id: str) -> MaterialLook:
    """The look of a material; :data:`NO_LOOK` when the file gives it no colour."""
    material = reader.by_url(material_id, ("material",))
    if material is None:
        return NO_LOOK
    instance = reader.find(material, "instance_effect")
    effect = (
        reader.by_url(instance.get("url"), ("effect",), instance) if instance is not None else None
    )
    if effect is None:
        return NO_LOOK
    technique = None
    # The common profile's technique first: another profile's (an <extra>'s) is a tool's own.
    common = reader.find(effect, "profile_COMMON/technique")
    for within in (common, effect):
        for name in ("phong", "lambert", "blinn", "constant"):
            technique = next(within.iter(reader.tag(name)), None) if within is not None else None
            if technique is not None:
                break
        if technique is not None:
            break
    if technique is None:
        return NO_LOOK
    rgba: RGBA | None = None
    texture = None
    texcoord = None
    for channel in (
        ("diffuse", "emission") if etree.QName(technique).localname == "constant" else ("diffuse",)
    ):
        element = reader.find(technique, channel)
        if element is None:
            continue
        colour = reader.find(element, "color")
        if colour is not None:
            values = floats(reader, colour)
            if len(values) >= 3:
                alpha = float(values[3]) if len(values) > 3 else 1.0
                r, g, b = (float(v) for v in values[:3])
                rgba = (r, g, b, alpha)
        sampler = reader.find(element, "texture")
        if sampler is not None:
            texture = _texture_file(reader, effect, sampler.get("texture"))
            texcoord = sampler.get("texcoord") if texture is not None else None
        if rgba or texture:
            break
    if rgba is not None:
        r, g, b, a = rgba
        a *= _opacity(reader, technique)
        rgba = (_unit_interval(r), _unit_interval(g), _unit_interval(b), _unit_interval(a))
    emission: float | None = None
    notes: tuple[str, ...] = ()
    if etree.QName(technique).localname != "constant":  # a constant's emission is its colour
        emission, notes = _emission(reader, technique, rgba, texture is not None, material_id)
    return MaterialLook(rgba, texture, texcoord, emission, notes)


# How far (per channel, 0-1) a glow may be from the share of the colour that shows it before
# a warning says so: 5 of 255 levels.
_GLOW_TOLERANCE = 0.02


def _emission(
    reader: Reader, technique, rgba: RGBA | None, textured: bool, material_id: str
) -> tuple[float | None, tuple[str, ...]]:
    """MuJoCo's emission for a technique's ``<emission>``, and what it cannot show: the share
    of the material's colour (white for a texture) closest to the glow's colour, in least
    squares. A material that gives no colour of its own leaves the URDF's, and glows not."""
    element = reader.find(technique, "emission")
    if element is None:
        return None, ()
    glows = f"material '{material_id}' glows"
    if reader.find(element, "texture") is not None:
        return None, (
            f"{glows} with a texture (<emission>), which a MuJoCo material cannot show; the "
            "model shows it without its glow",
        )
    colour = reader.find(element, "color")
    values = floats(reader, colour)[:3] if colour is not None else ()
    glow = [min(max(float(v), 0.0), 1.0) for v in values]
    if len(glow) < 3 or not any(glow):
        return None, ()
    written = " ".join(f"{g:g}" for g in glow)
    if rgba is None and not textured:
        return None, (
            f"{glows} {written} (<emission>) but gives no colour, and a MuJoCo material glows "
            "only in a share of its own: the model shows it without its glow",
        )
    base = list(rgba[:3]) if rgba is not None else [1.0, 1.0, 1.0]
    weight = sum(b * b for b in base)
    fit = sum(g * b for g, b in zip(glow, base, strict=True)) / weight if weight else 0.0
    share = _unit_interval(fit)
    missed = max(abs(g - share * b) for g, b in zip(glow, base, strict=True))
    notes = (
        (
            f"{glows} {written} (<emission>), and a MuJoCo material glows only in a share of "
            f"its own colour: the model gives it emission {share:g}",
        )
        if missed > _GLOW_TOLERANCE
        else ()
    )
    return share or None, notes


def _unit_interval(value: float) -> float:
    return round(min(max(value, 0.0), 1.0), 6)


# COLLADA's luminance weights for <transparent opaque="RGB_ZERO"> (1.4.1 spec, "Determining
# Transparency").
_LUMINANCE = (0.212671, 0.715160, 0.072169)


def _opacity(reader: Reader, technique) -> float:
    """How opaque a technique's <transparent> and <transparency> make it, as the COLLADA spec
    computes it (A_ONE: the colour's alpha times the transparency; RGB_ZERO: one minus its
    luminance times the transparency). Exporters write values the spec reads as invisible
    (A_ONE with a transparency of 0, a transparent colour with alpha 0) for parts they mean
    opaque: a result of none at all is taken as opaque. Without a <transparent>, only a
    transparency strictly between 0 and 1 is trusted, for the same reason."""
    element = reader.find(technique, "transparency/float")
    try:
        transparency = float(element.text) if element is not None and element.text else None
    except ValueError:
        transparency = None
    transparent = reader.find(technique, "transparent")
    colour = reader.find(transparent, "color") if transparent is not None else None
    values = [float(v) for v in floats(reader, colour)] if colour is not None else []
    if transparent is None or len(values) < 3:
        if transparency is not None and 0.0 < transparency < 1.0:
            return transparency
        return 1.0
    factor = 1.0 if transparency is None else transparency
    if transparent is not None and transparent.get("opaque", "A_ONE") in ("RGB_ZERO", "RGB_ONE"):
        luminance = sum(weight * v for weight, v in zip(_LUMINANCE, values[:3], strict=True))
        seen = luminance * factor
        opacity = 1.0 - seen if transparent.get("opaque") == "RGB_ZERO" else seen
    else:  # A_ONE (the default), A_ZERO
        alpha = values[3] if len(values) > 3 else 1.0
        seen = alpha * factor
        opacity = 1.0 - seen if transparent.get("opaque") == "A_ZERO" else seen
    opacity = min(max(opacity, 0.0), 1.0)
    return opacity if opacity > 0.0 else 1.0


def _texture_file(reader: Reader, effect, sampler_sid: str | None) -> Path | None:
    """Follow sampler2D -> surface -> image to the texture file of a <texture> reference."""
    if not sampler_sid:
        return None
    image_id = sampler_sid
    params = {p.get("sid"): p for p in effect.iter(reader.tag("newparam"))}
    sampler = params.get(sampler_sid)
    if sampler is not None:
        source = next(sampler.iter(reader.tag("source")), None)
        surface = params.get(source.text.strip()) if source is not None and source.text else None
        if surface is not None:
            init = next(surface.iter(reader.tag("init_from")), None)
            if init is not None and init.text:
                image_id = init.text.strip()
        else:  # COLLADA 1.5: the sampler names the image directly
            instance = next(sampler.iter(reader.tag("instance_image")), None)
            if instance is not None:
                image_id = instance.get("url", "").lstrip("#")
    image = reader.by_url(image_id, ("image",))
    if image is None:
        return None
    init = next(image.iter(reader.tag("init_from")), None)
    if init is None:
        return None
    ref = next(init.iter(reader.tag("ref")), None)
    text = (ref.text if ref is not None else init.text) or ""
    text = unquote(text.strip())
    if text.startswith("file://"):
        text = text[len("file://") :]
    path = Path(text)
    if not path.is_absolute():
        path = reader.path.parent / path
    return path if path.is_file() else None
