//! ParaView output: the mesh and the contact pairs as VTK XML unstructured grids, one pair of
//! files per state of the load path, and a `.pvd` collection to step through them. The data
//! arrays are text, raw appended binary, or appended binary compressed by zlib or LZ4
//! ([`VtkFormat`]); the files hold the same arrays with the same values in every format.
//!
//! Files written into the output directory (`NNN` = 0-based snapshot number, zero-padded):
//!
//! * `mesh_NNN.vtu` — points = nodes (`z = 0`, undeformed), cells = elements in element order
//!   (frames and bars as `VTK_LINE`, quadrilaterals as `VTK_QUAD`, triangles as
//!   `VTK_TRIANGLE`).
//!   Point data: `displacement` (`ux, uy, 0`, for *Warp By Vector*), `rotation` (`rz`),
//!   and, when the model has plane elements, `nodal_stress` (`sxx, syy, txy` extrapolated
//!   from the Gauss points and averaged over the plane elements at the node; 0 at nodes
//!   without one) and `nodal_von_mises`.
//!   Cell data: `kind` (1 frame, 2 bar, 3 quadrilateral, 4 triangle), `material` (0-based number of the distinct
//!   section or plane material, in order of first use), `element` (0-based element index);
//!   when the model has plane elements, `stress` (`sxx, syy, txy` averaged over the 4 Gauss
//!   points, a triangle's constant stress; 0 for lines), `szz` and `von_mises` (of the
//!   averaged stress); when it has frames or bars, `axial_force` (the signed `N` of largest
//!   magnitude along a frame or bar, tension positive), `max_abs_moment` and `max_abs_shear`
//!   (0 for plane elements). An array that the model's kinds of element would leave zero in
//!   every cell or point is not written: a frame model's files hold no stresses (on the
//!   1000-bearing beam of the benchmark, 37 % of each mesh file's bytes).
//! * `pairs_NNN.vtu` — one cell per contact pair, in pair order: a `VTK_VERTEX` at node B for a
//!   pair with the ground, a `VTK_LINE` from A to B for a node-to-node pair. Points `0..m` are
//!   the B nodes of the pairs; the A nodes of node-to-node pairs follow.
//!   Cell data: `state` (0 open, 1 stick, 2 slip+, 3 slip−), `x_n`, `x_t`, `z_n`, `z_t`,
//!   `force` (`x_n·n + x_t·t`, the force on B), `normal`, `tangent`, `friction`, `pair`.
//!   Point data (so that glyphs can be drawn and coloured without filters): the node's
//!   `displacement`, the pair's `force` on that node (`−force` at A), `state`, `x_n`, `x_t`,
//!   `z_n`, `z_t` and `pair`.
//! * `unilateral.pvd` — the collection: for every snapshot, `mesh_NNN.vtu` as part 0 and
//!   `pairs_NNN.vtu` as part 1 (no pairs files when the model has no pairs), `timestep` = the
//!   load parameter `p`.
//!
//! A run into the directory of an earlier one writes its files over the old ones in place
//! (cheaper for the file system than new files renamed over them; a symbolic link, a file with
//! other hard links or a read-only file is replaced instead, as a rename would). The collection
//! is removed before the first frame is written and written after the last, so that a
//! collection names the frames of one run. Files of an earlier run that this run does not
//! write stay in the directory, outside the collection; after a failure, the files this run
//! wrote are removed (with the earlier run's files they had replaced).
//!
//! The snapshots are the start of the path (`p = 0`), the loads of all events of the traced
//! path (when the results there can be recovered, also beyond the target) and the reported
//! solution, sorted by `p` without repeats. Each `.vtu` also carries its load as the field
//! `TimeValue` and the field `reported`: 1 in the two files of the reported solution, 0 in
//! all others (the state the summary and the JSON report, found in ParaView's field data
//! without knowing its load).

use rayon::prelude::*;
use std::borrow::Cow;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

use unilateral_analysis::Analysis;
use unilateral_contact::{PairResult, PairState};
use unilateral_fem::{von_mises, Element, Endpoint, Model, Results};

/// Name of the collection file written by [`write_vtk`].
pub const PVD_FILE: &str = "unilateral.pvd";

/// VTK cell type of a vertex.
const VTK_VERTEX: u8 = 1;
/// VTK cell type of a 2-node line.
const VTK_LINE: u8 = 3;
/// VTK cell type of a 4-node quadrilateral.
const VTK_QUAD: u8 = 9;
const VTK_TRIANGLE: u8 = 5;

/// Writes the mesh, the contact pairs and their results along the load path as VTK XML files
/// into `dir` (created if missing), with a `.pvd` collection ([`PVD_FILE`]) for ParaView;
/// returns the files written, the collection last. See the module documentation for the
/// contents.
///
/// The mesh is the model the analysis was condensed from
/// ([`Condensed::model`](unilateral_fem::Condensed::model)).
pub fn write_vtk(analysis: &Analysis, dir: &Path) -> io::Result<Vec<PathBuf>> {
    write_vtk_with(analysis, dir, VtkFormat::Ascii)
}

/// [`write_vtk`] with the data arrays in the given [`VtkFormat`] (the `.pvd` collection is
/// the same in every format).
pub fn write_vtk_with(
    analysis: &Analysis,
    dir: &Path,
    format: VtkFormat,
) -> io::Result<Vec<PathBuf>> {
    write_frames(analysis, dir, format, VTK_BLOCK, &|_| false)
}

/// [`write_vtk_with`], the frames' pairs read from the path `block` frames at a time; the
/// frames `i` with `lost(i)` are taken as not recovered (for tests: none is, in use).
fn write_frames(
    analysis: &Analysis,
    dir: &Path,
    format: VtkFormat,
    block: usize,
    lost: &(dyn Fn(usize) -> bool + Sync),
) -> io::Result<Vec<PathBuf>> {
    let model = analysis.condensed.model();
    crate::finite::analysis(analysis)?;
    let plan = FramePlan::new(analysis);
    let mesh = MeshGeometry::new(model, format);
    let pairs = PairGeometry::new(model, analysis, format);
    std::fs::create_dir_all(dir)?;
    // The width of the frame numbers as planned: the names the frames are written under; the
    // width of the frames actually made is the files' at the end.
    let planned_width = plan.items().saturating_sub(1).to_string().len().max(3);
    let mut pvd = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n\
         \x20 <Collection>\n",
    );
    // Each frame is recovered, made and written on the thread pool straight into its file (each
    // file's bytes do not depend on the number of threads). The frames' pairs are read from the
    // path a block at a time ([`VTK_BLOCK`] frames), so that a path of thousands of frames holds
    // one block of pairs and a structure per thread, not every frame at once.
    //
    // The files get their final names as planned, so that a run into the directory of an
    // earlier one rewrites the files in place: creating a file and renaming it over the old one
    // cost the file system several times the writing (on the 1000-bearing beam, a fifth of the
    // run's CPU, the writers queued on the directory's lock). Only frames that could not be
    // recovered (their numbers are closed up) or fewer frames than planned (a narrower number)
    // make renames. The collection is removed before the first frame is written and written
    // after the last, so that a collection in the directory names the frames of one run.
    let name_of = |part: usize, i: usize, width: usize| {
        if part == 0 {
            format!("mesh_{i:0width$}.vtu")
        } else {
            format!("pairs_{i:0width$}.vtu")
        }
    };
    let make = |i: usize, snap: &Snapshot| -> io::Result<Option<Vec<PathBuf>>> {
        if lost(i) {
            return Ok(None);
        }
        let recovered;
        let snap = if snap.pending {
            let Ok(r) = analysis.recover_pairs(snap.p, &snap.pairs) else {
                return Ok(None);
            };
            recovered = Snapshot {
                p: snap.p,
                pairs: Cow::Borrowed(&snap.pairs),
                results: Some(Cow::Owned(r)),
                reported: snap.reported,
                pending: false,
            };
            &recovered
        } else {
            snap
        };
        // Both files made (and their numbers checked) before either is written; a file of
        // this frame written before a failure is removed.
        let mut parts = Vec::with_capacity(2);
        // The pairs' points at nodes take the text of the nodes' displacements (ascii).
        let mut node_lines = Vec::new();
        let mesh_body = mesh.vtu(model, snap, Some(&mut node_lines));
        let pairs_body = (pairs.m > 0).then(|| pairs.vtu(snap, (&mesh_body.xml, &node_lines)));
        let name = name_of(0, i, planned_width);
        let file = mesh_body.finish_parts(&name)?;
        mesh.size.note(&file);
        parts.push((name, file));
        if let Some(body) = pairs_body {
            let name = name_of(1, i, planned_width);
            let file = body.finish_parts(&name)?;
            pairs.size.note(&file);
            parts.push((name, file));
        }
        let mut files = Vec::with_capacity(parts.len());
        for (name, file) in &parts {
            match file.write_over(dir, name) {
                Ok(path) => files.push(path),
                Err(e) => {
                    remove_quietly(&files);
                    return Err(e);
                }
            }
        }
        Ok(Some(files))
    };
    match std::fs::remove_file(dir.join(PVD_FILE)) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    let mut made: Vec<(f64, io::Result<Option<Vec<PathBuf>>>)> = Vec::new();
    // The next block's pairs (a product of the contact matrix with the block's breakpoints,
    // on one thread) are formed while the frames of this one are made.
    let mut blocks = plan.blocks(analysis, block);
    let mut next = blocks.next();
    while let Some(block) = next.take() {
        let first = made.len();
        // A frame a task: rayon's splitting by halves otherwise left a run of frames to one
        // thread at the end of a block (a tenth of the 300-bearing beam's frames' time).
        let frames = || {
            made.par_extend(
                block
                    .par_iter()
                    .with_max_len(1)
                    .enumerate()
                    .map(|(j, snap)| (snap.p, make(first + j, snap))),
            );
        };
        next = rayon::join(|| blocks.next(), frames).0;
        if made[first..].iter().any(|(_, r)| r.is_err()) {
            break;
        }
    }
    if made.is_empty() {
        // No state of the path could be recovered: the geometry alone.
        let empty = Snapshot {
            p: 0.0,
            pairs: Cow::Borrowed(&[]),
            results: None,
            reported: false,
            pending: false,
        };
        made.push((0.0, make(0, &empty)));
    }
    if made.iter().any(|(_, r)| r.is_err()) {
        remove_quietly(made.iter().flat_map(|(_, f)| f.iter().flatten().flatten()));
        return Err(made
            .into_iter()
            .find_map(|(_, r)| r.err())
            .expect("one frame failed"));
    }
    let frames = made
        .iter()
        .filter(|(_, r)| matches!(r, Ok(Some(_))))
        .count();
    let width = frames.saturating_sub(1).to_string().len().max(3);
    let mut written = Vec::new();
    let mut k = 0usize;
    // In load order, a frame's number is never above its planned one: renaming in that order
    // never meets a file of this run not yet renamed. Should a rename fail, every file of
    // this run is removed, as after a failed frame.
    let mut frames = made
        .into_iter()
        .filter_map(|(p, files)| files.ok().flatten().map(|f| (p, f)));
    while let Some((p, files)) = frames.next() {
        for (part, file) in files.iter().enumerate() {
            let name = name_of(part, k, width);
            dataset(&mut pvd, p, part, &name);
            let to = dir.join(&name);
            if file != &to {
                if let Err(e) = std::fs::rename(file, &to) {
                    let rest = files[part..].iter().cloned();
                    let later = frames.by_ref().flat_map(|(_, f)| f);
                    remove_quietly(written.iter().cloned().chain(rest).chain(later));
                    return Err(e);
                }
            }
            written.push(to);
        }
        k += 1;
    }
    pvd.push_str("  </Collection>\n</VTKFile>\n");
    check_numbers(PVD_FILE, &pvd)?;
    written.push(write_file(dir, PVD_FILE, pvd.as_bytes())?);
    Ok(written)
}

