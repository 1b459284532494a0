"""Writes the block meshes of the `[[meshes]]` tests (crates/io/tests/it/meshes.rs) and what
Gmsh itself says of them.

A rectangle 4 × 1 (x from 0 to 4, y from 0 to 1), twice:

* `block_tri_41.msh` (MSH 4.1): unstructured triangles, size 0.5;
* `block_quad_22.msh` (MSH 2.2): a transfinite 8 × 2 grid of quadrangles, whose nodes are those
  of a `[[blocks]]` grid with nx = 8, ny = 2.

Physical groups: the surface `body`; the curves `bottom`, `right`, `top` and `left`, plus an
unnamed one (tag 40) on the right edge; the point `tip` at (4, 1). `block_expected.txt` lists,
from Gmsh's API (an independent reference for our reader and builder): per mesh, the nodes that
elements use with their coordinates, the 2D elements (tag and node tags), and per physical group
its dimension, tag, name, and its nodes — for a curve, in order along its line elements.

Run with Gmsh's Python wheel (pip install gmsh): python3 make_blocks.py
"""
import gmsh


def block(name, quads, version, out, f):
    gmsh.model.add(name)
    geo = gmsh.model.geo
    pts = [geo.addPoint(x, y, 0) for x, y in ((0, 0), (4, 0), (4, 1), (0, 1))]
    lines = [geo.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
    loop = geo.addCurveLoop(lines)
    surf = geo.addPlaneSurface([loop])
    geo.synchronize()
    if quads:
        for c, n in zip(lines, (9, 3, 9, 3)):
            gmsh.model.mesh.setTransfiniteCurve(c, n)
        gmsh.model.mesh.setTransfiniteSurface(surf)
        gmsh.model.mesh.setRecombine(2, surf)
    else:
        gmsh.option.setNumber("Mesh.MeshSizeMax", 0.5)
    gmsh.model.addPhysicalGroup(2, [surf], 1, "body")
    for tag, (c, nm) in enumerate(zip(lines, ("bottom", "right", "top", "left")), start=11):
        gmsh.model.addPhysicalGroup(1, [c], tag, nm)
    gmsh.model.addPhysicalGroup(1, [lines[1]], 40)  # unnamed: known by its tag
    gmsh.model.addPhysicalGroup(0, [pts[2]], 50, "tip")
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.write(out)

    f.write("mesh %s\n" % out)
    used = set()
    types, etags, enodes = gmsh.model.mesh.getElements(2)
    for t, tags, nodes in zip(types, etags, enodes):
        k = gmsh.model.mesh.getElementProperties(t)[3]
        for i, e in enumerate(tags):
            ns = [int(n) for n in nodes[k * i:k * (i + 1)]]
            used.update(ns)
            f.write("element %d %s\n" % (e, " ".join(map(str, ns))))
    for n in sorted(used):
        c, _, _, _ = gmsh.model.mesh.getNode(n)
        f.write("node %d %.17g %.17g\n" % (n, c[0], c[1]))
    for dim, ptag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, ptag) or "-"
        order = []
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            if dim == 1:
                _, _, en = gmsh.model.mesh.getElements(1, ent)
                ns = [int(n) for n in en[0]]
                for n in ns[0::2] + ns[-1:]:
                    if n not in order:
                        order.append(n)
            else:
                ns, _ = gmsh.model.mesh.getNodesForPhysicalGroup(dim, ptag)
                order = sorted(int(n) for n in ns)
        f.write("group %d %d %s %s\n" % (dim, ptag, name, " ".join(map(str, order))))
    gmsh.model.remove()


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
with open("block_expected.txt", "w") as f:
    f.write("# written by make_blocks.py from Gmsh's API (gmsh %s)\n" % gmsh.__version__)
    block("block_tri", False, 4.1, "block_tri_41.msh", f)
    block("block_quad", True, 2.2, "block_quad_22.msh", f)
gmsh.finalize()
