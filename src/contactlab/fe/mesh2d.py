"""Plane-strain meshes of a strip (layer) on a block for the receding-contact models (sec. 8.2).

A symmetric half model: the strip occupies 0 <= x <= L, 0 <= y <= c, the block
0 <= x <= L, -H <= y <= 0; x = 0 is the plane of symmetry (Figs 8.1, 8.7, 8.13).
The interface is meshed with the same nodes' x positions on both sides (a conforming
pair of contact surfaces with coincident but distinct nodes): uniform elements of size
``h`` on 0 <= x <= ``x_fine``, then a geometric growth to the far edge. The strip is a
structured quad mesh; the block is an unstructured quad mesh whose size grows with the
distance from the interface. Meshes come from gmsh (Python API); the result is plain
numpy arrays so that the deck writer does not depend on gmsh.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


@dataclass
class StripBlockGeometry:
    """Dimensions (mm) and mesh controls of a strip-on-block half model.

    ``breaks`` are extra x positions (e.g. the edge of a pressure patch, w) where the
    strip's top surface needs a node; they must lie inside (0, x_fine).
    """

    length: float = 20.0
    thickness: float = 1.0
    depth: float = 20.0
    h: float = 0.05
    x_fine: float = 5.0
    layer_rows: int = 8
    growth: float = 1.15
    breaks: tuple[float, ...] = ()

    def check(self) -> None:
        if not (0 < self.h < self.thickness <= self.length and self.depth > 0):
            raise ValueError(f"bad strip/block dimensions or element size: {self}")
        if not (0 < self.x_fine < self.length):
            raise ValueError(f"x_fine must lie in (0, length), got {self.x_fine}")
        for xb in self.breaks:
            if not (0 < xb < self.x_fine):
                raise ValueError(f"break {xb} must lie in (0, x_fine={self.x_fine})")
        if self.layer_rows < 1 or self.growth < 1:
            raise ValueError("layer_rows must be >= 1 and growth >= 1")


@dataclass
class PlaneMesh:
    """Nodes (id -> x, y), linear quads and triangles (counter-clockwise), named sets.

    ``edges`` maps a set name to a list of (element id, face number) with the
    CalculiX/Abaqus face numbering of a linear 2D element (face k joins corner k and k+1).
    ``interface`` holds the node ids of the strip's bottom and the block's top, paired
    by x and sorted by x.
    """

    nodes: dict[int, tuple[float, float]]
    elements: dict[str, dict[int, tuple[int, ...]]]
    node_sets: dict[str, list[int]] = field(default_factory=dict)
    edges: dict[str, list[tuple[int, int]]] = field(default_factory=dict)
    interface: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    @property
    def n_elements(self) -> int:
        return sum(len(v) for v in self.elements.values())

    @property
    def n_nodes(self) -> int:
        return len(self.nodes)


def _graded_count(length: float, h: float, growth: float) -> tuple[int, float]:
    """Number of elements and progression ratio to go from size h, growing by ``growth``."""
    if growth <= 1.0 + 1e-9:
        return max(1, round(length / h)), 1.0
    n = max(1, math.ceil(math.log(1.0 + length * (growth - 1.0) / h) / math.log(growth)))
    # solve h * (r^n - 1)/(r - 1) = length for r so the first element is h
    lo, hi = 1.0 + 1e-12, growth * 2
    for _ in range(200):
        r = 0.5 * (lo + hi)
        total = h * (r**n - 1.0) / (r - 1.0)
        lo, hi = (r, hi) if total < length else (lo, r)
    return n, 0.5 * (lo + hi)


def strip_on_block(geom: StripBlockGeometry) -> PlaneMesh:
    """Mesh the half model with gmsh and return it as a :class:`PlaneMesh`."""
    import gmsh

    geom.check()
    xs = [0.0, *sorted(geom.breaks), geom.x_fine, geom.length]
    c, big_h = geom.thickness, geom.depth
    gmsh.initialize(["-noenv"], readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.option.setNumber("General.NumThreads", 1)
        # keep the coincident strip/block interface points apart (two contact surfaces)
        gmsh.option.setNumber("Geometry.AutoCoherence", 0)
        gmsh.model.add("strip_on_block")
        occ = gmsh.model.geo
        # strip: bottom and top points at each break
        bottom = [occ.addPoint(x, 0.0, 0.0) for x in xs]
        top = [occ.addPoint(x, c, 0.0) for x in xs]
        # block top points: distinct points at the same positions
        btop = [occ.addPoint(x, 0.0, 0.0) for x in xs]
        bl = occ.addPoint(0.0, -big_h, 0.0)
        br = occ.addPoint(geom.length, -big_h, 0.0)

        counts = []
        for i in range(len(xs) - 1):
            seg = xs[i + 1] - xs[i]
            if i < len(xs) - 2:
                counts.append((max(1, round(seg / geom.h)), 1.0))
            else:
                counts.append(_graded_count(seg, geom.h, geom.growth))

        strip_surfaces = []
        layer_bottom_lines, layer_top_lines, block_top_lines = [], [], []
        verticals = [occ.addLine(bottom[i], top[i]) for i in range(len(xs))]
        for i in range(len(xs) - 1):
            lb = occ.addLine(bottom[i], bottom[i + 1])
            lt = occ.addLine(top[i + 1], top[i])
            layer_bottom_lines.append(lb)
            layer_top_lines.append(lt)
            loop = occ.addCurveLoop([lb, verticals[i + 1], lt, -verticals[i]])
            strip_surfaces.append(occ.addPlaneSurface([loop]))
        for i in range(len(xs) - 1):
            block_top_lines.append(occ.addLine(btop[i], btop[i + 1]))
        right = occ.addLine(btop[-1], br)
        base = occ.addLine(br, bl)
        left = occ.addLine(bl, btop[0])
        block_loop = occ.addCurveLoop([*block_top_lines, right, base, left])
        block_surface = occ.addPlaneSurface([block_loop])
        occ.synchronize()

        mesh = gmsh.model.mesh
        for i, (n, r) in enumerate(counts):
            for line in (layer_bottom_lines[i], block_top_lines[i]):
                mesh.setTransfiniteCurve(line, n + 1, "Progression", r)
            mesh.setTransfiniteCurve(layer_top_lines[i], n + 1, "Progression", 1.0 / r)
        for v in verticals:
            mesh.setTransfiniteCurve(v, geom.layer_rows + 1)
        for s in strip_surfaces:
            mesh.setTransfiniteSurface(s)
            mesh.setRecombine(2, s)
        # block: element size grows with distance from the interface
        dist = mesh.field.add("Distance")
        mesh.field.setNumbers(dist, "CurvesList", block_top_lines)
        mesh.field.setNumber(dist, "Sampling", 400)
        grow = mesh.field.add("MathEval")
        coarse = max(big_h, geom.length) / 8.0
        mesh.field.setString(
            grow, "F",
            f"Min({coarse}, Max({geom.h}, {geom.h} + 0.25*F{dist}"
            f" + 0.02*Max(x - {geom.x_fine}, 0)))",
        )
        mesh.field.setAsBackgroundMesh(grow)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.Algorithm", 8)  # frontal-Delaunay for quads
        gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)
        gmsh.option.setNumber("Mesh.SubdivisionAlgorithm", 0)
        mesh.setRecombine(2, block_surface)
        mesh.generate(2)

        tags, coords, _ = mesh.getNodes()
        xyz = coords.reshape(-1, 3)
        nodes = {int(t): (float(p[0]), float(p[1])) for t, p in zip(tags, xyz, strict=True)}

        def cells(surfaces: list[int]) -> dict[int, tuple[int, ...]]:
            out: dict[int, tuple[int, ...]] = {}
            for s in surfaces:
                types, etags, enodes = mesh.getElements(2, s)
                for et, tg, nd in zip(types, etags, enodes, strict=True):
                    corners = {2: 3, 3: 4}.get(int(et))
                    if corners is None:
                        raise ValueError(f"gmsh produced elements of type {et} in surface {s}")
                    for e, conn in zip(tg, nd.reshape(-1, corners), strict=True):
                        out[int(e)] = tuple(int(n) for n in conn)
            return out

        elements = {"STRIP": cells(strip_surfaces), "BLOCK": cells([block_surface])}

        def curve_nodes(curves: list[int]) -> list[int]:
            ids: set[int] = set()
            for cv in curves:
                t, _, _ = mesh.getNodes(1, cv, includeBoundary=True)
                ids.update(int(i) for i in t)
            return sorted(ids, key=lambda n: (nodes[n][0], nodes[n][1]))

        node_sets = {
            "STRIP_BOTTOM": curve_nodes(layer_bottom_lines),
            "STRIP_TOP": curve_nodes(layer_top_lines),
            "STRIP_LEFT": curve_nodes([verticals[0]]),
            "STRIP_RIGHT": curve_nodes([verticals[-1]]),
            "BLOCK_TOP": curve_nodes(block_top_lines),
            "BLOCK_LEFT": curve_nodes([left]),
            "BLOCK_RIGHT": curve_nodes([right]),
            "BLOCK_BASE": curve_nodes([base]),
        }
    finally:
        gmsh.finalize()

    _orient_ccw(nodes, elements)
    plane = PlaneMesh(nodes=nodes, elements=elements, node_sets=node_sets)
    plane.edges = {
        "STRIP_BOTTOM": _faces_on(plane, "STRIP", set(node_sets["STRIP_BOTTOM"])),
        "STRIP_TOP": _faces_on(plane, "STRIP", set(node_sets["STRIP_TOP"])),
        "BLOCK_TOP": _faces_on(plane, "BLOCK", set(node_sets["BLOCK_TOP"])),
    }
    sb = np.array(node_sets["STRIP_BOTTOM"])
    bt = np.array(node_sets["BLOCK_TOP"])
    x_s = np.array([nodes[n][0] for n in sb])
    x_b = np.array([nodes[n][0] for n in bt])
    if sb.size != bt.size or np.max(np.abs(x_s - x_b)) > 1e-9 * geom.length:
        raise ValueError("interface nodes of strip and block do not pair up")
    plane.interface = (x_s, sb, bt)
    return plane


def _orient_ccw(nodes: dict[int, tuple[float, float]],
                elements: dict[str, dict[int, tuple[int, ...]]]) -> None:
    """Reverse elements with a negative signed area so every element is counter-clockwise."""
    for group in elements.values():
        for e, conn in group.items():
            p = np.array([nodes[n] for n in conn])
            area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
            if area < 0:
                group[e] = (conn[0], *conn[:0:-1])


def _faces_on(mesh: PlaneMesh, group: str, on: set[int]) -> list[tuple[int, int]]:
    """(element, face) pairs whose two corner nodes both lie in ``on``."""
    out = []
    for e, conn in mesh.elements[group].items():
        m = len(conn)
        for k in range(m):
            if conn[k] in on and conn[(k + 1) % m] in on:
                out.append((e, k + 1))
    return out


def structured_strip_on_block(xs: np.ndarray, thickness: float, depth: float,
                              strip_rows: int, block_rows: int) -> PlaneMesh:
    """A structured quad mesh of the strip-on-block half model, without gmsh.

    Both bodies share the interface node positions ``xs`` (mm, increasing from 0); the
    strip has ``strip_rows`` and the block ``block_rows`` uniform rows of CPE4 elements.
    Node and element numbers follow the rows (strip first), so the mesh, and a deck
    written on it, is the same on every machine: the patch test of the interface law
    (:mod:`contactlab.fe.interface_law`) and the deck tests use it.
    """
    xs = np.asarray(xs, dtype=float)
    if xs.ndim != 1 or xs.size < 2 or xs[0] != 0.0 or np.any(np.diff(xs) <= 0):
        raise ValueError("xs must be increasing node positions starting at 0")
    if not (thickness > 0 and depth > 0 and strip_rows >= 1 and block_rows >= 1):
        raise ValueError("thickness and depth must be > 0, strip_rows and block_rows >= 1")
    nx = xs.size
    nodes: dict[int, tuple[float, float]] = {}
    elements: dict[str, dict[int, tuple[int, ...]]] = {}
    grids: dict[str, np.ndarray] = {}
    next_node, next_elem = 1, 1
    for body, ys in (("STRIP", np.linspace(0.0, thickness, strip_rows + 1)),
                     ("BLOCK", np.linspace(-depth, 0.0, block_rows + 1))):
        ids = np.arange(next_node, next_node + nx * ys.size).reshape(ys.size, nx)
        next_node += ids.size
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                nodes[int(ids[j, i])] = (float(x), float(y))
        cells = {}
        for j in range(ys.size - 1):
            for i in range(nx - 1):
                cells[next_elem] = (int(ids[j, i]), int(ids[j, i + 1]), int(ids[j + 1, i + 1]),
                                    int(ids[j + 1, i]))
                next_elem += 1
        elements[body] = cells
        grids[body] = ids
    strip, block = grids["STRIP"], grids["BLOCK"]
    node_sets = {
        "STRIP_BOTTOM": [int(n) for n in strip[0]],
        "STRIP_TOP": [int(n) for n in strip[-1]],
        "STRIP_LEFT": [int(n) for n in strip[:, 0]],
        "STRIP_RIGHT": [int(n) for n in strip[:, -1]],
        "BLOCK_TOP": [int(n) for n in block[-1]],
        "BLOCK_LEFT": [int(n) for n in block[:, 0]],
        "BLOCK_RIGHT": [int(n) for n in block[:, -1]],
        "BLOCK_BASE": [int(n) for n in block[0]],
    }
    plane = PlaneMesh(nodes=nodes, elements=elements, node_sets=node_sets)
    plane.edges = {
        "STRIP_BOTTOM": _faces_on(plane, "STRIP", set(node_sets["STRIP_BOTTOM"])),
        "STRIP_TOP": _faces_on(plane, "STRIP", set(node_sets["STRIP_TOP"])),
        "BLOCK_TOP": _faces_on(plane, "BLOCK", set(node_sets["BLOCK_TOP"])),
    }
    plane.interface = (xs.copy(), strip[0].copy(), block[-1].copy())
    return plane