/// Removes the files of a run that failed (a file already gone is no further failure).
fn remove_quietly<P: AsRef<Path>>(files: impl IntoIterator<Item = P>) {
    for f in files {
        let _ = std::fs::remove_file(f);
    }
}

/// Frames whose pairs are read from the path at once ([`FramePlan::blocks`]).
const VTK_BLOCK: usize = 256;

/// The ends of the blocks of `n` frames read at most `size` at a time: a first block of an
/// eighth of `size` (its product is formed before any frame is made, while the other threads
/// wait; each later one while the frames of the one before are made), then blocks of equal
/// size (within one). Never a lone frame among more: the product of one column is formed by
/// another kernel than that of many, whose sums may differ in their last bits.
fn block_ends(n: usize, size: usize) -> Vec<usize> {
    let size = size.max(2);
    let first = (size / 8).max(2);
    if n <= first + 1 {
        return vec![n];
    }
    let rest = n - first;
    let blocks = rest.div_ceil(size).min(rest / 2);
    let mut ends = vec![first];
    let mut end = first;
    for b in 0..blocks {
        end += rest / blocks + usize::from(b < rest % blocks);
        ends.push(end);
    }
    ends
}

/// [`write_vtk`] for a caller that holds the model apart: `model` must be the model `analysis`
/// was made from; a model whose node, element or pair counts do not match gives an
/// [`io::ErrorKind::InvalidInput`] error. The analysis knows its model: prefer [`write_vtk`].
pub fn write_vtk_for(model: &Model, analysis: &Analysis, dir: &Path) -> io::Result<Vec<PathBuf>> {
    check_match(model, analysis)?;
    write_vtk(analysis, dir)
}

/// Every number of a VTK text is finite: the values of each `DataArray` (written by this
/// module as numbers only) and each `timestep` of the collection. Run on the collection; the
/// `.vtu` files' arrays are checked value by value as they are written ([`Body::note_value`]),
/// which also covers the values derived here (displaced points, von Mises stress, pair
/// forces), which could overflow even when the analysis' own numbers are finite. Reading the
/// numbers back from the text was a fifth of a `--vtk` run.
fn check_numbers(file: &str, text: &str) -> Result<(), crate::NonFiniteOutput> {
    let bad = |what: &str, token: &str| crate::NonFiniteOutput {
        field: format!("{what} in {file}"),
        value: token.parse().unwrap_or(f64::NAN),
    };
    let is_finite = |token: &str| token.parse::<f64>().is_ok_and(f64::is_finite);
    let mut rest = text;
    while let Some(at) = rest.find("<DataArray") {
        rest = &rest[at..];
        let Some(open_end) = rest.find('>') else {
            break;
        };
        let tag = &rest[..open_end];
        if tag.ends_with('/') {
            // An appended array: its values are checked as they are encoded.
            rest = &rest[open_end..];
            continue;
        }
        let name = tag
            .split("Name=\"")
            .nth(1)
            .and_then(|n| n.split('"').next())
            .unwrap_or("a data array");
        let body_end = rest.find("</DataArray>").unwrap_or(rest.len());
        let body = &rest[open_end + 1..body_end.max(open_end + 1)];
        if let Some(token) = body.split_ascii_whitespace().find(|t| !is_finite(t)) {
            return Err(bad(&format!("the data array \"{name}\""), token));
        }
        rest = &rest[body_end..];
    }
    for part in text.split("timestep=\"").skip(1) {
        let token = part.split('"').next().unwrap_or("");
        if !is_finite(token) {
            return Err(bad("a timestep", token));
        }
    }
    Ok(())
}

fn write_file(dir: &Path, name: &str, text: &[u8]) -> io::Result<PathBuf> {
    let path = dir.join(name);
    std::fs::write(&path, text)?;
    Ok(path)
}

fn dataset(pvd: &mut String, p: f64, part: usize, file: &str) {
    pvd.push_str("    <DataSet timestep=\"");
    num_text(pvd, p);
    let _ = writeln!(pvd, "\" group=\"\" part=\"{part}\" file=\"{file}\"/>");
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// The model must be the analysed one: same numbers of pairs, nodes and elements, and the
/// element results on elements of the right kind.
fn check_match(model: &Model, a: &Analysis) -> io::Result<()> {
    if model.pairs().len() != a.condensed.pairs() {
        return Err(invalid(format!(
            "the model has {} contact pairs but the analysis {}: not the analysed model",
            model.pairs().len(),
            a.condensed.pairs()
        )));
    }
    let Some(r) = &a.results else {
        return Ok(());
    };
    let (nodes, elements) = (model.nodes().len(), model.elements().len());
    if r.displacements.len() != nodes || r.nodal_stress.len() != nodes {
        return Err(invalid(format!(
            "the model has {nodes} nodes but the results {}: not the analysed model",
            r.displacements.len()
        )));
    }
    let lines_ok = r.lines.iter().all(|l| {
        matches!(
            model.elements().get(l.element.0),
            Some(Element::Frame { .. } | Element::Bar { .. })
        )
    });
    let planes_ok = r.planes.iter().all(|pl| {
        matches!(
            model.elements().get(pl.element.0),
            Some(Element::Plane { .. } | Element::Triangle { .. })
        )
    });
    if !lines_ok || !planes_ok || r.lines.len() + r.planes.len() != elements {
        return Err(invalid(format!(
            "the model has {elements} elements but the results {} lines and {} plane \
             elements: not the analysed model",
            r.lines.len(),
            r.planes.len()
        )));
    }
    Ok(())
}

/// One state of the load path.
struct Snapshot<'a> {
    p: f64,
    pairs: Cow<'a, [PairResult]>,
    results: Option<Cow<'a, Results>>,
    /// The state at the reported load (the field `reported` = 1 of its files).
    reported: bool,
    /// The structure is still to be recovered from the pairs; a frame whose recovery fails is
    /// left out.
    pending: bool,
}

/// The frames of the animation: the start, every step of the path that changes a pair's state
/// (where recoverable; none for a path traced with the tightening) and the reported solution,
/// sorted by load without repeats. The pairs of the path's frames are read block by block
/// ([`FramePlan::blocks`]).
struct FramePlan<'a> {
    /// (load, breakpoint) of the path's frames: breakpoint k is the point after step k.
    frames: Vec<(f64, usize)>,
    /// The frames' pairs are read from the path's breakpoints (one product a block), not
    /// solved at their loads (a path traced with the tightening shows only the start, the
    /// solution at p = 0 evaluated on the path).
    from_breakpoints: bool,
    /// The reported solution and its place among the frames (before `frames[at]`).
    reported: Option<(f64, &'a Results, usize)>,
}

impl<'a> FramePlan<'a> {
    fn new(a: &'a Analysis) -> Self {
        let same = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(y.abs()).max(1.0);
        let reported = a.p().zip(a.results.as_ref());
        // Frames where the working scheme changes: steps with events, not the pivots that only
        // settle the starting scheme or trade an open pair's friction parts. A path traced with
        // the paper's tightening has its events at loads that depend on c, where the structure
        // without c (the only one recovered) may show no change at all: its animation is the
        // start and the reported state; the physical path is animated by a run with c = 0.
        let tightened = a.solution.tightening > 0.0;
        let bps = &a.solution.path.breakpoints;
        // the settled start: the last breakpoint at p = 0
        let start = bps
            .iter()
            .take_while(|b| same(b.p, 0.0))
            .count()
            .saturating_sub(1);
        let events = a
            .solution
            .steps
            .iter()
            .filter(|s| !tightened && !s.settling && !s.events.is_empty())
            .map(|s| (s.p, s.index));
        let mut frames: Vec<(f64, usize)> = std::iter::once((0.0, start))
            .chain(events)
            .filter(|(p, _)| p.is_finite())
            .filter(|&(p, _)| reported.is_none_or(|(end, _)| !same(p, end)))
            .collect();
        frames.sort_by(|x, y| x.0.total_cmp(&y.0));
        frames.dedup_by(|x, y| same(x.0, y.0));
        // The reported solution takes its place in load order (events beyond the target
        // follow it).
        let reported = reported.map(|(p, r)| (p, r, frames.partition_point(|f| f.0 < p)));
        FramePlan {
            frames,
            from_breakpoints: !tightened && !bps.is_empty(),
            reported,
        }
    }

    /// How many frames are planned (some may prove not to be on the path).
    fn items(&self) -> usize {
        self.frames.len() + usize::from(self.reported.is_some())
    }

