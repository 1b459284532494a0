//! A reader of Gmsh meshes (MSH 4.1 and 2.2, ASCII), with errors that name the line.
//!
//! The reader returns the mesh as the file writes it — node and element tags, the element
//! types a 2D plane model uses (points, 2-node lines, 3-node triangles, 4-node quadrangles),
//! and the physical groups with their names — and checks what the file itself can get wrong:
//! sections that end early or do not end, counts and tags that disagree with their headers,
//! elements on nodes that are not defined, element types a 2D linear model cannot use (second
//! order, 3D), nodes off the plane `z = 0`. Turning the mesh into a finite-element model
//! (materials of groups, orientation and shape of elements, sets and surfaces) is the model
//! builder's job.
//!
//! The file is read as a stream of words ([`crate::scan`]): a mesh of a million elements is
//! never held as text.

use std::collections::HashMap;
use std::path::Path;

use crate::error::{InputError, InputErrorKind, Pos};
use crate::scan::{Scan, Scanner, Source};

/// The MSH format versions read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MshVersion {
    /// MSH 2.2 ASCII (physical and elementary tags on each element).
    V2_2,
    /// MSH 4.1 ASCII (entities with their physical tags; nodes and elements in entity blocks).
    V4_1,
}

/// A node of the mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MshNode {
    /// The node's tag in the file (≥ 1).
    pub tag: usize,
    /// Its coordinates (the file's `z` is 0 up to round-off).
    pub xy: [f64; 2],
    /// The line where its coordinates are written.
    pub line: usize,
}

/// The element types a 2D linear model uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MshElementType {
    /// A point (type 15): sets only.
    Point,
    /// A 2-node line (type 1): sets, surfaces, or frames.
    Line,
    /// A 3-node triangle (type 2).
    Triangle,
    /// A 4-node quadrangle (type 3).
    Quadrangle,
}

impl MshElementType {
    /// Gmsh's number of the type.
    pub fn gmsh_type(self) -> u32 {
        match self {
            MshElementType::Point => 15,
            MshElementType::Line => 1,
            MshElementType::Triangle => 2,
            MshElementType::Quadrangle => 3,
        }
    }

    /// Nodes per element.
    pub fn nodes(self) -> usize {
        match self {
            MshElementType::Point => 1,
            MshElementType::Line => 2,
            MshElementType::Triangle => 3,
            MshElementType::Quadrangle => 4,
        }
    }

    /// The dimension of the element.
    pub fn dimension(self) -> usize {
        match self {
            MshElementType::Point => 0,
            MshElementType::Line => 1,
            MshElementType::Triangle | MshElementType::Quadrangle => 2,
        }
    }

    fn of(t: u32) -> Result<Self, String> {
        Ok(match t {
            15 => MshElementType::Point,
            1 => MshElementType::Line,
            2 => MshElementType::Triangle,
            3 => MshElementType::Quadrangle,
            _ => {
                let what = match t {
                    8 => "the 3-node second-order line",
                    9 => "the 6-node second-order triangle",
                    10 => "the 9-node second-order quadrangle",
                    16 => "the 8-node second-order quadrangle",
                    4 => "the 4-node tetrahedron (3D)",
                    5 => "the 8-node hexahedron (3D)",
                    6 => "the 6-node prism (3D)",
                    7 => "the 5-node pyramid (3D)",
                    11 => "the 10-node second-order tetrahedron (3D)",
                    12 | 17 => "a second-order hexahedron (3D)",
                    13 | 18 => "a second-order prism (3D)",
                    14 | 19 => "a second-order pyramid (3D)",
                    20..=31 => "a higher-order element",
                    _ => "a type this reader does not know",
                };
                return Err(format!(
                    "element type {t} is {what}: a 2D model takes points (15), 2-node lines (1), \
                     3-node triangles (2) and 4-node quadrangles (3) — mesh with first-order \
                     elements (Gmsh: Mesh.ElementOrder = 1) in 2D"
                ));
            }
        })
    }
}

/// An element of the mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MshElement {
    /// The element's tag in the file.
    pub tag: usize,
    /// Its type.
    pub kind: MshElementType,
    /// Its nodes' tags, in the file's order.
    pub nodes: Vec<usize>,
    /// The tag of the geometric entity (curve, surface, …) it belongs to.
    pub entity: usize,
    /// The physical groups it belongs to (tags of groups of the element's dimension).
    pub physical: Vec<usize>,
    /// The line where it is written.
    pub line: usize,
}

/// A physical group: a named (or numbered) set of entities of one dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicalGroup {
    /// Its dimension: 0 points, 1 curves, 2 surfaces.
    pub dimension: usize,
    /// Its tag.
    pub tag: usize,
    /// Its name, when `$PhysicalNames` gives one.
    pub name: Option<String>,
    /// The line of its name.
    pub line: Option<usize>,
}

impl PhysicalGroup {
    /// The name the model file uses for the group: its physical name, or its tag.
    pub fn label(&self) -> String {
        self.name.clone().unwrap_or_else(|| self.tag.to_string())
    }
}

