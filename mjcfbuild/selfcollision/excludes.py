"""Contact excludes in the model tree."""

from __future__ import annotations

from lxml import etree


def write_excludes(root: etree._Element, pairs: list[tuple[str, str]]) -> None:
    """Add ``<contact><exclude body1 body2/>`` for each pair the tree does not exclude yet."""
    if not pairs:
        return
    section = root.find("contact")
    if section is None:
        section = etree.SubElement(root, "contact")
    present = {frozenset((e.get("body1"), e.get("body2"))) for e in section.iter("exclude")}
    for body1, body2 in pairs:
        if frozenset((body1, body2)) in present:
            continue
        present.add(frozenset((body1, body2)))
        etree.SubElement(section, "exclude", {"body1": body1, "body2": body2})