    /// The frames in load order, at most `size` planned frames at a time: each block's pairs read
    /// from the path's breakpoints by one product (or, with the tightening, or where the
    /// product leaves the floating-point range although the solution does not, solved at the
    /// frames' loads); the structures are recovered frame by frame as the files are made
    /// ([`Snapshot::pending`]). Frames whose load is not on the path are left out. Where the
    /// product fails, that block alone falls back to solving at its loads (and, where that
    /// fails too, only that block's frames are left out).
    fn blocks(&self, a: &'a Analysis, size: usize) -> impl Iterator<Item = Vec<Snapshot<'a>>> + '_ {
        let n = self.frames.len();
        let at = self.reported.map_or(n + 1, |(_, _, at)| at);
        let mut ends = block_ends(n, size).into_iter();
        let mut start = 0usize;
        let mut reported_done = self.reported.is_none();
        std::iter::from_fn(move || {
            if start >= n && reported_done {
                return None;
            }
            let end = ends.next().unwrap_or(n);
            let part = &self.frames[start..end];
            let loads: Vec<f64> = part.iter().map(|f| f.0).collect();
            let at_loads = || -> Vec<Option<Vec<PairResult>>> {
                a.solution.at_many(&loads).map_or_else(
                    |_| vec![None; loads.len()],
                    |v| v.into_iter().map(|x| x.map(|(pairs, _)| pairs)).collect(),
                )
            };
            let answers: Vec<Option<Vec<PairResult>>> = if part.is_empty() {
                Vec::new()
            } else if self.from_breakpoints {
                let points: Vec<(usize, f64)> = part.iter().map(|&(_, k)| (k, 0.0)).collect();
                // The frames read the pairs by their place: unnamed.
                match a.solution.traced_on_segments_unnamed(&points) {
                    Ok(v) => v.into_iter().map(|x| x.map(|(_, pairs)| pairs)).collect(),
                    Err(_) => at_loads(),
                }
            } else {
                at_loads()
            };
            let mut out = Vec::with_capacity(part.len() + 1);
            for (j, (p, pairs)) in loads.iter().zip(answers).enumerate() {
                if !reported_done && start + j == at {
                    out.push(self.reported_snapshot(a));
                    reported_done = true;
                }
                if let Some(pairs) = pairs {
                    out.push(Snapshot {
                        p: *p,
                        pairs: Cow::Owned(pairs),
                        results: None,
                        reported: false,
                        pending: true,
                    });
                }
            }
            if !reported_done && at >= end && end == n {
                out.push(self.reported_snapshot(a));
                reported_done = true;
            }
            start = end;
            Some(out)
        })
    }

    fn reported_snapshot(&self, a: &'a Analysis) -> Snapshot<'a> {
        let (p, r, _) = self.reported.expect("a reported solution");
        Snapshot {
            p,
            pairs: Cow::Borrowed(&a.solution.pairs),
            results: Some(Cow::Borrowed(r)),
            reported: true,
            pending: false,
        }
    }
}

/// The parts of a mesh file that do not change along the path.
struct MeshGeometry {
    n_points: usize,
    n_cells: usize,
    /// `<Points>` and `<Cells>`.
    grid: Body,
    /// Cell arrays `kind`, `material`, `element`.
    cell_ids: Body,
    /// Which result arrays the model's elements can make non-zero.
    kinds: ElementKinds,
    /// The largest file made so far.
    size: Size,
}

/// The largest sizes of the files of one kind made so far, for the next file's buffers: a
/// frame's buffers are then allocated once, not grown by doubling (copying each file's
/// hundreds of kilobytes several times).
#[derive(Debug, Default)]
struct Size {
    xml: std::sync::atomic::AtomicUsize,
    data: std::sync::atomic::AtomicUsize,
}

impl Size {
    fn reserve(&self, b: &mut Body) {
        use std::sync::atomic::Ordering::Relaxed;
        b.xml.reserve(self.xml.load(Relaxed));
        b.data.reserve(self.data.load(Relaxed));
    }

    fn note(&self, f: &Finished) {
        use std::sync::atomic::Ordering::Relaxed;
        self.xml.fetch_max(f.head.len(), Relaxed);
        self.data.fetch_max(f.data.len(), Relaxed);
    }
}

/// Whether a model has plane elements (quadrilaterals, triangles) and line elements (frames,
/// bars): the stress arrays are written only with the first, the section-force arrays only
/// with the second (each would be zero everywhere otherwise).
#[derive(Debug, Clone, Copy)]
struct ElementKinds {
    plane: bool,
    line: bool,
}

impl ElementKinds {
    fn of(model: &Model) -> Self {
        let is_line = |e: &Element| matches!(e, Element::Frame { .. } | Element::Bar { .. });
        Self {
            plane: model.elements().iter().any(|e| !is_line(e)),
            line: model.elements().iter().any(is_line),
        }
    }
}

impl MeshGeometry {
    fn new(model: &Model, format: VtkFormat) -> Self {
        let mut grid = Body::new(format);
        grid.push_str("      <Points>\n");
        f64_array(
            &mut grid,
            "Points",
            &[],
            model.nodes().iter().map(|&[x, y]| [x, y, 0.0]),
        );
        grid.push_str("      </Points>\n      <Cells>\n");
        let elements = model.elements();
        let mut connectivity = Vec::new();
        let mut offsets = Vec::with_capacity(elements.len());
        let mut types = Vec::with_capacity(elements.len());
        let mut kinds = Vec::with_capacity(elements.len());
        let mut materials = Vec::with_capacity(elements.len());
        let mut seen: HashMap<(u8, Vec<u64>), i64> = HashMap::new();
        for e in elements {
            let (kind, nodes, ty, key): (u8, &[_], u8, Vec<f64>) = match e {
                Element::Frame { nodes, section, .. } => (1, nodes, VTK_LINE, section_key(section)),
                Element::Bar { nodes, section } => (2, nodes, VTK_LINE, section_key(section)),
                Element::Plane {
                    nodes,
                    material: m,
                    analysis,
                    formulation,
                } => {
                    let a = matches!(analysis, unilateral_fem::PlaneAnalysis::PlaneStrain);
                    let f = matches!(formulation, unilateral_fem::PlaneFormulation::QM6);
                    let key = vec![
                        m.e,
                        m.nu,
                        m.thickness,
                        m.alpha,
                        a as u8 as f64,
                        f as u8 as f64,
                    ];
                    (3, nodes, VTK_QUAD, key)
                }
                Element::Triangle {
                    nodes,
                    material: m,
                    analysis,
                } => {
                    let a = matches!(analysis, unilateral_fem::PlaneAnalysis::PlaneStrain);
                    let key = vec![m.e, m.nu, m.thickness, m.alpha, a as u8 as f64];
                    (4, nodes, VTK_TRIANGLE, key)
                }
            };
            connectivity.extend(nodes.iter().map(|n| n.0 as i64));
            offsets.push(connectivity.len() as i64);
            types.push(i64::from(ty));
            kinds.push(i64::from(kind));
            let next = seen.len() as i64;
            let bits = key.iter().map(|v| v.to_bits()).collect();
            materials.push(*seen.entry((kind.min(2), bits)).or_insert(next));
        }
        int_array(&mut grid, "Int64", "connectivity", connectivity);
        int_array(&mut grid, "Int64", "offsets", offsets);
        int_array(&mut grid, "UInt8", "types", types);
        grid.push_str("      </Cells>\n");
        let mut cell_ids = Body::new(format);
        int_array(&mut cell_ids, "Int32", "kind", kinds);
        int_array(&mut cell_ids, "Int32", "material", materials);
        int_array(&mut cell_ids, "Int64", "element", 0..elements.len() as i64);
        Self {
            n_points: model.nodes().len(),
            n_cells: elements.len(),
            grid,
            cell_ids,
            kinds: ElementKinds::of(model),
            size: Size::default(),
        }
    }