/// A Gmsh mesh as its file writes it.
#[derive(Debug, Clone, PartialEq)]
pub struct GmshMesh {
    /// The format version.
    pub version: MshVersion,
    /// Every node, in the file's order.
    pub nodes: Vec<MshNode>,
    /// Every element of a type a 2D model uses, in the file's order.
    pub elements: Vec<MshElement>,
    /// Every physical group named in `$PhysicalNames` or used by an element, named ones first.
    pub groups: Vec<PhysicalGroup>,
}

impl GmshMesh {
    /// The group called `label` (its name, or its tag written as a number), if any.
    pub fn group(&self, label: &str) -> Option<&PhysicalGroup> {
        self.groups
            .iter()
            .find(|g| g.name.as_deref() == Some(label))
            .or_else(|| {
                self.groups
                    .iter()
                    .find(|g| g.name.is_none() && g.tag.to_string() == label)
            })
    }

    /// The elements of a group.
    pub fn elements_of<'m>(
        &'m self,
        group: &'m PhysicalGroup,
    ) -> impl Iterator<Item = &'m MshElement> + 'm {
        self.elements.iter().filter(move |e| {
            e.kind.dimension() == group.dimension && e.physical.contains(&group.tag)
        })
    }
}

/// Reads a Gmsh mesh file (MSH 4.1 or 2.2, ASCII).
///
/// Every problem is an [`InputError`] naming the file and the line: a section that ends early,
/// counts or tags that disagree with the section's header, a node or element tag given twice,
/// an element on a node the file does not define, an element type a 2D first-order model cannot
/// use, a node off the plane `z = 0`, a binary file.
pub fn read_gmsh(path: &Path) -> Result<GmshMesh, InputError> {
    parse_msh(path, Source::File(path))
}

/// Where a section started (for "the file ends inside" messages).
struct Section {
    name: String,
    line: usize,
}

struct Reader<'a> {
    path: &'a Path,
    s: Scanner<'a>,
    version: MshVersion,
    /// Physical tags of each (dimension, entity) — MSH 4.1's `$Entities`.
    entity_groups: HashMap<(usize, usize), Vec<usize>>,
    nodes: Vec<MshNode>,
    elements: Vec<MshElement>,
    named: Vec<PhysicalGroup>,
    /// The node farthest from the plane z = 0: its `z`, where it is written, its tag.
    largest_z: Option<(f64, Pos, usize)>,
}

fn syntax(path: &Path, pos: Option<Pos>, msg: String) -> Box<InputError> {
    Box::new(InputError::at(path, pos, InputErrorKind::Syntax, msg))
}

impl<'a> Reader<'a> {
    fn err(&self, pos: Option<Pos>, kind: InputErrorKind, msg: String) -> Box<InputError> {
        Box::new(InputError::at(self.path, pos, kind, msg))
    }

    /// The next word, which must exist inside `section`.
    fn word(&mut self, section: &Section, what: &str) -> Scan<(String, Pos)> {
        let path = self.path;
        let last = self.s.last();
        match self.s.next_word()? {
            Some(w) => Ok((w.text.to_string(), w.pos)),
            None => Err(syntax(
                path,
                last,
                format!(
                    "the file ends inside the section {} that starts on line {}, before {what} (truncated file?)",
                    section.name, section.line
                ),
            )),
        }
    }

    /// A whole number ≥ 0.
    fn count(&mut self, section: &Section, what: &str) -> Scan<(usize, Pos)> {
        let path = self.path;
        let last = self.s.last();
        let Some(w) = self.s.next_word()? else {
            return Err(syntax(
                path,
                last,
                format!(
                    "the file ends inside the section {} that starts on line {}, before {what} (truncated file?)",
                    section.name, section.line
                ),
            ));
        };
        let pos = w.pos;
        match w.text.parse::<usize>() {
            Ok(v) => Ok((v, pos)),
            Err(_) => Err(syntax(
                path,
                Some(pos),
                format!("expected {what} (a whole number ≥ 0), found `{}`", w.text),
            )),
        }
    }

    /// A tag (a whole number ≥ 1).
    fn tag(&mut self, section: &Section, what: &str) -> Scan<(usize, Pos)> {
        let (v, pos) = self.count(section, what)?;
        if v == 0 {
            return Err(self.err(
                Some(pos),
                InputErrorKind::Value,
                format!("{what} is 0: Gmsh's tags start at 1"),
            ));
        }
        Ok((v, pos))
    }

