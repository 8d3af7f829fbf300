"""A lidar's rays written out one by one, for MuJoCo to compile quickly.

A lidar is built as a ``<replicate>`` of one rangefinder site turned by the angle increment
(``add_lidar_sites``), and every sensor naming that site is replicated with it. MuJoCo compiles
such a model in time quadratic in the rays: pybullet_data's racecar, whose Hokuyo has 1,081,
took 4-5 s per compile (its assembly compiles it six times), where the same sites and
rangefinders written out compile in 0.01 s. So before the model is compiled, each such
replicate becomes its sites and each sensor naming its site one sensor per ray, with MuJoCo's
names, order and poses: the compiled model is the same.
"""

from __future__ import annotations

from lxml import etree

from mjcfbuild.numbers import output

# What add_lidar_sites writes: the turn of each copy is about the body's +y.
_TURN_AXIS = 1


def unroll_lidar_rays(root: etree._Element) -> None:
    """Replace each lidar ``<replicate>`` of ``root`` by its sites, and each sensor naming
    its site by one sensor per ray, as MuJoCo's compiler would make them."""
    section = root.find("sensor")
    unrolled: list[tuple[str, list[str], list[etree._Element]]] = []
    for replicate in list(root.iter("replicate")):
        found = _lidar(replicate)
        if found is None:
            continue
        site, count, separator, turn = found
        name = site.get("name", "")
        if _named_outside_sensors(root, name, section):
            continue  # MuJoCo's own replication handles what we would not
        digits = len(str(count))
        suffixes = [f"{separator}{index:0{digits}d}" for index in range(count)]
        parent = replicate.getparent()
        assert parent is not None, "a replicate is inside a body"
        position = parent.index(replicate)
        parent.remove(replicate)
        for index, suffix in enumerate(suffixes):
            ray = etree.Element("site", {"name": name + suffix})
            if index:
                angles = [0.0, 0.0, 0.0]
                angles[_TURN_AXIS] = index * turn
                ray.set("euler", " ".join(output(angle) for angle in angles))
            parent.insert(position + index, ray)
        readers = [] if section is None else [s for s in section if _reads(s, name)]
        for sensor in readers:
            section.remove(sensor)
        unrolled.append((name, suffixes, readers))
    # MuJoCo puts replicated sensors after the others: replicate by replicate, ray by ray,
    # each ray's sensors in their written order.
    for name, suffixes, readers in unrolled:
        assert section is not None or not readers, "readers come from the sensor section"
        for suffix in suffixes:
            for sensor in readers:
                copy = etree.SubElement(section, sensor.tag, dict(sensor.attrib))
                if copy.get("name"):
                    copy.set("name", copy.get("name", "") + suffix)
                for attribute in ("site", "objname"):
                    if copy.get(attribute) == name:
                        copy.set(attribute, name + suffix)


def _lidar(replicate: etree._Element) -> tuple[etree._Element, int, str, float] | None:
    """The site, count, separator and turn of a replicate as add_lidar_sites writes it
    (one bare named site, no offset, a turn about +y); None for any other."""
    children = [child for child in replicate if isinstance(child.tag, str)]
    if len(children) != 1 or children[0].tag != "site" or set(children[0].attrib) != {"name"}:
        return None
    if set(replicate.attrib) != {"count", "sep", "offset", "euler"}:
        return None
    try:
        count = int(replicate.get("count", ""))
        offset = [float(v) for v in replicate.get("offset", "").split()]
        euler = [float(v) for v in replicate.get("euler", "").split()]
    except ValueError:
        return None
    turned = [axis for axis, angle in enumerate(euler) if angle != 0.0]
    if count < 1 or offset != [0.0, 0.0, 0.0] or len(euler) != 3 or turned not in ([], [1]):
        return None
    return children[0], count, replicate.get("sep", ""), euler[_TURN_AXIS]


def _reads(sensor: etree._Element, site: str) -> bool:
    """Whether ``sensor`` names the site ``site`` (MuJoCo replicates it with the site)."""
    if sensor.get("site") == site:
        return True
    return sensor.get("objtype") == "site" and sensor.get("objname") == site


def _named_outside_sensors(root: etree._Element, name: str, section: etree._Element | None) -> bool:
    """Whether anything names the site ``name`` other than the site itself and the sensors
    reading it (a sensor's ``site``, or its ``objname`` with ``objtype="site"``): a sensor's
    ``refname``, an actuator's ``refsite``, an equality's ``site1``... which MuJoCo resolves
    against its replicated sites, and which unrolled rays would leave dangling."""
    for element in root.iter():
        parent = element.getparent()
        if not isinstance(element.tag, str):
            continue
        if element.tag == "site" and parent is not None and parent.tag == "replicate":
            continue  # a replicated site itself
        reader = section is not None and parent is section
        for attribute, value in element.attrib.items():
            if value != name or attribute == "name":  # a name defines, it does not refer
                continue
            if reader and attribute == "site":
                continue
            if reader and attribute == "objname" and element.get("objtype") == "site":
                continue
            return True
    return False