    /// The mesh file of `snap`; in ascii, where each node's displacement line starts in its
    /// XML (and where the last ends) into `node_lines`.
    fn vtu(&self, model: &Model, snap: &Snapshot, node_lines: Option<&mut Vec<usize>>) -> Body {
        let mut s = header(
            self.grid.format,
            snap,
            self.n_points,
            self.n_cells,
            &self.size,
        );
        if let Some(r) = snap.results.as_deref() {
            point_results(&mut s, r, self.kinds, node_lines);
        }
        s.append(&self.grid);
        s.push_str("      <CellData Scalars=\"kind\">\n");
        s.append(&self.cell_ids);
        if let Some(r) = snap.results.as_deref() {
            cell_results(&mut s, model, r, self.kinds);
        }
        s.push_str("      </CellData>\n");
        s.push_str(FOOTER);
        s
    }
}

/// `E, A, I, h, α` of a frame or bar section (bars: `I` and `h` do not matter to them, but
/// the same numbers make the same material).
fn section_key(s: &unilateral_fem::FrameSection) -> Vec<f64> {
    vec![s.e, s.area, s.inertia, s.depth, s.alpha]
}

fn point_results(
    s: &mut Body,
    r: &Results,
    kinds: ElementKinds,
    node_lines: Option<&mut Vec<usize>>,
) {
    s.push_str("      <PointData Vectors=\"displacement\">\n");
    f64_array_at(
        s,
        "displacement",
        &["ux", "uy", "uz"],
        r.displacements.iter().map(|d| [d[0], d[1], 0.0]),
        node_lines,
    );
    f64_array(s, "rotation", &[], r.displacements.iter().map(|d| [d[2]]));
    if !kinds.plane {
        s.push_str("      </PointData>\n");
        return;
    }
    let nodal = |n: &Option<[f64; 4]>| n.unwrap_or([0.0; 4]);
    f64_array(
        s,
        "nodal_stress",
        &["sxx", "syy", "txy"],
        r.nodal_stress.iter().map(|n| {
            let [sx, sy, t, _] = nodal(n);
            [sx, sy, t]
        }),
    );
    f64_array(
        s,
        "nodal_von_mises",
        &[],
        r.nodal_stress.iter().map(|n| [von_mises(nodal(n))]),
    );
    s.push_str("      </PointData>\n");
}

fn cell_results(s: &mut Body, model: &Model, r: &Results, kinds: ElementKinds) {
    let n = model.elements().len();
    if kinds.plane {
        let mut stress = vec![[0.0; 4]; n];
        for pl in &r.planes {
            let mut avg = [0.0; 4];
            for g in &pl.stress {
                for (a, v) in avg.iter_mut().zip(g) {
                    *a += v / pl.stress.len() as f64;
                }
            }
            stress[pl.element.0] = avg;
        }
        f64_array(
            s,
            "stress",
            &["sxx", "syy", "txy"],
            stress.iter().map(|t| [t[0], t[1], t[2]]),
        );
        f64_array(s, "szz", &[], stress.iter().map(|t| [t[3]]));
        f64_array(s, "von_mises", &[], stress.iter().map(|&t| [von_mises(t)]));
    }
    if kinds.line {
        let mut line = vec![[0.0; 3]; n];
        for l in &r.lines {
            let mut v = [0.0f64; 3];
            for pt in &l.diagram {
                if pt.n.abs() > v[0].abs() {
                    v[0] = pt.n;
                }
                v[1] = v[1].max(pt.m.abs());
                v[2] = v[2].max(pt.q.abs());
            }
            line[l.element.0] = v;
        }
        f64_array(s, "axial_force", &[], line.iter().map(|v| [v[0]]));
        f64_array(s, "max_abs_moment", &[], line.iter().map(|v| [v[1]]));
        f64_array(s, "max_abs_shear", &[], line.iter().map(|v| [v[2]]));
    }
}

/// The parts of a pairs file that do not change along the path.
struct PairGeometry {
    m: usize,
    n_points: usize,
    /// Node of each point (B nodes of the pairs, then A nodes of node-to-node pairs).
    /// Each point as `(n1, n2, ξ)`: the point `(1 − ξ)·n1 + ξ·n2` (a node is `(n, n, 0)`; the A
    /// point of a node-to-segment pair lies on its segment).
    point_node: Vec<(usize, usize, f64)>,
    /// Pair of each point.
    point_pair: Vec<usize>,
    /// `+1` at B, `−1` at A.
    point_sign: Vec<f64>,
    /// `<Points>` and `<Cells>`.
    grid: Body,
    /// The points' pair numbers (the last point array of a frame with results).
    point_ids: Body,
    /// The cells' normals, tangents, friction coefficients and pair numbers (the last cell
    /// arrays).
    cell_constants: Body,
    normals: Vec<[f64; 2]>,
    tangents: Vec<[f64; 2]>,
    /// The largest file made so far.
    size: Size,
}

impl PairGeometry {
    fn new(model: &Model, a: &Analysis, format: VtkFormat) -> Self {
        let specs = model.pairs();
        let m = specs.len();
        let mut point_node: Vec<(usize, usize, f64)> =
            specs.iter().map(|p| (p.b.0, p.b.0, 0.0)).collect();
        let mut point_pair: Vec<usize> = (0..m).collect();
        let mut point_sign = vec![1.0; m];
        let mut connectivity = Vec::new();
        let mut offsets = Vec::with_capacity(m);
        let mut types = Vec::with_capacity(m);
        for (i, p) in specs.iter().enumerate() {
            match p.a {
                Endpoint::Ground => types.push(i64::from(VTK_VERTEX)),
                Endpoint::Node(n) => {
                    connectivity.push(point_node.len() as i64);
                    point_node.push(match p.segment {
                        Some((a2, xi)) => (n.0, a2.0, xi),
                        None => (n.0, n.0, 0.0),
                    });
                    point_pair.push(i);
                    point_sign.push(-1.0);
                    types.push(i64::from(VTK_LINE));
                }
            }
            connectivity.push(i as i64);
            offsets.push(connectivity.len() as i64);
        }
        let nodes = model.nodes();
        let mut grid = Body::new(format);
        grid.push_str("      <Points>\n");
        f64_array(
            &mut grid,
            "Points",
            &[],
            point_node.iter().map(|&(n1, n2, xi)| {
                let [x1, y1] = nodes.get(n1).copied().unwrap_or([0.0; 2]);
                let [x2, y2] = nodes.get(n2).copied().unwrap_or([0.0; 2]);
                [(1.0 - xi) * x1 + xi * x2, (1.0 - xi) * y1 + xi * y2, 0.0]
            }),
        );
        grid.push_str("      </Points>\n      <Cells>\n");
        int_array(&mut grid, "Int64", "connectivity", connectivity);
        int_array(&mut grid, "Int64", "offsets", offsets);
        int_array(&mut grid, "UInt8", "types", types);
        grid.push_str("      </Cells>\n");
        let c = &a.condensed;
        let pad = |v: &[[f64; 2]]| -> Vec<[f64; 2]> {
            (0..m)
                .map(|i| v.get(i).copied().unwrap_or([0.0; 2]))
                .collect()
        };
        let normals = pad(&c.normals);
        let tangents = pad(&c.tangents);
        // The arrays that are the same in every frame, made once.
        let mut point_ids = Body::new(format);
        int_array(
            &mut point_ids,
            "Int64",
            "pair",
            point_pair.iter().map(|&i| i as i64),
        );
        let mut cell_constants = Body::new(format);
        let v3 = |v: &[f64; 2]| [v[0], v[1], 0.0];
        f64_array(&mut cell_constants, "normal", &[], normals.iter().map(v3));
        f64_array(&mut cell_constants, "tangent", &[], tangents.iter().map(v3));
        f64_array(
            &mut cell_constants,
            "friction",
            &[],
            (0..m).map(|i| [c.friction.get(i).copied().unwrap_or(0.0)]),
        );
        int_array(&mut cell_constants, "Int64", "pair", 0..m as i64);
        Self {
            m,
            n_points: point_node.len(),
            point_node,
            point_pair,
            point_sign,
            grid,
            point_ids,
            cell_constants,
            normals,
            tangents,
            size: Size::default(),
        }
    }

    /// The points' displacements: a point at a node (`ξ = 0`) has its node's, `(1 − 0)·d + 0·d`
    /// = `d` to the bit (a zero of either sign written `0`), so in ascii its line is the mesh
    /// file's line of that node, copied; a point between two nodes is interpolated.
    fn displacements(&self, s: &mut Body, r: &Results, (text, starts): (&[u8], &[usize])) {
        let disp = |n: usize| r.displacements.get(n).copied().unwrap_or([0.0; 3]);
        let at = |&(n1, n2, xi): &(usize, usize, f64)| {
            let (d1, d2) = (disp(n1), disp(n2));
            [
                (1.0 - xi) * d1[0] + xi * d2[0],
                (1.0 - xi) * d1[1] + xi * d2[1],
                0.0,
            ]
        };
        let names = ["ux", "uy", "uz"];
        if !s.is_ascii() || starts.len() != r.displacements.len() + 1 {
            f64_array(s, "displacement", &names, self.point_node.iter().map(at));
            return;
        }
        let out = &mut s.xml;
        ascii_open(out, "displacement", &names, 3);
        // A copied line's numbers are checked here too (its text is the mesh file's), so that
        // this file refuses them whatever is done with the mesh file.
        let mut bad = None;
        for point in &self.point_node {
            match *point {
                (n1, n2, xi) if n1 == n2 && xi == 0.0 && n1 + 1 < starts.len() => {
                    out.extend_from_slice(&text[starts[n1]..starts[n1 + 1]]);
                    let d = disp(n1);
                    if let Some(&v) = d[..2].iter().find(|v| !v.is_finite()) {
                        bad = bad.or(Some(v));
                    }
                }
                _ => push_tuple(out, at(point), &mut bad),
            }
        }
        out.extend_from_slice(ASCII_CLOSE);
        s.note_value("displacement", bad);
    }

    /// Force of pair `i` on its node B.
    fn force(&self, i: usize, r: &PairResult) -> [f64; 3] {
        let (n, t) = (self.normals[i], self.tangents[i]);
        [
            r.x_n * n[0] + r.x_t * t[0],
            r.x_n * n[1] + r.x_t * t[1],
            0.0,
        ]
    }

