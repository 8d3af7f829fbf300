"""Step ``mesh``: convert one mesh file into its product, through the shared cache."""

from __future__ import annotations

from pathlib import Path

from mjcfbuild.engine.depfile import Depfile
from mjcfbuild.engine.store import open_store, product_key
from mjcfbuild.engine.versions import step_versions
from mjcfbuild.errors import InputError
from mjcfbuild.failpoints import failpoint
from mjcfbuild.meshes.product import MeshProduct
from mjcfbuild.meshes.references import referenced_files
from mjcfbuild.steps.outputs import write_output
from mjcfbuild.steps.payloads import MeshPayload


def run(payload: dict) -> dict:
    """Convert the ``source`` mesh into ``product_dir``; write the summary."""
    request = MeshPayload.from_dict(payload)
    source = Path(request.source)
    product_dir = Path(request.product_dir)
    options = request.options
    check_size(source, request.max_file_bytes)
    references = referenced_files(source)
    store = open_store(request.cache)
    key = cache_key(request, references)
    stored = store.fetch(key, product_dir) if store else None
    cached = stored is not None
    if stored is not None:
        summary = MeshProduct.from_dict(stored)
    else:
        # numpy and trimesh: only when a conversion is needed
        from mjcfbuild.meshes.convert import convert_with_options

        summary = convert_with_options(source, product_dir, options.cache_params())
        if store:
            store.store(key, product_dir, summary.to_dict())
    failpoint("mesh")
    Depfile([str(p) for p in references], [], {}).write(Path(request.depfile))
    outputs = {str(product_dir / name): digest for name, digest in summary.files.items()}
    write_output(Path(request.summary), summary.text(), outputs)
    return {
        "outputs": outputs,
        "discovered": [str(p) for p in references],
        "warnings": summary.warnings,
        "cached": cached,
        "stored": not cached and store is not None,
    }


def cache_key(request: MeshPayload, references: list[Path] | None = None) -> str:
    """The product key of the conversion ``request`` asks for (see :func:`product_key`)."""
    source = Path(request.source)
    if references is None:
        references = referenced_files(source)
    params = {**request.options.cache_params(), "versions": step_versions("mesh")}
    return product_key("mesh", params, [source, *references])


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
