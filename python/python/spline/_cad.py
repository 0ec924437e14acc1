"""CAD files: STEP (AP214) and IGES 5.3 B-spline curves and surfaces in and out."""

from __future__ import annotations

import os
from dataclasses import dataclass
from typing import Any, Iterable, List, Optional, Sequence, Union

from . import _core
from ._exchange import read_json

PathLike = Union[str, "os.PathLike[str]"]


@dataclass(frozen=True)
class CadItem:
    """One entity of a CAD file: its geometry (``BSpline`` for a polynomial curve,
    ``NurbsCurve``, ``NurbsSurface``) with the file's id (STEP ``#id``, IGES directory
    entry), name and entity type (``B_SPLINE_CURVE_WITH_KNOTS``, ``CYLINDRICAL_SURFACE``,
    ``126``…). Analytic entities arrive converted exactly to NURBS."""

    id: int
    name: str
    entity: str
    geometry: Any


def _read(path: PathLike, extensions: Sequence[str]) -> List[CadItem]:
    path = os.fspath(path)
    if not path.lower().endswith(tuple(extensions)):
        raise _core.SplineError(f"{path}: expected a file ending in {' or '.join(extensions)}")
    return [CadItem(i, name, entity, read_json(text)) for i, name, entity, text in _core.read_cad(path)]


def _write(path: PathLike, objects: Iterable[Any], names: Optional[Sequence[str]], extensions: Sequence[str]) -> None:
    path = os.fspath(path)
    if not path.lower().endswith(tuple(extensions)):
        raise _core.SplineError(f"{path}: expected a file ending in {' or '.join(extensions)}")
    objects = list(objects)
    if names is None:
        names = [f"object{k}" for k in range(len(objects))]
    if len(names) != len(objects):
        raise _core.SplineError(f"{len(names)} names for {len(objects)} objects")
    items = []
    for k, (name, obj) in enumerate(zip(names, objects)):
        to_json = getattr(obj, "to_json", None)
        if to_json is None:
            raise _core.SplineError(f"object {k} ({type(obj).__name__}) is not a curve or surface of this package")
        items.append((str(name), to_json()))
    _core.write_cad(path, items)


def read_step(path: PathLike) -> List[CadItem]:
    """The B-spline curves and surfaces of a STEP file (every face's surface and edge's
    curve of a B-rep; lines, circles, planes, cylinders, cones, spheres, tori… converted
    exactly to NURBS). Raises ``SplineError`` with the line for what cannot be read."""
    return _read(path, (".step", ".stp", ".p21"))


def write_step(path: PathLike, objects: Iterable[Any], names: Optional[Sequence[str]] = None) -> None:
    """Writes curves (2-D curves in the plane z = 0) and surfaces to a STEP AP214 file,
    numbers that read back bit for bit."""
    _write(path, objects, names, (".step", ".stp", ".p21"))


def read_iges(path: PathLike) -> List[CadItem]:
    """The rational B-spline curves (126) and surfaces (128) of an IGES file, lines (110),
    arcs (100) and surfaces of revolution (120) and tabulated cylinders (122) converted."""
    return _read(path, (".igs", ".iges"))


def write_iges(path: PathLike, objects: Iterable[Any], names: Optional[Sequence[str]] = None) -> None:
    """Writes curves and surfaces to an IGES 5.3 file as entities 126 and 128."""
    _write(path, objects, names, (".igs", ".iges"))