    /// The pairs file of `snap`; `node_lines` = the mesh file's XML and where each node's
    /// displacement line starts in it ([`MeshGeometry::vtu`]; none in binary).
    fn vtu(&self, snap: &Snapshot, node_lines: (&[u8], &[usize])) -> Body {
        let mut s = header(self.grid.format, snap, self.n_points, self.m, &self.size);
        let pairs = &snap.pairs[..];
        let have = pairs.len() == self.m && snap.results.is_some();
        // Points 0..m are the B points of pairs 0..m in order, where a pair's force is its
        // force on B, and the points after them are A points, whose numbers are their pair's
        // (the force negated): in ascii each number is formatted once, at its B point; an A
        // point's line and each cell array's text are copies of B points' lines.
        let mut lines: [std::ops::Range<usize>; 5] = Default::default();
        if let (true, Some(r)) = (have, snap.results.as_deref()) {
            s.push_str("      <PointData Scalars=\"state\" Vectors=\"force\">\n");
            self.displacements(&mut s, r, node_lines);
            let names = ["fx", "fy", "fz"];
            let again = &self.point_pair[self.m..];
            lines[4] = pair_point_array(
                &mut s,
                ("force", &names),
                (0..self.m).map(|i| {
                    let f = self.force(i, &pairs[i]);
                    [f[0], f[1], 0.0]
                }),
                (again, true),
                self.point_pair
                    .iter()
                    .zip(&self.point_sign)
                    .map(|(&i, &sign)| {
                        let f = self.force(i, &pairs[i]);
                        [sign * f[0], sign * f[1], 0.0]
                    }),
            );
            int_array(
                &mut s,
                "Int32",
                "state",
                self.point_pair.iter().map(|&i| state_code(pairs[i].state)),
            );
            for (k, (name, f)) in PAIR_FIELDS.into_iter().enumerate() {
                lines[k] = pair_point_array(
                    &mut s,
                    (name, &[]),
                    pairs.iter().map(|r| [f(r)]),
                    (again, false),
                    self.point_pair.iter().map(|&i| [f(&pairs[i])]),
                );
            }
            s.append(&self.point_ids);
            s.push_str("      </PointData>\n");
        }
        s.append(&self.grid);
        s.push_str("      <CellData Scalars=\"state\" Vectors=\"force\">\n");
        if have {
            int_array(
                &mut s,
                "Int32",
                "state",
                pairs.iter().map(|r| state_code(r.state)),
            );
            let ascii = s.is_ascii();
            for (k, (name, f)) in PAIR_FIELDS.into_iter().enumerate() {
                if ascii {
                    copied_array(&mut s, name, &[], 1, lines[k].clone());
                } else {
                    f64_array(&mut s, name, &[], pairs.iter().map(|r| [f(r)]));
                }
            }
            let names = ["fx", "fy", "fz"];
            if ascii {
                copied_array(&mut s, "force", &names, 3, lines[4].clone());
            } else {
                let forces = pairs.iter().enumerate().map(|(i, r)| self.force(i, r));
                f64_array(&mut s, "force", &names, forces);
            }
        }
        s.append(&self.cell_constants);
        s.push_str("      </CellData>\n");
        s.push_str(FOOTER);
        s
    }
}

/// A scalar number of a pair, by its array's name.
type PairField = (&'static str, fn(&PairResult) -> f64);

/// The scalar numbers of a pair written at its points and at its cell, in file order.
const PAIR_FIELDS: [PairField; 4] = [
    ("x_n", |r| r.x_n),
    ("x_t", |r| r.x_t),
    ("z_n", |r| r.z_n),
    ("z_t", |r| r.z_t),
];

/// 0 open, 1 stick, 2 slip+, 3 slip−.
fn state_code(s: PairState) -> i64 {
    match s {
        PairState::Open => 0,
        PairState::Stick => 1,
        PairState::SlipPlus => 2,
        PairState::SlipMinus => 3,
    }
}

/// The start of an unstructured-grid file up to the opening `<Piece>`, with the load as the
/// field `TimeValue` and the field `reported` (1 in the files of the reported load, else 0).
fn header(format: VtkFormat, snap: &Snapshot, points: usize, cells: usize, size: &Size) -> Body {
    let mut b = Body::new(format);
    size.reserve(&mut b);
    let mut s = String::from("<?xml version=\"1.0\"?>\n");
    s.push_str(b.file_tag());
    s.push_str(
        "\x20 <UnstructuredGrid>\n\
         \x20   <FieldData>\n\
         \x20     <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" \
         format=\"ascii\">",
    );
    num_text(&mut s, snap.p);
    b.note_value("TimeValue", Some(snap.p).filter(|p| !p.is_finite()));
    let _ = write!(
        s,
        "</DataArray>\n      <DataArray type=\"Int32\" Name=\"reported\" NumberOfTuples=\"1\" \
         format=\"ascii\">{}</DataArray>\n    </FieldData>\n    \
         <Piece NumberOfPoints=\"{points}\" NumberOfCells=\"{cells}\">\n",
        u8::from(snap.reported)
    );
    b.push_str(&s);
    b
}

/// The end of an unstructured grid (the [`Body`] adds the appended data and `</VTKFile>`).
const FOOTER: &str = "    </Piece>\n  </UnstructuredGrid>\n";

/// A `Float64` data array, one tuple a line, not indented (the indentation was a third of
/// an ascii frame's bytes); `names` are the component names (none for a
/// scalar or for unnamed components).
fn f64_array<const N: usize>(
    b: &mut Body,
    name: &str,
    names: &[&str],
    tuples: impl Iterator<Item = [f64; N]>,
) {
    f64_array_at(b, name, names, tuples, None);
}

/// The end of an ascii array's tag, after its name and components.
const ASCII_FORMAT: &[u8] = b" format=\"ascii\">\n";

/// The end of an ascii array, after its lines.
const ASCII_CLOSE: &[u8] = b"        </DataArray>\n";

/// Opens an ascii `Float64` array: its tag up to its first line.
fn ascii_open(s: &mut Vec<u8>, name: &str, names: &[&str], components: usize) {
    s.extend_from_slice(f64_head(name, names, components).as_bytes());
    s.extend_from_slice(ASCII_FORMAT);
}

/// The start of a `Float64` data array's tag, up to its format.
fn f64_head(name: &str, names: &[&str], components: usize) -> String {
    let mut head = format!(
        "        <DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{components}\""
    );
    for (k, c) in names.iter().enumerate() {
        let _ = write!(head, " ComponentName{k}=\"{c}\"");
    }
    head
}

/// A point array of a pairs file: in ascii the lines of the B points (`b_points`, one a pair
/// in order), then each A point's line copied from its pair's (`again`: the pair of each A
/// point), each number negated where `negate`; returns where the B points' lines lie in the
/// body's XML (for [`copied_array`]). In a binary format the array is `all` (every point's
/// tuple in order) and the range is empty.
fn pair_point_array<const N: usize>(
    b: &mut Body,
    (name, names): (&str, &[&str]),
    b_points: impl Iterator<Item = [f64; N]>,
    (again, negate): (&[usize], bool),
    all: impl Iterator<Item = [f64; N]>,
) -> std::ops::Range<usize> {
    if !b.is_ascii() {
        f64_array(b, name, names, all);
        return 0..0;
    }
    let mut starts = Vec::new();
    let s = &mut b.xml;
    ascii_open(s, name, names, N);
    let mut bad = None;
    for t in b_points {
        starts.push(s.len());
        push_tuple(s, t, &mut bad);
    }
    starts.push(s.len());
    let mut line = Vec::new();
    for &i in again {
        // (a pair's number is below m: `starts` has m + 1 entries)
        let (Some(&a), Some(&z)) = (starts.get(i), starts.get(i + 1)) else {
            continue;
        };
        if negate {
            line.clear();
            line.extend_from_slice(&s[a..z]);
            push_negated(s, &line);
        } else {
            s.extend_from_within(a..z);
        }
    }
    s.extend_from_slice(ASCII_CLOSE);
    b.note_value(name, bad);
    starts[0]..starts[starts.len() - 1]
}

/// Appends an ascii line of numbers (as [`num`] writes them, separated by spaces) with each
/// number negated: [`num`]'s text of `−x` is `-` and its text of `x` (the digits of a number
/// do not depend on its sign), and both zeros are `0`.
fn push_negated(s: &mut Vec<u8>, line: &[u8]) {
    for (k, word) in line.split(|&c| c == b' ' || c == b'\n').enumerate() {
        if word.is_empty() {
            continue;
        }
        if k > 0 {
            s.push(b' ');
        }
        match word {
            [b'-', rest @ ..] => s.extend_from_slice(rest),
            b"0" => s.push(b'0'),
            _ => {
                s.push(b'-');
                s.extend_from_slice(word);
            }
        }
    }
    s.push(b'\n');
}

/// [`f64_array`], recording in ascii into `starts` where each line's text starts in the body's
/// XML, and where the last one ends (nothing in a binary format).
fn f64_array_at<const N: usize>(
    b: &mut Body,
    name: &str,
    names: &[&str],
    tuples: impl Iterator<Item = [f64; N]>,
    mut starts: Option<&mut Vec<usize>>,
) {
    let head = f64_head(name, names, N);
    if !b.is_ascii() {
        b.binary_array(&head, name, "Float64", tuples.flatten());
        return;
    }
    let s = &mut b.xml;
    s.extend_from_slice(head.as_bytes());
    s.extend_from_slice(ASCII_FORMAT);
    let mut bad = None;
    for t in tuples {
        if let Some(v) = starts.as_deref_mut() {
            v.push(s.len());
        }
        push_tuple(s, t, &mut bad);
    }
    if let Some(v) = starts {
        v.push(s.len());
    }
    s.extend_from_slice(ASCII_CLOSE);
    b.note_value(name, bad);
}

/// One line of an ascii array: the tuple's numbers separated by spaces; the first non-finite
/// one kept in `bad`.
#[inline]
fn push_tuple<const N: usize>(s: &mut Vec<u8>, t: [f64; N], bad: &mut Option<f64>) {
    for (k, v) in t.into_iter().enumerate() {
        if k > 0 {
            s.push(b' ');
        }
        num(s, v);
        if !v.is_finite() && bad.is_none() {
            *bad = Some(v);
        }
    }
    s.push(b'\n');
}

/// An ascii `Float64` array of `components` components whose lines are the text at `lines`
/// in the body's XML, made by [`pair_point_array`] (its numbers were checked there).
fn copied_array(
    b: &mut Body,
    name: &str,
    names: &[&str],
    components: usize,
    lines: std::ops::Range<usize>,
) {
    let s = &mut b.xml;
    ascii_open(s, name, names, components);
    s.extend_from_within(lines);
    s.extend_from_slice(ASCII_CLOSE);
}

/// An integer data array of VTK type `ty`, twelve values a line.
fn int_array(b: &mut Body, ty: &str, name: &str, values: impl IntoIterator<Item = i64>) {
    let head = format!("        <DataArray type=\"{ty}\" Name=\"{name}\"");
    if !b.is_ascii() {
        b.binary_array(&head, name, ty, values.into_iter().map(|v| v as f64));
        return;
    }
    let s = &mut b.xml;
    s.extend_from_slice(head.as_bytes());
    s.extend_from_slice(b" format=\"ascii\">");
    let mut text = itoa::Buffer::new();
    for (k, v) in values.into_iter().enumerate() {
        s.extend_from_slice(if k % 12 == 0 { b"\n          " } else { b" " });
        s.extend_from_slice(text.format(v).as_bytes());
    }
    s.extend_from_slice(b"\n        </DataArray>\n");
}

/// A number as the shortest text that reads back as the same `f64`: `zmij`'s (in zmij 1.0,
/// plain decimals from 10⁻⁵ up to 10¹⁶, else an exponent: `0.000025`, `-1.5e-9`, `1e+16`; the
/// layout is zmij's and may change with it, the values cannot), with `0` for both zeros and no
/// `.0` after a whole number. Unlike the tables' text ([`crate::decimal`]) this is
/// not the standard library's layout: in the last digit of an exact halfway case the two may
/// pick different texts, both reading back as the number. Formatting is most of an ascii
/// `--vtk` run's writing, and `zmij`'s text as it comes is a fraction of the cost of laying
/// its digits out again. A non-finite value (refused before the file is written) is written
/// as the standard library writes it.
pub(crate) fn num(s: &mut Vec<u8>, x: f64) {
    if x == 0.0 {
        s.push(b'0');
    } else if x.is_finite() {
        let mut b = zmij::Buffer::new();
        let t = b.format_finite(x);
        push_short(s, t.strip_suffix(".0").unwrap_or(t).as_bytes());
    } else {
        s.extend_from_slice(x.to_string().as_bytes());
    }
}

/// [`num`] into a `String`.
fn num_text(s: &mut String, x: f64) {
    let mut t = Vec::with_capacity(32);
    num(&mut t, x);
    s.push_str(std::str::from_utf8(&t).unwrap_or("NaN"));
}

/// Appends `t`, at most 32 bytes (a number's text), by copies of fixed sizes that the compiler
/// makes inline: `extend_from_slice` calls the C library's `memcpy` for a length it does not
/// know, which for a number's 20 bytes cost more than formatting it (the ascii frames of the
/// 300-bearing beam spent a seventh of their time in those calls).
#[inline]
fn push_short(s: &mut Vec<u8>, t: &[u8]) {
    let n = t.len();
    if n > 32 {
        s.extend_from_slice(t);
        return;
    }
    let at = s.len();
    s.extend_from_slice(&[0u8; 32]);
    let d = &mut s[at..at + 32];
    // Two copies of a fixed size that overlap where the text is shorter than both together.
    if n >= 16 {
        d[..16].copy_from_slice(&t[..16]);
        d[n - 16..n].copy_from_slice(&t[n - 16..]);
    } else if n >= 8 {
        d[..8].copy_from_slice(&t[..8]);
        d[n - 8..n].copy_from_slice(&t[n - 8..]);
    } else if n >= 4 {
        d[..4].copy_from_slice(&t[..4]);
        d[n - 4..n].copy_from_slice(&t[n - 4..]);
    } else {
        d[..n].copy_from_slice(t);
    }
    s.truncate(at + n);
}

/// How the data arrays of the `.vtu` files are written (`--vtk-format`).
///
/// * [`VtkFormat::Ascii`] — every value as text in its `DataArray` (the default: readable and
///   comparable by eye or `diff`, and read by scripts that parse the text).
/// * [`VtkFormat::Binary`] — the arrays as raw little-endian bytes in one
///   `<AppendedData encoding="raw">` block at the end of the file, each array preceded by its
///   byte count as a `UInt64` (`header_type="UInt64"`): exact, and no number is
///   formatted or parsed as text (smaller for full-precision numbers: the 63 files of the
///   sheet pile wall's path take 2.5 MB against 4.4 MB of text; a file of many exact zeros and
///   small integers can be larger than its text).
/// * [`VtkFormat::Compressed`] — the same, each array zlib-compressed in blocks of
///   [`COMPRESSED_BLOCK`] bytes (`compressor="vtkZLibDataCompressor"`: a `UInt64` header of
///   the block count, the block size, the size of a partial last block (0 when it is full)
///   and the compressed size of every block, then the compressed blocks). Read by every VTK
///   reader (meshio too; VTK 9.7 checked). Each block is one zlib stream made by
///   [`crate::deflate`], this crate's encoder (fixed Huffman codes, LZ4's way of finding
///   matches, a hash table kept from stream to stream): about twice as fast as `zlib-rs` at its
///   fastest level on a path's many small arrays, files as small (the 1000-bearing beam's
///   frames take 751 MB, 35 % of the binary files; `docs/performance.md`, round 36).
/// * [`VtkFormat::Lz4`] — the same blocks compressed by LZ4 (`compressor="vtkLZ4DataCompressor"`,
///   each block as VTK's `LZ4_decompress_safe` reads it): read by VTK from 8.1 on (ParaView
///   5.5, 2018), not by meshio 5.3. On the 300-bearing beam's arrays LZ4 (`lz4_flex`) took
///   0.074 s where zlib-rs's fastest level took 0.20 s (round 34), for files 11 % larger, and
///   is inflated several times faster; since round 36 ([`crate::deflate`]) zlib's files take
///   about 2.4 times LZ4's compressing time (0.040 s against 0.016 s of a whole run, 1.95
///   against 1.77 times the run without files).
///
/// The small field data of a file (`TimeValue`, `reported`, `stage`) stays text in every
/// format.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum VtkFormat {
    /// Values as text.
    #[default]
    Ascii,
    /// Raw appended binary.
    Binary,
    /// Zlib-compressed appended binary.
    Compressed,
    /// LZ4-compressed appended binary.
    Lz4,
}

impl VtkFormat {
    /// Whether the arrays are compressed (LZ4 or zlib).
    fn compressed(self) -> bool {
        matches!(self, VtkFormat::Compressed | VtkFormat::Lz4)
    }
}

/// The uncompressed size of a compressed block (VTK's own default).
pub const COMPRESSED_BLOCK: usize = 32768;

/// The uncompressed size of a zlib block: [`COMPRESSED_BLOCK`], its name before LZ4 blocks.
#[deprecated(note = "the block size of both compressions: use COMPRESSED_BLOCK")]
pub const ZLIB_BLOCK: usize = COMPRESSED_BLOCK;

/// The XML of a `.vtu` file being written and, in a binary format, its appended data: each
/// binary array's `offset` attribute is filled in when the file is finished, so that pieces
/// made once (the geometry, which does not change along the path) can be put into every file.
pub(crate) struct Body {
    format: VtkFormat,
    pub(crate) xml: Vec<u8>,
    data: Vec<u8>,
    /// `(place in xml, offset in data)` of every binary array's `offset` attribute.
    marks: Vec<(usize, usize)>,
    /// The first non-finite value of a binary array: its array's name and the value.
    bad: Option<(String, f64)>,
    /// A failure of the compressor (none is expected: it writes into memory).
    failed: Option<io::Error>,
}

impl Body {
    pub(crate) fn new(format: VtkFormat) -> Self {
        Self {
            format,
            xml: Vec::new(),
            data: Vec::new(),
            marks: Vec::new(),
            bad: None,
            failed: None,
        }
    }

