"""Writes the Gmsh meshes of the bundled examples `cylinder-on-foundation.toml` and
`footing-on-soil.toml` (and of the Hertz test, crates/analysis/tests/it/hertz.rs).

Units: mm.

* `disc-coarse.msh`, `disc-fine.msh`: a disc of radius R = 50 centred at (0, 50) (its lowest
  point at the origin), triangles of size h (0.3, and 0.15 for the fine mesh) within 3.5 of the
  lowest point, growing to 8 far from it; a mesh node at the centre (an embedded point).
  Physical groups: the surface `disc`, the curve `arc` (the lower arc, 20° either side of the
  lowest point), the points `centre` and `top` (0, 100).
* `block-coarse.msh`, `block-fine.msh`: the foundation block 200 × 100 (x from −100 to 100, y
  from −100 to 0), triangles of size 0.7·h near the origin (so that the two meshes do not
  match along the contact), growing to 12. Groups: `block`, `top`, `bottom`.
* `footing.msh`: a footing 2 m wide and 0.8 m high with a chamfer of 0.2 m at its upper
  corners (x from −1 to 1, y from 0 to 0.8; units m), quadrangles of size 0.1 (recombined).
  Groups: `footing`, `base` (its bottom edge), `top`, and the point `column`
  at (0, 0.8), a mesh node.
* `soil.msh`: a soil block 12 m × 6 m (x from −6 to 6, y from −6 to 0; units m), triangles
  of size 0.13 near the footing growing to 0.8. Groups: `soil`, `top`, `bottom`, `sides`.

Run with Gmsh's Python wheel (pip install gmsh; these were written with gmsh 4.15.2):
python3 make.py
"""
import gmsh


def refine_near(points, size_min, dist_min, size_max, dist_max):
    f = gmsh.model.mesh.field
    d = f.add("Distance")
    f.setNumbers(d, "PointsList", points)
    t = f.add("Threshold")
    f.setNumber(t, "InField", d)
    f.setNumber(t, "SizeMin", size_min)
    f.setNumber(t, "SizeMax", size_max)
    f.setNumber(t, "DistMin", dist_min)
    f.setNumber(t, "DistMax", dist_max)
    f.setAsBackgroundMesh(t)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)


def write(out):
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.write(out)
    gmsh.model.remove()


def disc(h, out):
    import math
    gmsh.model.add("disc")
    geo = gmsh.model.geo
    r = 50.0
    c = geo.addPoint(0, r, 0)
    angles = (-90 - 20, -90 + 20, 90)
    p = [geo.addPoint(r * math.cos(math.radians(a)), r + r * math.sin(math.radians(a)), 0)
         for a in angles]
    bottom = geo.addPoint(0, 0, 0)
    arc1 = geo.addCircleArc(p[0], c, bottom)
    arc2 = geo.addCircleArc(bottom, c, p[1])
    right = geo.addCircleArc(p[1], c, p[2])
    left = geo.addCircleArc(p[2], c, p[0])
    loop = geo.addCurveLoop([arc1, arc2, right, left])
    s = geo.addPlaneSurface([loop])
    geo.synchronize()
    gmsh.model.mesh.embed(0, [c], 2, s)
    refine_near([bottom], h, 3.5, 8.0, 45.0)
    gmsh.model.addPhysicalGroup(2, [s], 1, "disc")
    gmsh.model.addPhysicalGroup(1, [arc1, arc2], 2, "arc")
    gmsh.model.addPhysicalGroup(0, [c], 3, "centre")
    gmsh.model.addPhysicalGroup(0, [p[2]], 4, "top")
    gmsh.model.mesh.generate(2)
    write(out)


def rectangle(name, x0, y0, x1, y1, near, size_min, dist_min, size_max, dist_max, out,
              sides=False):
    gmsh.model.add(name)
    geo = gmsh.model.geo
    pts = [geo.addPoint(x, y, 0) for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
    lines = [geo.addLine(pts[i], pts[(i + 1) % 4]) for i in range(4)]
    s = geo.addPlaneSurface([geo.addCurveLoop(lines)])
    m = geo.addPoint(near[0], near[1], 0)
    geo.synchronize()
    refine_near([m], size_min, dist_min, size_max, dist_max)
    gmsh.model.addPhysicalGroup(2, [s], 1, name)
    gmsh.model.addPhysicalGroup(1, [lines[2]], 2, "top")
    gmsh.model.addPhysicalGroup(1, [lines[0]], 3, "bottom")
    if sides:
        gmsh.model.addPhysicalGroup(1, [lines[1], lines[3]], 4, "sides")
    gmsh.model.mesh.generate(2)
    write(out)


def footing(out):
    gmsh.model.add("footing")
    gmsh.model.mesh.field.setAsBackgroundMesh(-1)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 1)
    geo = gmsh.model.geo
    # the top edge in two halves, so that the column's point (0, 0.8) is a mesh node
    xy = ((-1, 0), (1, 0), (1, 0.6), (0.8, 0.8), (0, 0.8), (-0.8, 0.8), (-1, 0.6))
    pts = [geo.addPoint(x, y, 0, 0.1) for x, y in xy]
    lines = [geo.addLine(pts[i], pts[(i + 1) % 7]) for i in range(7)]
    s = geo.addPlaneSurface([geo.addCurveLoop(lines)])
    geo.synchronize()
    gmsh.model.mesh.setRecombine(2, s)
    gmsh.model.addPhysicalGroup(2, [s], 1, "footing")
    gmsh.model.addPhysicalGroup(1, [lines[0]], 2, "base")
    gmsh.model.addPhysicalGroup(1, [lines[3], lines[4]], 3, "top")
    gmsh.model.addPhysicalGroup(0, [pts[4]], 4, "column")
    gmsh.model.mesh.generate(2)
    write(out)


gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
for h, tag in ((0.3, "coarse"), (0.15, "fine")):
    disc(h, "disc-%s.msh" % tag)
    rectangle("block", -100, -100, 100, 0, (0, 0), 0.7 * h, 3.0, 12.0, 50.0,
              "block-%s.msh" % tag)
footing("footing.msh")
rectangle("soil", -6, -6, 6, 0, (0, 0), 0.13, 1.2, 0.8, 5.0, "soil.msh", sides=True)
gmsh.finalize()
