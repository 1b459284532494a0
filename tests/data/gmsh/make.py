"""Writes the Gmsh test meshes of the io crate and what Gmsh itself says of them.

A half disc of radius 1 meshed with triangles resting on a rectangular plate meshed with
quadrangles (recombined), their meshes not matching along the contact line; physical groups of
every dimension, one of them unnamed. The same mesh is saved as MSH 4.1 and as MSH 2.2 ASCII.
`expected.txt` lists, from Gmsh's own API (an independent reference for our reader): the node
count, the coordinates of three nodes, and per physical group its dimension, tag, name and the
number of elements of each type.

Run with Gmsh's Python wheel (pip install gmsh): python3 make.py
"""
import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("disc_on_plate")
occ = gmsh.model.occ
disc = occ.addDisk(0, 1.0, 0, 1.0, 1.0)
cut = occ.addRectangle(-1.5, 1.0, 0, 3.0, 1.5)
half, _ = occ.cut([(2, disc)], [(2, cut)])
plate = occ.addRectangle(-2.0, -0.6, 0, 4.0, 0.6)
occ.synchronize()
half_tag = half[0][1]
# Curves of the half disc: the arc (lowest point y = 0) and the top edge.
arc, top = None, None
for dim, tag in gmsh.model.getBoundary([(2, half_tag)], oriented=False):
    bb = gmsh.model.getBoundingBox(dim, tag)
    if abs(bb[4] - 1.0) < 1e-6 and abs(bb[1] - 1.0) < 1e-6:
        top = tag
    else:
        arc = tag
plate_top = None
for dim, tag in gmsh.model.getBoundary([(2, plate)], oriented=False):
    bb = gmsh.model.getBoundingBox(dim, tag)
    if abs(bb[1]) < 1e-6 and abs(bb[4]) < 1e-6:
        plate_top = tag
gmsh.model.addPhysicalGroup(2, [half_tag], 10, "disc")
gmsh.model.addPhysicalGroup(2, [plate], 20, "plate")
gmsh.model.addPhysicalGroup(1, [arc], 11, "arc")
gmsh.model.addPhysicalGroup(1, [plate_top], 21, "plate top")
gmsh.model.addPhysicalGroup(1, [top], 12)  # unnamed: known by its tag
gmsh.option.setNumber("Mesh.MeshSizeMax", 0.35)
gmsh.model.mesh.setRecombine(2, plate)
gmsh.model.mesh.generate(2)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.write("disc_on_plate_41.msh")
gmsh.option.setNumber("Mesh.MshFileVersion", 2.2)
gmsh.write("disc_on_plate_22.msh")

tags, coords, _ = gmsh.model.mesh.getNodes()
with open("expected.txt", "w") as f:
    f.write("# written by make.py from Gmsh's API (gmsh %s)\n" % gmsh.__version__)
    f.write("nodes %d\n" % len(tags))
    for k in (0, len(tags) // 2, len(tags) - 1):
        f.write("node %d %.17g %.17g\n" % (tags[k], coords[3 * k], coords[3 * k + 1]))
    for dim, ptag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, ptag) or "-"
        counts = {}
        for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            types, etags, _ = gmsh.model.mesh.getElements(dim, ent)
            for t, e in zip(types, etags):
                counts[t] = counts.get(t, 0) + len(e)
        f.write("group %d %d %s %s\n" % (dim, ptag, name.replace(" ", "_"),
                " ".join("%d:%d" % kv for kv in sorted(counts.items()))))
gmsh.finalize()