    pub(crate) fn push_str(&mut self, s: &str) {
        self.xml.extend_from_slice(s.as_bytes());
    }

    /// Records the first non-finite value written to a data array (`value`: one found in the
    /// array `name`, if any), which [`Body::finish`] refuses.
    pub(crate) fn note_value(&mut self, name: &str, value: Option<f64>) {
        if let (None, Some(v)) = (&self.bad, value) {
            self.bad = Some((name.to_string(), v));
        }
    }

    /// Appends a piece made apart (with its binary arrays).
    pub(crate) fn append(&mut self, other: &Body) {
        let (x, d) = (self.xml.len(), self.data.len());
        self.marks
            .extend(other.marks.iter().map(|&(a, b)| (a + x, b + d)));
        self.xml.extend_from_slice(&other.xml);
        self.data.extend_from_slice(&other.data);
        if self.bad.is_none() {
            self.bad.clone_from(&other.bad);
        }
        if let (None, Some(e)) = (&self.failed, &other.failed) {
            self.failed = Some(io::Error::new(e.kind(), e.to_string()));
        }
    }

    pub(crate) fn is_ascii(&self) -> bool {
        self.format == VtkFormat::Ascii
    }

    /// The `<VTKFile …>` tag of an unstructured grid in this format.
    pub(crate) fn file_tag(&self) -> &'static str {
        match self.format {
            VtkFormat::Ascii => {
                "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            }
            VtkFormat::Binary => {
                "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
                 header_type=\"UInt64\">\n"
            }
            VtkFormat::Compressed => {
                "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
                 header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
            }
            VtkFormat::Lz4 => {
                "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
                 header_type=\"UInt64\" compressor=\"vtkLZ4DataCompressor\">\n"
            }
        }
    }

    /// A binary data array: `head` is the start of its tag (`<DataArray type=… Name=…`,
    /// indented), `ty` its VTK type and `values` its values in order (integers exactly
    /// representable, as every index and code here is).
    pub(crate) fn binary_array(
        &mut self,
        head: &str,
        name: &str,
        ty: &str,
        values: impl IntoIterator<Item = f64>,
    ) {
        self.xml.extend_from_slice(head.as_bytes());
        self.xml
            .extend_from_slice(b" format=\"appended\" offset=\"");
        self.marks.push((self.xml.len(), self.data.len()));
        self.xml.extend_from_slice(b"\"/>\n");
        let u64s = |out: &mut Vec<u8>, vs: &[usize]| {
            for &v in vs {
                out.extend_from_slice(&(v as u64).to_le_bytes());
            }
        };
        // Raw: the values go straight after their byte count (filled in once they are all
        // there); compressed: into a buffer of their own, compressed by blocks.
        let raw_format = !self.format.compressed();
        let start = self.data.len();
        let mut own = Vec::new();
        let raw = if raw_format {
            u64s(&mut self.data, &[0]);
            &mut self.data
        } else {
            &mut own
        };
        // The type chosen once an array, not once a value.
        let bad = match ty {
            "Float64" => encode(raw, values, |r, v| r.extend_from_slice(&v.to_le_bytes())),
            "Int64" => encode(raw, values, |r, v| {
                r.extend_from_slice(&(v as i64).to_le_bytes());
            }),
            "Int32" => encode(raw, values, |r, v| {
                r.extend_from_slice(&(v as i32).to_le_bytes());
            }),
            _ => encode(raw, values, |r, v| r.push(v as u8)), // UInt8
        };
        self.note_value(name, bad);
        if raw_format {
            let bytes = (self.data.len() - start - 8) as u64;
            self.data[start..start + 8].copy_from_slice(&bytes.to_le_bytes());
            return;
        }
        let raw = own;
        {
            let compress = if self.format == VtkFormat::Lz4 {
                lz4
            } else {
                zlib
            };
            let chunks = raw.chunks(COMPRESSED_BLOCK);
            let blocks: Vec<Vec<u8>> = match chunks.map(compress).collect() {
                Ok(b) => b,
                Err(e) => {
                    self.failed.get_or_insert(e);
                    Vec::new()
                }
            };
            let mut head = vec![blocks.len(), COMPRESSED_BLOCK, raw.len() % COMPRESSED_BLOCK];
            head.extend(blocks.iter().map(Vec::len));
            u64s(&mut self.data, &head);
            for b in &blocks {
                self.data.extend_from_slice(b);
            }
        }
    }

    /// The finished file: the XML with the offsets filled in, then in a binary format the
    /// appended data, then `</VTKFile>`. Every number of its data arrays was checked finite as
    /// it was written (ascii or binary); a non-finite one is refused here, named by its array.
    /// The XML written so far must end with `</UnstructuredGrid>` (or `</Collection>`).
    pub(crate) fn finish(self, file: &str) -> io::Result<Vec<u8>> {
        self.finish_parts(file).map(Finished::into_bytes)
    }

