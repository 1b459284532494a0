//! `[[blocks]]`: structured grids of plane elements.

use super::*;

impl Builder<'_> {
    pub(super) fn blocks(&mut self, top: &Table) -> Result<(), InputError> {
        for t in table_array(top, "blocks")? {
            t.check_keys(&[
                "name",
                "origin",
                "width",
                "height",
                "nx",
                "ny",
                "material",
                "analysis",
                "formulation",
                "connect_to",
            ])?;
            let name = self.object_name(&t, "block")?;
            let origin = vec2(
                self.doc,
                t.require("origin", "the lower-left corner [x, y]")?,
                &t.child("origin"),
            )?;
            let w = positive(&t, "width", "the width")?;
            let h = positive(&t, "height", "the height")?;
            let nx = self.doc.positive_integer(
                t.require("nx", "the number of divisions along x")?,
                &t.child("nx"),
            )?;
            let ny = self.doc.positive_integer(
                t.require("ny", "the number of divisions along y")?,
                &t.child("ny"),
            )?;
            if (nx + 1).saturating_mul(ny + 1) > MAX_GENERATED {
                return Err(self.err(
                    t.pos,
                    &t.child("nx"),
                    InputErrorKind::Value,
                    format!("{nx} × {ny} divisions is too many (at most {MAX_GENERATED} nodes per block)"),
                ));
            }
            let material = self.material(&t)?;
            let (analysis, formulation) = self.plane_options(&t)?;
            let rect = [origin[0], origin[1], origin[0] + w, origin[1] + h];
            for (other, r, p) in &self.blocks {
                let ox = rect[2].min(r[2]) - rect[0].max(r[0]);
                let oy = rect[3].min(r[3]) - rect[1].max(r[1]);
                let scale = w.min(h).min(r[2] - r[0]).min(r[3] - r[1]);
                if ox > 1e-9 * scale && oy > 1e-9 * scale {
                    return Err(self.invalid_at(&name, format!(
                            "block `{}` overlaps block `{other}`{}: separate bodies must not overlap (blocks may touch along an edge)",
                            name.name,
                            Self::line_of(*p)
                        ),
                    ));
                }
            }
            self.blocks.push((name.name.clone(), rect, name.pos));
            let n = &name.name;
            let geometry = BlockGrid::new(origin, w, h, nx, ny);
            // proto node of each grid node, in the grid's index order
            let mut grid = vec![0usize; geometry.points().len()];
            for j in 0..=ny {
                for i in 0..=nx {
                    let k = geometry.index(i, j);
                    let nm = format!("{n}.{i}.{j}");
                    self.check_new_name(&nm, name.pos, &name.key)?;
                    grid[k] = self.new_proto(geometry.points()[k], nm, name.pos);
                }
            }
            let protos = |nodes: Vec<usize>| nodes.into_iter().map(|k| grid[k]).collect::<Vec<_>>();
            let mut sets = vec![("nodes", grid.clone())];
            sets.extend(
                geometry
                    .boundary()
                    .into_iter()
                    .map(|(edge, nodes)| (edge, protos(nodes))),
            );
            for (s, nodes) in sets {
                self.add_set(format!("{n}.{s}"), nodes, name.pos, &name.key)?;
            }
            let mut elems = Vec::with_capacity(nx * ny);
            for (c, cell) in geometry.cells().into_iter().enumerate() {
                let (i, j) = (c % nx, c / nx);
                let e = self.add_element(Pending {
                    kind: Kind::Plane(material, analysis, formulation),
                    nodes: cell.iter().map(|&k| grid[k]).collect(),
                    name: format!("{n}.{i}.{j}"),
                    pos: name.pos,
                    key: t.key.clone(),
                })?;
                elems.push(e);
            }
            self.element_sets.insert(n.clone(), elems);
            if let Some(c) = t.get("connect_to") {
                let targets = refs(self.doc, c, &t.child("connect_to"))?;
                self.connects.push((grid, targets));
            }
        }
        Ok(())
    }
}
