"""Step ``mesh``: convert one mesh file into its product, through the shared cache."""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path
from typing import Any

from mjcfbuild.errors import InputError
from mjcfbuild.failpoints import failpoint
from mjcfbuild.meshes.product import MeshProduct
from mjcfbuild.meshes.references import missing_paths, missing_references, referenced_files
from mjcfbuild.meshes.upaxis import UpAxisDecision
from mjcfbuild.products.store import open_store, product_key
from mjcfbuild.steps.depfile import Depfile
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import MeshPayload
from mjcfbuild.steps.versions import MESH


def run(payload: dict) -> dict:
    """Convert the ``source`` mesh into ``product_dir``; write the summary. An error about
    the whole mesh file (no line of its own) points at the URDF line naming it, as a missing
    mesh does (:func:`at_urdf_line`)."""
    request = MeshPayload.from_dict(payload)
    try:
        return _run(request)
    except InputError as error:
        raise at_urdf_line(error, request) from None


def at_urdf_line(error: InputError, request: MeshPayload) -> InputError:
    """``error``, about the mesh file as a whole, pointed at the URDF line that names the mesh
    (``robot.urdf:6: meshes/arm.stl: not an STL file ...``), so that it says which element to
    fix; an error at a line of the mesh file (a DAE's), or with no URDF line known, as it is."""
    location = error.location
    file, _, line = request.named_at.rpartition(":")
    if location is None or location.line is not None or not line.isdigit():
        return error
    if os.path.normpath(location.file) != os.path.normpath(request.source):
        return error
    moved = InputError(
        f"{request.label or location.file}: {error.message}",
        file=file,
        line=int(line),
        hint=error.hint,
    )
    moved.details = error.details
    return moved


def _run(request: MeshPayload) -> dict:
    """:func:`run`, given its payload."""
    source = Path(request.source)
    product_dir = Path(request.product_dir)
    check_size(source, request.max_file_bytes)
    references = referenced_files(source)
    store = open_store(request.cache)
    params, decision = conversion_options(request)
    looks_from = Path(request.looks_from) if request.looks_from else None
    key = _key(params, source, references, looks_from)
    stored = store.fetch(key, product_dir, "mesh") if store else None
    cached = stored is not None
    if stored is not None:
        summary = MeshProduct.from_dict(stored)
    else:
        # numpy and trimesh: only when a conversion is needed
        from mjcfbuild.meshes.convert import convert_with_options

        summary = convert_with_options(source, product_dir, params, looks_from)
        if store:
            store.store(key, product_dir, summary.to_dict(), "mesh")
    # The decision's reason follows this build's evidence; the product follows only its verdict.
    summary = dataclasses.replace(summary, up_axis=decision.to_dict() if decision else None)
    failpoint("mesh")
    # A file the mesh names that is not there reruns the task when it appears.
    missing = [str(p) for p in missing_paths(source)]
    # The files the look comes from count as the mesh's own references do.
    read = [*references, *(referenced_files(looks_from) if looks_from else [])]
    Depfile([str(p) for p in read], missing, {}).write(Path(request.depfile))
    outputs = {str(product_dir / name): digest for name, digest in summary.files.items()}
    write_output(Path(request.summary), summary.text(), outputs)
    return {
        "outputs": outputs,
        "discovered": [str(p) for p in read],
        "warnings": [
            *_missing_warning(source, request.label, request.options.roles),
            *summary.warnings,
        ],
        "cached": cached,
        "stored": not cached and store is not None,
        "dropped": len(store.dropped) if store else 0,
    }