    /// [`Body::finish`] as its parts, for a writer that writes them one after the other (the
    /// appended data of a path's frames, gigabytes in all, not copied once more).
    pub(crate) fn finish_parts(self, file: &str) -> io::Result<Finished> {
        if let Some(e) = self.failed {
            return Err(e);
        }
        if let Some((name, value)) = self.bad {
            return Err(crate::NonFiniteOutput {
                field: format!("the data array \"{name}\" in {file}"),
                value,
            }
            .into());
        }
        let ascii = self.is_ascii();
        let mut head = if self.marks.is_empty() {
            // Nothing to fill in (an ascii file is all XML): its bytes as they are, not a
            // copy of a megabyte a frame.
            self.xml
        } else {
            let mut head = Vec::with_capacity(self.xml.len() + 2 * self.marks.len() + 64);
            let mut at = 0;
            for &(place, offset) in &self.marks {
                head.extend_from_slice(&self.xml[at..place]);
                head.extend_from_slice(itoa::Buffer::new().format(offset).as_bytes());
                at = place;
            }
            head.extend_from_slice(&self.xml[at..]);
            head
        };
        let tail: &'static [u8] = if ascii {
            b"</VTKFile>\n"
        } else {
            head.extend_from_slice(b"  <AppendedData encoding=\"raw\">\n   _");
            b"\n  </AppendedData>\n</VTKFile>\n"
        };
        Ok(Finished {
            head,
            data: self.data,
            tail,
        })
    }
}

/// A finished file in three parts: the XML (and the start of the appended data), the appended
/// data (empty in ascii) and the end ([`Body::finish_parts`]).
pub(crate) struct Finished {
    head: Vec<u8>,
    data: Vec<u8>,
    tail: &'static [u8],
}

impl Finished {
    fn into_bytes(self) -> Vec<u8> {
        let mut out = self.head;
        out.reserve_exact(self.data.len() + self.tail.len());
        out.extend_from_slice(&self.data);
        out.extend_from_slice(self.tail);
        out
    }

    /// Writes the file `dir/name` over its old bytes, if any: the file is not truncated first
    /// but cut to its new length after the writing. Truncating a file frees its blocks, and
    /// on a file system mounted with `discard` a thread waits for the device to discard them
    /// (on the 1000-bearing beam, a quarter of the writers' waits); a frame rewritten by a
    /// second run is mostly the same size and keeps its blocks.
    fn write_over(&self, dir: &Path, name: &str) -> io::Result<PathBuf> {
        let path = dir.join(name);
        let mut f = crate::overwrite::open_over(&path)?;
        match self.write_into(&mut f) {
            Ok(()) => Ok(path),
            Err(e) => {
                // Not a mix of this run's bytes and an earlier run's.
                drop(f);
                let _ = std::fs::remove_file(&path);
                Err(e)
            }
        }
    }

    fn write_into(&self, f: &mut std::fs::File) -> io::Result<()> {
        use std::io::{IoSlice, Write as _};
        // One system call for the parts where it takes them all: a page that two parts share
        // is then written whole, never read back from the device first.
        let mut parts = [
            IoSlice::new(&self.head),
            IoSlice::new(&self.data),
            IoSlice::new(self.tail),
        ];
        let mut rest = &mut parts[..];
        while !rest.is_empty() {
            match f.write_vectored(rest) {
                Ok(0) => return Err(io::ErrorKind::WriteZero.into()),
                Ok(n) => IoSlice::advance_slices(&mut rest, n),
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        let len = (self.head.len() + self.data.len() + self.tail.len()) as u64;
        crate::overwrite::cut_to(f, len)
    }
}

/// Appends `values` to `raw` by `put`, −0 as 0 (as in the text); the first non-finite value.
fn encode(
    raw: &mut Vec<u8>,
    values: impl IntoIterator<Item = f64>,
    put: impl Fn(&mut Vec<u8>, f64),
) -> Option<f64> {
    let mut bad = None;
    for v in values {
        let v = if v == 0.0 { 0.0 } else { v };
        if !v.is_finite() && bad.is_none() {
            bad = Some(v);
        }
        put(raw, v);
    }
    bad
}

/// One block as an LZ4 block (no frame: the raw block that VTK's `LZ4_decompress_safe` reads,
/// its size in the header before the blocks).
fn lz4(bytes: &[u8]) -> io::Result<Vec<u8>> {
    Ok(lz4_flex::block::compress(bytes))
}

/// One block's zlib stream ([`crate::deflate`]).
fn zlib(bytes: &[u8]) -> io::Result<Vec<u8>> {
    Ok(crate::deflate::zlib(bytes))
}

#[cfg(test)]
mod tests {
    use super::{
        check_numbers, num_text as num, push_negated, push_short, push_tuple, Body, VtkFormat,
    };

    /// The ascii text of a number reads back as the number (`0` for both zeros, no `.0` after
    /// a whole number), and the text of a negated number is the text with its sign changed:
    /// on numbers of every size and kind (a fixed sequence of bits, replayable).
    #[test]
    fn ascii_numbers_read_back_and_negate_as_text() {
        let mut next = crate::replay::bits(7);
        let mut xs = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            100.0,
            1e15,
            1e16,
            1e-7,
            1.5e-7,
            2.5e-5,
            5e-324,
            f64::MAX,
            f64::MIN_POSITIVE,
            0.1 + 0.2,
        ];
        for _ in 0..200_000 {
            let bits = next();
            xs.push(f64::from_bits(bits));
            // Results' sizes: a mantissa in [1, 2) times 2^-60 … 2^60, either sign.
            let m = 1.0 + (bits >> 12) as f64 / (1u64 << 52) as f64;
            xs.push(
                m * 2f64.powi((bits % 121) as i32 - 60) * if bits & 1 == 0 { 1.0 } else { -1.0 },
            );
            xs.push((bits % 100_000) as f64 - 50_000.0);
        }
        for x in xs.into_iter().filter(|x| x.is_finite()) {
            let mut t = String::new();
            num(&mut t, x);
            let back: f64 = t.parse().unwrap_or_else(|_| panic!("{t} does not parse"));
            assert_eq!(back, x, "{t} for {:#018x}", x.to_bits());
            assert!(x != 0.0 || t == "0", "{t} for a zero");
            assert!(!t.ends_with(".0"), "{t}");
            // A pairs file's A points negate their B points' lines as text.
            let line = |v: [f64; 3]| {
                let mut s = Vec::new();
                push_tuple(&mut s, v, &mut None);
                s
            };
            let mut negated = Vec::new();
            push_negated(&mut negated, &line([x, 1.5, 0.0]));
            let direct = line([-x, -1.5, -0.0]);
            assert_eq!(
                String::from_utf8_lossy(&negated),
                String::from_utf8_lossy(&direct),
                "the negated text of {t}"
            );
        }
    }

    /// A short text is appended as it is, at every length (the fixed-size copies overlap
    /// differently at each), after text already there and with a buffer that must grow.
    #[test]
    fn short_texts_are_appended_whole() {
        let text: Vec<u8> = (0..40u8).map(|k| b'a' + k % 26).collect();
        for n in 0..=40 {
            for before in [0, 1, 7, 100] {
                let mut s = vec![b'x'; before];
                s.shrink_to_fit();
                push_short(&mut s, &text[..n]);
                let mut want = vec![b'x'; before];
                want.extend_from_slice(&text[..n]);
                assert_eq!(s, want, "{n} after {before}");
            }
        }
    }

    /// A non-finite value of a binary array is named, as the text scan names one of an ascii
    /// array; a finite file has its offsets filled in (the second array after the first's
    /// 8-byte count and two 8-byte values).
    #[test]
    fn binary_arrays_are_checked_and_placed() {
        let mut b = Body::new(VtkFormat::Binary);
        b.binary_array(
            "<DataArray type=\"Float64\" Name=\"u\"",
            "u",
            "Float64",
            [1.0, -2.5],
        );
        b.binary_array("<DataArray type=\"Int32\" Name=\"k\"", "k", "Int32", [3.0]);
        let text = String::from_utf8_lossy(&b.finish("a.vtu").unwrap()).into_owned();
        assert!(
            text.contains("Name=\"u\" format=\"appended\" offset=\"0\"/>"),
            "{text}"
        );
        assert!(
            text.contains("Name=\"k\" format=\"appended\" offset=\"24\"/>"),
            "{text}"
        );
        for format in [VtkFormat::Compressed, VtkFormat::Lz4, VtkFormat::Binary] {
            let mut b = Body::new(format);
            b.binary_array(
                "<DataArray type=\"Float64\" Name=\"u\"",
                "u",
                "Float64",
                [1.0, f64::INFINITY, f64::NAN],
            );
            let e = b.finish("a.vtu").unwrap_err();
            let n = crate::NonFiniteOutput::in_io_error(&e).expect("a NonFiniteOutput");
            assert_eq!(n.field, "the data array \"u\" in a.vtu");
            assert_eq!(n.value, f64::INFINITY, "the first one, {format:?}");
        }
        // The raw bytes: each array's byte count, then its values, little-endian.
        let mut b = Body::new(VtkFormat::Binary);
        b.binary_array(
            "<DataArray type=\"Int32\" Name=\"k\"",
            "k",
            "Int32",
            [3.0, -1.0],
        );
        let bytes = b.finish("a.vtu").unwrap();
        let mut want = 8u64.to_le_bytes().to_vec();
        want.extend_from_slice(&3i32.to_le_bytes());
        want.extend_from_slice(&(-1i32).to_le_bytes());
        assert!(bytes.windows(want.len()).any(|w| w == want.as_slice()));
    }

    /// A value of an ascii array is checked as it is written: the first non-finite one is
    /// refused by `finish`, named by its array, whichever array comes first; finite arrays pass
    /// and read back as written.
    #[test]
    fn ascii_arrays_are_checked_as_they_are_written() {
        let mut b = Body::new(VtkFormat::Ascii);
        super::f64_array(
            &mut b,
            "u",
            &["x", "y"],
            [[1.0, -2.5e-3], [0.0, 3.0]].into_iter(),
        );
        let text = String::from_utf8(b.finish("a.vtu").unwrap()).unwrap();
        assert!(text.contains("\n1 -0.0025\n0 3\n"), "{text}");
        for (first, second, name, value) in [
            (f64::NAN, 1.0, "u", f64::NAN),
            (1.0, f64::NEG_INFINITY, "v", f64::NEG_INFINITY),
        ] {
            let mut b = Body::new(VtkFormat::Ascii);
            super::f64_array(&mut b, "u", &[], [[first]].into_iter());
            super::f64_array(&mut b, "v", &[], [[second], [f64::INFINITY]].into_iter());
            let e = b.finish("a.vtu").unwrap_err();
            let n = crate::NonFiniteOutput::in_io_error(&e).expect("a NonFiniteOutput");
            assert_eq!(n.field, format!("the data array \"{name}\" in a.vtu"));
            assert_eq!(n.value.is_nan(), value.is_nan());
            if !value.is_nan() {
                assert_eq!(n.value, value);
            }
        }
    }

    #[test]
    fn non_finite_numbers_in_a_vtk_text_are_found() {
        let ok = "<DataArray type=\"Float64\" Name=\"u\" format=\"ascii\">\n 1 -2.5e-3 0\n</DataArray>\n<DataSet timestep=\"0.5\" part=\"0\"/>";
        assert!(check_numbers("a.vtu", ok).is_ok());
        for (text, field) in [
            (
                ok.replace("-2.5e-3", "NaN"),
                "the data array \"u\" in a.vtu",
            ),
            (
                ok.replace("-2.5e-3", "-inf"),
                "the data array \"u\" in a.vtu",
            ),
            (ok.replace("0.5", "inf"), "a timestep in a.vtu"),
        ] {
            assert_eq!(check_numbers("a.vtu", &text).unwrap_err().field, field);
        }
    }
}

#[cfg(test)]
mod block_tests {
    use super::*;