    /// A finite number.
    fn number(&mut self, section: &Section, what: &str) -> Scan<(f64, Pos)> {
        let (text, pos) = self.word(section, what)?;
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok((v, pos)),
            Ok(_) => Err(self.err(
                Some(pos),
                InputErrorKind::Value,
                format!("{what} `{text}` is not a finite number"),
            )),
            Err(_) => Err(syntax(
                self.path,
                Some(pos),
                format!("expected {what} (a number), found `{text}`"),
            )),
        }
    }

    /// The end marker of `section`.
    fn end(&mut self, section: &Section) -> Scan<()> {
        let want = format!("$End{}", &section.name[1..]);
        let (w, pos) = self.word(section, &format!("`{want}`"))?;
        if w != want {
            return Err(syntax(
                self.path,
                Some(pos),
                format!(
                    "expected `{want}` to close the section that starts on line {}, found `{w}` (a count in the section's header disagrees with its content?)",
                    section.line
                ),
            ));
        }
        Ok(())
    }

    fn physical_names(&mut self, sec: &Section) -> Scan<()> {
        let (n, _) = self.count(sec, "the number of physical names")?;
        for _ in 0..n {
            let (dimension, dpos) = self.count(sec, "the dimension of a physical group")?;
            if dimension > 3 {
                return Err(self.err(
                    Some(dpos),
                    InputErrorKind::Value,
                    format!(
                        "the dimension of a physical group is {dimension}: expected 0, 1, 2 or 3"
                    ),
                ));
            }
            let (tag, _) = self.tag(sec, "the tag of a physical group")?;
            let Some((rest, pos)) = self.s.rest_of_line()? else {
                return Err(syntax(
                    self.path,
                    self.s.last(),
                    "expected the group's name in double quotes after its dimension and tag".into(),
                ));
            };
            let name = rest
                .strip_prefix('"')
                .and_then(|r| r.strip_suffix('"'))
                .filter(|n| !n.contains('"'));
            let Some(name) = name else {
                return Err(syntax(
                    self.path,
                    Some(pos),
                    format!("expected the group's name in double quotes, found `{rest}`"),
                ));
            };
            if self
                .named
                .iter()
                .any(|g| g.dimension == dimension && g.tag == tag)
            {
                return Err(self.err(
                    Some(pos),
                    InputErrorKind::Invalid,
                    format!(
                        "the physical group of dimension {dimension} and tag {tag} is named twice"
                    ),
                ));
            }
            self.named.push(PhysicalGroup {
                dimension,
                tag,
                name: Some(name.to_string()),
                line: Some(pos.line),
            });
        }
        self.end(sec)
    }

    /// MSH 4.1 `$Entities`: the physical tags of each point, curve, surface and volume.
    fn entities(&mut self, sec: &Section) -> Scan<()> {
        let mut counts = [0usize; 4];
        for (d, c) in counts.iter_mut().enumerate() {
            *c = self
                .count(sec, &format!("the number of entities of dimension {d}"))?
                .0;
        }
        for (dim, &count) in counts.iter().enumerate() {
            for _ in 0..count {
                let (tag, _) = self.count(sec, "an entity's tag")?;
                // Points: x y z; others: the bounding box (6 numbers).
                let coords = if dim == 0 { 3 } else { 6 };
                for _ in 0..coords {
                    self.number(sec, "an entity's coordinate")?;
                }
                let (n, _) = self.count(sec, "the number of an entity's physical tags")?;
                let mut tags = Vec::with_capacity(n.min(64));
                for _ in 0..n {
                    // Physical tags may be negative (an orientation); the group is its absolute value.
                    let (t, pos) = self.word(sec, "a physical tag")?;
                    let v = t.parse::<i64>().ok().filter(|v| *v != 0).ok_or_else(|| {
                        syntax(
                            self.path,
                            Some(pos),
                            format!("expected a physical tag (a whole number ≠ 0), found `{t}`"),
                        )
                    })?;
                    tags.push(v.unsigned_abs() as usize);
                }
                if dim > 0 {
                    let (b, _) = self.count(sec, "the number of an entity's bounding entities")?;
                    for _ in 0..b {
                        self.word(sec, "a bounding entity's tag")?;
                    }
                }
                self.entity_groups.insert((dim, tag), tags);
            }
        }
        self.end(sec)
    }

    /// The mesh lies in the plane z = 0 up to the round-off of its coordinates: every `|z|`
    /// within 1e-9 of the mesh's extent in x and y (not of the node's own coordinates: a node
    /// near the origin has the same round-off as the others).
    fn check_plane(&self) -> Scan<()> {
        let Some((z, zpos, tag)) = self.largest_z else {
            return Ok(());
        };
        let xy: Vec<[f64; 2]> = self.nodes.iter().map(|n| n.xy).collect();
        if z.abs() > unilateral_fem::mesh::coincidence_tolerance(&xy) {
            return Err(self.err(
                Some(zpos),
                InputErrorKind::Unsupported,
                format!("node {tag} has z = {z}: a 2D model needs a mesh in the plane z = 0"),
            ));
        }
        Ok(())
    }

    /// One node's coordinates; the node with the largest `|z|` is kept for [`Reader::check_plane`].
    fn coordinates(&mut self, sec: &Section, tag: usize) -> Scan<MshNode> {
        let (x, pos) = self.number(sec, "a node's x")?;
        let (y, _) = self.number(sec, "a node's y")?;
        let (z, zpos) = self.number(sec, "a node's z")?;
        if z != 0.0 && self.largest_z.is_none_or(|(zz, ..)| z.abs() > zz.abs()) {
            self.largest_z = Some((z, zpos, tag));
        }
        Ok(MshNode {
            tag,
            xy: [x, y],
            line: pos.line,
        })
    }

    fn nodes_v4(&mut self, sec: &Section) -> Scan<()> {
        let (blocks, _) = self.count(sec, "the number of node blocks")?;
        let (total, tpos) = self.count(sec, "the number of nodes")?;
        let (min_tag, _) = self.count(sec, "the smallest node tag")?;
        let (max_tag, _) = self.count(sec, "the largest node tag")?;
        self.nodes
            .reserve(total.min(self.s.remaining_bytes() as usize / 8));
        let mut tags = Vec::new();
        for _ in 0..blocks {
            let (dim, _) = self.count(sec, "a node block's entity dimension")?;
            self.count(sec, "a node block's entity tag")?;
            let (parametric, ppos) = self.count(sec, "a node block's parametric flag (0 or 1)")?;
            if parametric > 1 {
                return Err(self.err(
                    Some(ppos),
                    InputErrorKind::Value,
                    format!("the parametric flag is {parametric}: expected 0 or 1"),
                ));
            }
            let (n, npos) = self.count(sec, "the number of nodes in the block")?;
            if n > total.saturating_sub(self.nodes.len()) {
                return Err(self.err(
                    Some(npos),
                    InputErrorKind::Size,
                    format!(
                        "this block has {n} nodes, more than the {total} the section's header (line {}) declares in all",
                        tpos.line
                    ),
                ));
            }
            tags.clear();
            for _ in 0..n {
                let (t, pos) = self.tag(sec, "a node tag")?;
                if t < min_tag || t > max_tag {
                    return Err(self.err(
                        Some(pos),
                        InputErrorKind::Value,
                        format!(
                            "node tag {t} is outside the range {min_tag}..={max_tag} of the section's header (line {})",
                            tpos.line
                        ),
                    ));
                }
                tags.push(t);
            }
            let extra = if parametric == 1 && (1..=2).contains(&dim) {
                dim
            } else {
                0
            };
            for &t in &tags {
                let node = self.coordinates(sec, t)?;
                for _ in 0..extra {
                    self.number(sec, "a node's parametric coordinate")?;
                }
                self.nodes.push(node);
            }
        }
        if self.nodes.len() != total {
            let at = self.s.last();
            return Err(self.err(
                at,
                InputErrorKind::Size,
                format!(
                    "the section's header (line {}) declares {total} nodes, its blocks hold {}",
                    tpos.line,
                    self.nodes.len()
                ),
            ));
        }
        self.end(sec)
    }

    fn nodes_v2(&mut self, sec: &Section) -> Scan<()> {
        let (total, _) = self.count(sec, "the number of nodes")?;
        self.nodes
            .reserve(total.min(self.s.remaining_bytes() as usize / 8));
        for _ in 0..total {
            let (t, _) = self.tag(sec, "a node tag")?;
            let node = self.coordinates(sec, t)?;
            self.nodes.push(node);
        }
        self.end(sec)
    }

    /// The element type word at `pos`, checked.
    fn element_type(&self, t: &str, pos: Pos) -> Scan<MshElementType> {
        let n = t.parse::<u32>().map_err(|_| {
            syntax(
                self.path,
                Some(pos),
                format!("expected an element type (a whole number), found `{t}`"),
            )
        })?;
        MshElementType::of(n).map_err(|m| self.err(Some(pos), InputErrorKind::Unsupported, m))
    }

    fn elements_v4(&mut self, sec: &Section) -> Scan<()> {
        let (blocks, _) = self.count(sec, "the number of element blocks")?;
        let (total, tpos) = self.count(sec, "the number of elements")?;
        let (min_tag, _) = self.count(sec, "the smallest element tag")?;
        let (max_tag, _) = self.count(sec, "the largest element tag")?;
        self.elements
            .reserve(total.min(self.s.remaining_bytes() as usize / 8));
        let mut read = 0usize;
        for _ in 0..blocks {
            let (dim, _) = self.count(sec, "an element block's entity dimension")?;
            let (entity, _) = self.count(sec, "an element block's entity tag")?;
            let (t, typos) = self.word(sec, "an element block's element type")?;
            let kind = self.element_type(&t, typos)?;
            if kind.dimension() != dim {
                return Err(self.err(
                    Some(typos),
                    InputErrorKind::Invalid,
                    format!(
                        "the block's entity has dimension {dim}, but its element type {} has dimension {}",
                        kind.gmsh_type(),
                        kind.dimension()
                    ),
                ));
            }
            let physical = self
                .entity_groups
                .get(&(dim, entity))
                .cloned()
                .unwrap_or_default();
            let (n, npos) = self.count(sec, "the number of elements in the block")?;
            if n > total - read {
                return Err(self.err(
                    Some(npos),
                    InputErrorKind::Size,
                    format!(
                        "this block has {n} elements, more than the {total} the section's header (line {}) declares in all",
                        tpos.line
                    ),
                ));
            }
            for _ in 0..n {
                let (tag, pos) = self.tag(sec, "an element tag")?;
                if tag < min_tag || tag > max_tag {
                    return Err(self.err(
                        Some(pos),
                        InputErrorKind::Value,
                        format!(
                            "element tag {tag} is outside the range {min_tag}..={max_tag} of the section's header (line {})",
                            tpos.line
                        ),
                    ));
                }
                let mut nodes = Vec::with_capacity(kind.nodes());
                for _ in 0..kind.nodes() {
                    nodes.push(self.tag(sec, "a node tag of an element")?.0);
                }
                self.elements.push(MshElement {
                    tag,
                    kind,
                    nodes,
                    entity,
                    physical: physical.clone(),
                    line: pos.line,
                });
            }
            read += n;
        }
        if read != total {
            let at = self.s.last();
            return Err(self.err(
                at,
                InputErrorKind::Size,
                format!(
                    "the section's header (line {}) declares {total} elements, its blocks hold {read}",
                    tpos.line
                ),
            ));
        }
        self.end(sec)
    }

    fn elements_v2(&mut self, sec: &Section) -> Scan<()> {
        let (total, _) = self.count(sec, "the number of elements")?;
        self.elements
            .reserve(total.min(self.s.remaining_bytes() as usize / 8));
        for _ in 0..total {
            let (tag, pos) = self.tag(sec, "an element tag")?;
            let (t, typos) = self.word(sec, "an element type")?;
            let kind = self.element_type(&t, typos)?;
            let (ntags, _) = self.count(sec, "the number of an element's tags")?;
            let mut tags = Vec::with_capacity(ntags.min(8));
            for _ in 0..ntags {
                tags.push(self.count(sec, "an element's tag")?.0);
            }
            let mut nodes = Vec::with_capacity(kind.nodes());
            for _ in 0..kind.nodes() {
                nodes.push(self.tag(sec, "a node tag of an element")?.0);
            }
            // The first tag is the physical group (0: none), the second the entity.
            let physical = tags
                .first()
                .copied()
                .filter(|&p| p > 0)
                .into_iter()
                .collect();
            self.elements.push(MshElement {
                tag,
                kind,
                nodes,
                entity: tags.get(1).copied().unwrap_or(0),
                physical,
                line: pos.line,
            });
        }
        self.end(sec)
    }

    /// Skips an unknown section up to its end marker.
    fn skip(&mut self, sec: &Section) -> Scan<()> {
        let want = format!("$End{}", &sec.name[1..]);
        loop {
            let (w, _) = self.word(sec, &format!("`{want}`"))?;
            if w == want {
                return Ok(());
            }
        }
    }

    /// MSH 2.2 writes an element once per physical group it belongs to: one element with all
    /// its groups. Gmsh's own writer gives each copy a tag of its own; a copy has the same type,
    /// geometric entity (given, > 0) and nodes (in order), which two different elements of a
    /// mesher never share. Written with the same tag, a repeat with other nodes is an error.
    fn merge_repeated(&mut self) -> Scan<()> {
        let mut first: HashMap<usize, usize> = HashMap::with_capacity(self.elements.len());
        let mut same: HashMap<(MshElementType, usize, Vec<usize>), usize> =
            HashMap::with_capacity(self.elements.len());
        let mut keep: Vec<MshElement> = Vec::with_capacity(self.elements.len());
        for e in std::mem::take(&mut self.elements) {
            // Only where the file gives the element's entity (Gmsh always does; a hand-written
            // element without tags, entity 0, may share its nodes with another on purpose).
            let key = (e.entity > 0).then(|| (e.kind, e.entity, e.nodes.clone()));
            let copy_of = key.as_ref().and_then(|k| same.get(k)).copied();
            if let (Some(k), false) = (copy_of, first.contains_key(&e.tag)) {
                let f = &mut keep[k];
                for p in e.physical {
                    if !f.physical.contains(&p) {
                        f.physical.push(p);
                    }
                }
                continue;
            }
            match first.get(&e.tag) {
                Some(&k) => {
                    let f: &mut MshElement = &mut keep[k];
                    if f.kind != e.kind || f.nodes != e.nodes {
                        return Err(self.err(
                            Some(Pos { line: e.line, col: 1 }),
                            InputErrorKind::Invalid,
                            format!(
                                "element {} is defined twice, here and on line {}, with other nodes",
                                e.tag, f.line
                            ),
                        ));
                    }
                    for p in e.physical {
                        if !f.physical.contains(&p) {
                            f.physical.push(p);
                        }
                    }
                }
                None => {
                    first.insert(e.tag, keep.len());
                    if let Some(k) = key {
                        same.insert(k, keep.len());
                    }
                    keep.push(e);
                }
            }
        }
        self.elements = keep;
        Ok(())
    }

    /// Tags given twice, elements on undefined nodes.
    fn check(&self) -> Scan<()> {
        let nodes = TagIndex::new(self.nodes.iter().map(|n| (n.tag, n.line)));
        if let Err((tag, line, first)) = nodes {
            return Err(self.err(
                Some(Pos { line, col: 1 }),
                InputErrorKind::Invalid,
                format!("node {tag} is defined twice, here and on line {first}"),
            ));
        }
        let nodes = nodes.unwrap_or_else(|_| TagIndex::Sorted(Vec::new()));
        if let Err((tag, line, first)) =
            TagIndex::new(self.elements.iter().map(|e| (e.tag, e.line)))
        {
            return Err(self.err(
                Some(Pos { line, col: 1 }),
                InputErrorKind::Invalid,
                format!("element {tag} is defined twice, here and on line {first}"),
            ));
        }
        for e in &self.elements {
            if let Some(n) = e.nodes.iter().find(|&&n| !nodes.contains(n)) {
                return Err(self.err(
                    Some(Pos {
                        line: e.line,
                        col: 1,
                    }),
                    InputErrorKind::Invalid,
                    format!(
                        "element {} uses node {n}, which the $Nodes section does not define",
                        e.tag
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// The tags of a section, for finding repeated ones and looking tags up without hashing a
/// million of them: a table indexed by tag when the tags are dense (as Gmsh writes them),
/// else a sorted list.
enum TagIndex {
    /// `line[tag]`: the line of the tag (0: not defined).
    Dense(Vec<usize>),
    /// `(tag, line)` sorted by tag.
    Sorted(Vec<(usize, usize)>),
}

impl TagIndex {
    /// The index of `(tag, line)` pairs, or the first repeated tag: `(tag, line, first line)`.
    fn new(
        items: impl ExactSizeIterator<Item = (usize, usize)> + Clone,
    ) -> Result<Self, (usize, usize, usize)> {
        let n = items.len();
        let max = items.clone().map(|(t, _)| t).max().unwrap_or(0);
        if max <= 2 * n + 1024 {
            let mut line = vec![0; max + 1];
            for (t, l) in items {
                if line[t] != 0 {
                    return Err((t, l, line[t]));
                }
                line[t] = l;
            }
            Ok(TagIndex::Dense(line))
        } else {
            let mut v: Vec<(usize, usize)> = items.collect();
            // A stable sort keeps the file's order among equal tags: the second is the repeat.
            v.sort_by_key(|&(t, _)| t);
            if let Some(w) = v.windows(2).find(|w| w[0].0 == w[1].0) {
                return Err((w[1].0, w[1].1, w[0].1));
            }
            Ok(TagIndex::Sorted(v))
        }
    }

    fn contains(&self, tag: usize) -> bool {
        match self {
            TagIndex::Dense(line) => line.get(tag).is_some_and(|&l| l != 0),
            TagIndex::Sorted(v) => v.binary_search_by_key(&tag, |&(t, _)| t).is_ok(),
        }
    }
}

pub(crate) fn parse_msh(path: &Path, source: Source<'_>) -> Result<GmshMesh, InputError> {
    let mut s = source.scanner(path)?;
    if s.is_empty()? {
        return Err(InputError::at(
            path,
            None,
            InputErrorKind::Syntax,
            "the file is empty: expected a Gmsh mesh starting with `$MeshFormat`",
        ));
    }
    let first = s.next_word()?.map(|w| (w.text == "$MeshFormat", w.pos));
    let Some((true, fpos)) = first else {
        return Err(InputError::at(
            path,
            first.map(|f| f.1),
            InputErrorKind::Syntax,
            "not a Gmsh mesh: the file must start with `$MeshFormat`",
        ));
    };
    let mut r = Reader {
        path,
        s,
        version: MshVersion::V4_1,
        entity_groups: HashMap::new(),
        nodes: Vec::new(),
        elements: Vec::new(),
        named: Vec::new(),
        largest_z: None,
    };
    let sec = Section {
        name: "$MeshFormat".into(),
        line: fpos.line,
    };
    let (v, vpos) = r.word(&sec, "the format version")?;
    r.version = match v.as_str() {
        "4.1" => MshVersion::V4_1,
        "2.2" => MshVersion::V2_2,
        _ => {
            return Err(*r.err(
                Some(vpos),
                InputErrorKind::Unsupported,
                format!(
                    "MSH version {v} is not read: save the mesh as MSH 4.1 or 2.2 ASCII (Gmsh: Mesh.MshFileVersion = 4.1)"
                ),
            ))
        }
    };
    let (file_type, tpos) = r.count(&sec, "the file type (0 for ASCII)")?;
    if file_type != 0 {
        return Err(*r.err(
            Some(tpos),
            InputErrorKind::Unsupported,
            "this is a binary MSH file: save the mesh as ASCII (Gmsh: Mesh.Binary = 0)".into(),
        ));
    }
    r.count(&sec, "the size of a floating-point number")?;
    r.end(&sec)?;
    let mut seen: Vec<String> = Vec::new();
    loop {
        let path = r.path;
        let Some(w) = r.s.next_word()? else { break };
        let (name, pos) = (w.text.to_string(), w.pos);
        if !name.starts_with('$') || name.starts_with("$End") {
            return Err(*syntax(
                path,
                Some(pos),
                format!(
                    "expected the start of a section (`$Nodes`, `$Elements`, …), found `{name}`"
                ),
            ));
        }
        let sec = Section {
            name: name.clone(),
            line: pos.line,
        };
        let known = matches!(
            name.as_str(),
            "$PhysicalNames" | "$Entities" | "$Nodes" | "$Elements"
        );
        if known && seen.contains(&name) {
            return Err(*r.err(
                Some(pos),
                InputErrorKind::Invalid,
                format!("a second {name} section: a mesh file has one"),
            ));
        }
        match (name.as_str(), r.version) {
            ("$PhysicalNames", _) => r.physical_names(&sec)?,
            ("$Entities", MshVersion::V4_1) => r.entities(&sec)?,
            ("$Nodes", MshVersion::V4_1) => r.nodes_v4(&sec)?,
            ("$Nodes", MshVersion::V2_2) => r.nodes_v2(&sec)?,
            // Without `$Entities` the elements have no physical groups: allowed.
            ("$Elements", MshVersion::V4_1) => r.elements_v4(&sec)?,
            ("$Elements", MshVersion::V2_2) => r.elements_v2(&sec)?,
            ("$PartitionedEntities", _) => {
                return Err(*r.err(
                    Some(pos),
                    InputErrorKind::Unsupported,
                    "a partitioned mesh is not read: save it unpartitioned (Gmsh: Mesh.PartitionSplitMeshFiles = 0, no partitions)".into(),
                ))
            }
            _ => r.skip(&sec)?,
        }
        seen.push(name);
    }
    if !seen.iter().any(|s| s == "$Nodes") || !seen.iter().any(|s| s == "$Elements") {
        return Err(InputError::at(
            path,
            r.s.last(),
            InputErrorKind::Syntax,
            "the mesh has no $Nodes or no $Elements section (truncated file?)",
        ));
    }
    r.check_plane()?;
    if r.version == MshVersion::V2_2 {
        r.merge_repeated()?;
    }
    r.check()?;
    // The groups: the named ones, then those elements use without a name.
    let mut groups = r.named;
    for e in &r.elements {
        for &p in &e.physical {
            let d = e.kind.dimension();
            if !groups.iter().any(|g| g.dimension == d && g.tag == p) {
                groups.push(PhysicalGroup {
                    dimension: d,
                    tag: p,
                    name: None,
                    line: None,
                });
            }
        }
    }
    Ok(GmshMesh {
        version: r.version,
        nodes: r.nodes,
        elements: r.elements,
        groups,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<GmshMesh, InputError> {
        parse_msh(Path::new("m.msh"), Source::Text(s))
    }

    /// Two triangles on the unit square with a named bottom edge, written by hand in MSH 4.1 as
    /// Gmsh writes it (the reference is the text itself: tags, coordinates, groups).
    const SQUARE_41: &str = r#"$MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
2
1 1 "bottom"
2 2 "soil body"
$EndPhysicalNames
$Entities
0 1 1 0
1 0 0 0 1 0 0 1 1 2 1 2
1 0 0 0 1 1 0 1 2 4 1 2 3 4
$EndEntities
$Nodes
2 4 1 4
1 1 0 2
1
2
0 0 0
1 0 0
2 1 0 2
3
4
1 1 0
0 1 0
$EndNodes
$Elements
2 3 1 3
1 1 1 1
1 1 2
2 1 2 2
2 1 2 3
3 1 3 4
$EndElements
"#;

    #[test]
    fn msh41_nodes_elements_groups() {
        let m = p(SQUARE_41).unwrap();
        assert_eq!(m.version, MshVersion::V4_1);
        let tags: Vec<usize> = m.nodes.iter().map(|n| n.tag).collect();
        assert_eq!(tags, [1, 2, 3, 4]);
        assert_eq!(m.nodes[2].xy, [1.0, 1.0]);
        assert_eq!(m.nodes[2].line, 24);
        assert_eq!(m.elements.len(), 3);
        assert_eq!(m.elements[0].kind, MshElementType::Line);
        assert_eq!(m.elements[0].physical, [1]);
        assert_eq!(m.elements[2].nodes, [1, 3, 4]);
        assert_eq!(m.elements[2].line, 33);
        let soil = m.group("soil body").unwrap();
        assert_eq!((soil.dimension, soil.tag), (2, 2));
        assert_eq!(m.elements_of(soil).count(), 2);
        assert!(m.group("nothing").is_none());
    }

    #[test]
    fn msh22_with_unnamed_group() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 2 0 0\n5 0 3 0\n$EndNodes\n$Elements\n2\n1 2 2 7 1 1 2 5\n2 1 2 9 3 1 2\n$EndElements\n";
        let m = p(text).unwrap();
        assert_eq!(m.version, MshVersion::V2_2);
        assert_eq!(m.nodes[2].tag, 5);
        assert_eq!(m.elements[0].kind, MshElementType::Triangle);
        assert_eq!(m.elements[0].nodes, [1, 2, 5]);
        assert_eq!(m.elements[0].physical, [7]);
        assert_eq!(m.elements[0].entity, 1);
        assert_eq!(m.group("7").unwrap().dimension, 2);
        assert_eq!(m.group("9").unwrap().dimension, 1);
    }

    /// An element of two groups written twice: one element with both groups. Gmsh's 2.2 writer
    /// (4.x, a surface in two physical groups) gives each copy a tag of its own —
    /// `33 2 2 1 1 81 83 101` and `34 2 2 5 1 81 83 101` in a file a review made with Gmsh, whose
    /// body came out twice as stiff when read as two elements; a writer may also repeat the tag.
    #[test]
    fn msh22_element_in_two_groups_is_one_element() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n$Elements\n2\n4 1 2 3 1 1 2\n4 1 2 5 1 1 2\n$EndElements\n";
        let m = p(text).unwrap();
        assert_eq!(m.elements.len(), 1);
        assert_eq!(m.elements[0].physical, [3, 5]);
        let gmsh = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n81 0 0 0\n83 1 0 0\n101 0 1 0\n$EndNodes\n$Elements\n3\n33 2 2 1 1 81 83 101\n34 2 2 5 1 81 83 101\n35 2 2 5 2 81 83 101\n$EndElements\n";
        let m = p(gmsh).unwrap();
        // the copies in entity 1 are one element of groups 1 and 5; the same nodes in another
        // entity (2) are an element of their own
        assert_eq!(m.elements.len(), 2);
        assert_eq!(
            (m.elements[0].tag, &m.elements[0].physical[..]),
            (33, &[1, 5][..])
        );
        assert_eq!((m.elements[1].tag, m.elements[1].entity), (35, 2));
        // without tags (entity 0) two elements on the same nodes are two elements
        let bare = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n$Elements\n2\n1 1 0 1 2\n2 1 0 1 2\n$EndElements\n";
        assert_eq!(p(bare).unwrap().elements.len(), 2);
        let bad = text.replace("4 1 2 5 1 1 2", "4 1 2 5 1 2 1");
        let e = p(&bad).unwrap_err();
        assert!(e.message.contains("with other nodes"), "{e}");
        assert_eq!(e.location.line, Some(12));
    }

    /// Sparse tags (looked up in a sorted list, not a table): found, missing and repeated.
    #[test]
    fn sparse_tags() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n5 0 0 0\n9000000 1 0 0\n$EndNodes\n$Elements\n1\n7000000 1 2 3 1 5 9000000\n$EndElements\n";
        assert_eq!(p(text).unwrap().elements[0].nodes, [5, 9_000_000]);
        let e = p(&text.replace("1 5 9000000", "1 5 8999999")).unwrap_err();
        assert!(e.message.contains("uses node 8999999"), "{e}");
        let e = p(&text.replace("5 0 0 0", "9000000 0 0 0")).unwrap_err();
        assert!(
            e.message
                .contains("node 9000000 is defined twice, here and on line 6"),
            "{e}"
        );
        assert_eq!(e.location.line, Some(7));
    }

    #[test]
    fn unknown_sections_are_skipped() {
        let text = SQUARE_41.replace(
            "$Nodes\n",
            "$Comments\nwritten by hand $Nodes-like words\n$EndComments\n$Nodes\n",
        );
        assert_eq!(p(&text).unwrap().nodes.len(), 4);
    }

    /// `z` is judged against the mesh's extent (1 here), not the node's own coordinates: the
    /// node at the origin with z = 1e-17 is in the plane as much as the others (it was refused,
    /// 1e-17 > 1e-9·0); z = 2e-9 is off it wherever the node is.
    #[test]
    fn z_round_off_is_judged_against_the_meshs_extent() {
        let at_origin = SQUARE_41.replace("0 0 0\n1 0 0\n", "0 0 1e-17\n1 0 1e-17\n");
        assert_ne!(at_origin, SQUARE_41);
        let m = p(&at_origin).unwrap();
        assert_eq!(m.nodes[0].xy, [0.0, 0.0]);
        let off = SQUARE_41.replace("0 0 0\n1 0 0\n", "0 0 2e-9\n1 0 0\n");
        let e = p(&off).unwrap_err();
        assert!(e.message.contains("node 1 has z = 0.000000002"), "{e}");
        assert_eq!(e.location.line, Some(19), "{e}");
    }

    /// Each malformed file: the message names the problem and the line (counted by hand).
    #[test]
    fn malformed_files_name_the_line() {
        let cases: Vec<(String, &str, Option<usize>)> = vec![
            ("".into(), "empty", None),
            ("$Nodes\n".into(), "must start with `$MeshFormat`", Some(1)),
            (
                SQUARE_41.replace("4.1 0 8", "3.0 0 8"),
                "version 3.0",
                Some(2),
            ),
            (SQUARE_41.replace("4.1 0 8", "4.1 1 8"), "binary", Some(2)),
            (
                SQUARE_41[..SQUARE_41.find("3\n4\n").unwrap()].to_string(),
                "ends inside the section $Nodes that starts on line 14",
                Some(21),
            ),
            (
                SQUARE_41.replace("2 1 2 2\n", "2 1 9 2\n"),
                "6-node second-order triangle",
                Some(31),
            ),
            (
                SQUARE_41.replace("2 1 2 3\n", "2 1 2 7\n"),
                "uses node 7",
                Some(32),
            ),
            (
                SQUARE_41.replace("3 1 3 4\n", "2 1 3 4\n"),
                "element 2 is defined twice, here and on line 32",
                Some(33),
            ),
            (
                SQUARE_41.replace("2 4 1 4\n", "2 4 1 3\n"),
                "node tag 4 is outside the range 1..=3",
                Some(23),
            ),
            (
                SQUARE_41.replace("0 1 0\n$EndNodes", "0 1 0.5\n$EndNodes"),
                "z = 0.5",
                Some(25),
            ),
            (
                SQUARE_41.replace("2 3 1 3\n", "2 4 1 3\n"),
                "declares 4 elements, its blocks hold 3",
                Some(33),
            ),
            (
                SQUARE_41.replace("2 2 \"soil body\"", "2 2 soil"),
                "in double quotes",
                Some(7),
            ),
            (
                SQUARE_41.replace("1 0 0\n2 1 0 2", "1 x 0\n2 1 0 2"),
                "found `x`",
                Some(20),
            ),
            (
                SQUARE_41.replace("$EndElements\n", ""),
                "before `$EndElements`",
                Some(33),
            ),
        ];
        for (text, frag, line) in cases {
            let Err(e) = p(&text) else {
                panic!("no error for:\n{text}")
            };
            assert!(e.message.contains(frag), "{frag}: {e}");
            assert_eq!(e.location.line, line, "{frag}: {e}");
        }
    }
}