def _missing_warning(source: Path, label: str, roles: list[str] | None = None) -> list[str]:
    """One warning naming what ``source`` refers to that is not there, or none; none for a
    mesh only collided with (``roles`` without "visual"), whose materials nothing shows."""
    if roles is not None and "visual" not in roles:
        return []
    missing = missing_references(source)
    if not missing:
        return []
    them = "it" if len(missing) == 1 else "them"
    beside = all(path.parent == source.parent for path in missing_paths(source))
    return [
        f"{label or source.name}: refers to {', '.join(missing)}, not found "
        f"{'beside it' if beside else 'where it says'}; the "
        f"model shows the mesh without {them} (add the file{'s' if them == 'them' else ''}, "
        "or remove the reference from the mesh)"
    ]


def cache_key(request: MeshPayload, references: list[Path] | None = None) -> str:
    """The product key of the conversion ``request`` asks for (see :func:`product_key`)."""
    source = Path(request.source)
    if references is None:
        references = referenced_files(source)
    looks_from = Path(request.looks_from) if request.looks_from else None
    return _key(conversion_options(request)[0], source, references, looks_from)


def _key(
    params: dict[str, Any], source: Path, references: list[Path], looks_from: Path | None = None
) -> str:
    files: list[str | Path] = [source, *references]
    if looks_from is not None:  # convert -a: the look of the file the OBJ stands for
        params = {**params, "looks_from": True}
        files += [looks_from, *referenced_files(looks_from)]
    return product_key("mesh", {**params, "versions": MESH.versions()}, files)


def conversion_options(request: MeshPayload) -> tuple[dict[str, Any], UpAxisDecision | None]:
    """The options the conversion takes, with ``auto`` up axis decided (``apply`` or
    ``ignore``), and for a DAE file tagged other than Z-up, what was decided and why."""
    params = request.options.cache_params()
    mode = params["collada_up_axis"]
    source = Path(request.source)
    if source.suffix.lower() != ".dae":
        return params, None
    from mjcfbuild.meshes.upaxis import read_up_axis

    tag = read_up_axis(source)
    if mode == "auto":
        decision = _decide(source, tag, request)
        params["collada_up_axis"] = "apply" if decision.turned else "ignore"
        return params, decision if tag != "Z_UP" else None
    if tag == "Z_UP":
        return params, None
    said = f"robot.yaml meshes.collada_up_axis (or collada_up_axis_files) says {mode}"
    if mode == "apply":
        return params, UpAxisDecision(tag, True, f"tagged {tag}, turned to Z-up: {said}")
    return params, UpAxisDecision(tag, False, f"tagged {tag}, kept as written: {said}")


def _decide(source: Path, tag: str, request: MeshPayload) -> UpAxisDecision:
    from mjcfbuild.meshes.upaxis import MeshUse, decide

    uses = [MeshUse.from_dict(use) for use in request.evidence]
    if tag not in ("Y_UP", "X_UP") or not uses:
        return decide(_no_vertices(), tag, uses)
    import numpy as np

    from mjcfbuild.meshes.collada import read_collada

    parts = read_collada(source).parts
    vertices = np.concatenate([part.vertices for part in parts]) if parts else _no_vertices()
    if len(vertices) == 0:
        return UpAxisDecision(tag, False, f"tagged {tag}, kept as written: it has no vertices")
    return decide(vertices, tag, uses)


def _no_vertices() -> Any:
    import numpy as np

    return np.zeros((0, 3))


def check_size(source: Path, max_bytes: int) -> None:
    """Refuse an empty mesh file, or one larger than ``meshes.max_file_mb``, before loading it."""
    try:
        size = source.stat().st_size
    except OSError as exc:  # removed or replaced since the plan was made
        raise InputError(f"cannot read the mesh file: {exc.strerror}", file=source) from None
    if size == 0:
        raise InputError("the mesh file is empty", file=source, hint="export the mesh again")
    if size > max_bytes:
        raise InputError(
            f"the mesh file is {size / 1e6:.3g} MB, more than meshes.max_file_mb "
            f"({max_bytes / 1e6:g} MB)",
            file=source,
            hint="simplify the mesh, or raise meshes.max_file_mb in robot.yaml",
        )