    /// The bundled sheet pile wall, analysed (traced past its target: 31 frames).
    fn sheet_pile_wall() -> Analysis {
        let file =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/sheet-pile-wall.toml");
        let unilateral_io::Problem::Structural(problem) =
            unilateral_io::read_problem(&file).unwrap()
        else {
            panic!("a structural model");
        };
        unilateral_analysis::analyze(&problem.model, &problem.settings).unwrap()
    }

    /// A pairs file refuses a non-finite displacement at a pair's node by itself, naming its
    /// own array and file, in every format (in ascii the lines of its points at nodes are the
    /// mesh file's text, copied: the mesh file refuses them too, but the pairs file does not
    /// lean on it). Reference: the NaN put into the first pair's node B by hand.
    #[test]
    fn a_pairs_file_refuses_a_non_finite_displacement_by_itself() {
        let a = sheet_pile_wall();
        let model = a.condensed.model();
        let mut r = a.results.clone().expect("results");
        let node = model.pairs()[0].b.0;
        r.displacements[node][1] = f64::NAN;
        for format in [VtkFormat::Ascii, VtkFormat::Binary, VtkFormat::Lz4] {
            let mesh = MeshGeometry::new(model, format);
            let pairs = PairGeometry::new(model, &a, format);
            let snap = Snapshot {
                p: 0.5,
                pairs: Cow::Borrowed(&a.solution.pairs),
                results: Some(Cow::Borrowed(&r)),
                reported: false,
                pending: false,
            };
            let mut lines = Vec::new();
            let body = mesh.vtu(model, &snap, Some(&mut lines));
            let e = pairs
                .vtu(&snap, (&body.xml, &lines))
                .finish_parts("pairs_000.vtu")
                .err()
                .unwrap_or_else(|| panic!("{format:?}: the pairs file was not refused"));
            let n = crate::NonFiniteOutput::in_io_error(&e).expect("a NonFiniteOutput");
            assert_eq!(n.field, "the data array \"displacement\" in pairs_000.vtu");
            assert!(n.value.is_nan(), "{format:?}");
            assert!(body.finish_parts("mesh_000.vtu").is_err(), "{format:?}");
        }
    }

    /// The blocks of frames cover every frame once, in order: a small first one, then blocks
    /// of at most the size asked (within one of each other), none of one frame among more.
    #[test]
    fn blocks_cover_the_frames_without_a_lone_frame() {
        assert_eq!(block_ends(624, 256), vec![32, 230, 427, 624]);
        assert_eq!(block_ends(31, 256), vec![31]);
        assert_eq!(block_ends(40, 256), vec![32, 40]);
        assert_eq!(block_ends(0, 256), vec![0]);
        for size in [1, 2, 3, 5, 16, 256] {
            for n in 0..600 {
                let ends = block_ends(n, size);
                assert_eq!(ends.last(), Some(&n), "n {n}, size {size}");
                let mut start = 0;
                for &e in &ends {
                    let len = e - start;
                    assert!(len >= 2 || n < 2, "n {n}, size {size}: {ends:?}");
                    assert!(len <= size.max(2) + 1, "n {n}, size {size}: {ends:?}");
                    start = e;
                }
            }
        }
    }

    /// The frames' pairs are read from the path a block at a time: whatever the block, the
    /// same files with the same bytes, the reported solution in its place among the frames
    /// (the bundled sheet pile wall is traced past its target: events follow the reported
    /// load), numbered in load order.
    #[test]
    fn the_frames_do_not_depend_on_the_block() {
        let a = sheet_pile_wall();
        let plan = FramePlan::new(&a);
        let (_, _, at) = plan.reported.expect("a reported solution");
        assert!(
            at > 0 && at < plan.frames.len(),
            "reported at {at} of {}",
            plan.frames.len()
        );
        let read = |block: usize| -> Vec<(String, Vec<u8>)> {
            let dir = tempfile::tempdir().unwrap();
            let files = write_frames(&a, dir.path(), VtkFormat::Binary, block, &|_| false).unwrap();
            files
                .iter()
                .map(|f| {
                    let name = f.file_name().unwrap().to_string_lossy().into_owned();
                    (name, std::fs::read(f).unwrap())
                })
                .collect()
        };
        let whole = read(VTK_BLOCK);
        // 31 frames (the start, 29 changes, the reported state), two files each, and the
        // collection.
        assert_eq!(whole.len(), 2 * 31 + 1);
        for block in [1, 2, 5, 30] {
            let got = read(block);
            assert_eq!(got.len(), whole.len(), "block {block}");
            for (g, w) in got.iter().zip(&whole) {
                assert_eq!(g.0, w.0, "block {block}");
                assert!(g.1 == w.1, "block {block}: {} differs", g.0);
            }
        }
        // The reported state is the frame at its place in load order.
        let pvd = String::from_utf8(whole.last().unwrap().1.clone()).unwrap();
        let reported = format!("file=\"mesh_{at:03}.vtu\"");
        let line = pvd
            .lines()
            .find(|l| l.contains(&reported))
            .expect("the reported frame");
        assert!(line.contains("timestep=\"1\""), "{line}");
    }

    /// A second run into a directory rewrites its files in place: files longer than the new
    /// ones are cut to them, and frames that could not be recovered leave no gap (the frames
    /// after them are renamed down, in load order). The bytes of each frame are those of the
    /// same frame written alone into an empty directory; the collection names the new frames.
    #[test]
    fn a_second_run_rewrites_the_files_and_closes_up_lost_frames() {
        let a = sheet_pile_wall();
        let fresh = tempfile::tempdir().unwrap();
        let whole = write_frames(&a, fresh.path(), VtkFormat::Binary, 7, &|_| false).unwrap();
        assert_eq!(whole.len(), 2 * 31 + 1);
        let bytes = |f: &Path| std::fs::read(f).unwrap();
        // An earlier run's files under every name, each longer than the new one.
        let dir = tempfile::tempdir().unwrap();
        for f in &whole {
            let mut old = bytes(f);
            old.extend(std::iter::repeat_n(b'#', 5000));
            std::fs::write(dir.path().join(f.file_name().unwrap()), old).unwrap();
        }
        // One of them read-only and one with a second name in a snapshot directory: both
        // replaced, as files renamed over them would be (the new file not read-only, even for
        // a user such as root who may write a read-only file; the snapshot not touched).
        let locked = dir.path().join("mesh_000.vtu");
        let mut perms = std::fs::metadata(&locked).unwrap().permissions();
        perms.set_readonly(true);
        std::fs::set_permissions(&locked, perms).unwrap();
        let snapshot = tempfile::tempdir().unwrap();
        let kept_name = snapshot.path().join("pairs_003.vtu");
        std::fs::hard_link(dir.path().join("pairs_003.vtu"), &kept_name).unwrap();
        let kept_bytes = bytes(&kept_name);
        let lost = |i: usize| i % 3 == 1;
        let kept: Vec<usize> = (0..31).filter(|&i| !lost(i)).collect();
        let got = write_frames(&a, dir.path(), VtkFormat::Binary, 7, &lost).unwrap();
        assert_eq!(got.len(), 2 * kept.len() + 1);
        for (k, &i) in kept.iter().enumerate() {
            for part in 0..2 {
                let new = &got[2 * k + part];
                let name = if part == 0 { "mesh" } else { "pairs" };
                assert_eq!(new, &dir.path().join(format!("{name}_{k:03}.vtu")));
                assert!(
                    bytes(new) == bytes(&whole[2 * i + part]),
                    "{} differs from frame {i}",
                    new.display()
                );
            }
        }
        assert!(!std::fs::metadata(&locked).unwrap().permissions().readonly());
        assert!(
            bytes(&kept_name) == kept_bytes,
            "the snapshot's file was written through"
        );
        let pvd = String::from_utf8(bytes(got.last().unwrap())).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), 2 * kept.len());
        assert!(pvd.contains(&format!("file=\"pairs_{:03}.vtu\"", kept.len() - 1)));
        assert!(!pvd.contains(&format!("file=\"mesh_{:03}.vtu\"", kept.len())));
    }

    /// A frame that cannot be written (its name taken by a directory) fails the run, and every
    /// file the run wrote is removed, the other part of that frame with them: no collection,
    /// no frame of a half-made run.
    #[test]
    fn a_failed_write_leaves_no_file_of_the_run() {
        let a = sheet_pile_wall();
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir(dir.path().join("pairs_005.vtu")).unwrap();
        let e = write_frames(&a, dir.path(), VtkFormat::Binary, 7, &|_| false).unwrap_err();
        assert!(!e.to_string().is_empty());
        let left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(left, ["pairs_005.vtu"], "{left:?}");
    }
}
