//! ParaView files over a load history of a structural model: a `.pvd` collection whose
//! timestep is the pseudo-time `stage − 1 + s`, with the unloaded start (`t = 0`), every change
//! of the working scheme inside a stage (up to [`HISTORY_VTK_STEPS`] of them), and the end of
//! every stage run (`t = K − 1 + s_end`, the full results of that stage).
//!
//! Files (`NNN` = 0-based snapshot number, zero-padded): `history_mesh_NNN.vtu` (points =
//! nodes, cells = elements as `VTK_LINE` or `VTK_QUAD`; point data `displacement`
//! (`ux, uy, 0`) and `rotation`; cell data `element`), `history_pairs_NNN.vtu` (one cell per
//! pair: a `VTK_VERTEX` at node B for a pair with the ground, a `VTK_LINE` A–B otherwise; cell
//! data `state` (0 open, 1 stick, 2 slip+, 3 slip−), `x_n`, `x_t`, `z_n`, `z_t` (the
//! accumulated slip), `pair`), and [`HISTORY_PVD`]. Each `.vtu` carries its pseudo-time as
//! the field `TimeValue` and its stage as the field `stage`. The data arrays are text, raw
//! appended binary, or compressed by zlib or LZ4 ([`VtkFormat`], [`history_vtk_with`]), as the
//! path's.
//!
//! The writer of one state here is small on purpose: it holds what a history needs to be
//! stepped through in ParaView. The full set of fields of `vtk.rs` (stresses, forces,
//! normals) would come from that module's writer of one state once it takes a state rather
//! than an `Analysis`.

use std::fmt::Write as _;

use unilateral_analysis::HistoryAnalysis;
use unilateral_contact::{PairResult, PairState};
use unilateral_fem::{Element, Endpoint, Model, Results};

use crate::finite::finite;
use crate::history::{check, pseudo_time};
use crate::vtk::{Body, VtkFormat};

/// The collection file of a history.
pub const HISTORY_PVD: &str = "history.pvd";

/// The most changes of the working scheme inside stages that get a snapshot of their own;
/// a longer history has snapshots at the stage ends only.
pub const HISTORY_VTK_STEPS: usize = 2000;

/// One state of the history: its pseudo-time, stage (0 for the start), pairs and results.
struct State<'a> {
    t: f64,
    stage: usize,
    pairs: Option<&'a [PairResult]>,
    results: Option<&'a Results>,
}

/// The ParaView files of a history as `(file name, text)`, the collection [`HISTORY_PVD`]
/// last. Every number is checked finite first (else an error carrying a
/// [`NonFiniteOutput`](crate::NonFiniteOutput), see
/// [`in_io_error`](crate::NonFiniteOutput::in_io_error)), and the sizes of the results
/// against the model (else an [`std::io::ErrorKind::InvalidInput`] error: results that are
/// not the analysed model's are the program's fault, as in [`crate::write_vtk_for`]).
pub fn history_vtk(a: &HistoryAnalysis) -> std::io::Result<Vec<(String, String)>> {
    history_vtk_with(a, VtkFormat::Ascii)?
        .into_iter()
        .map(|(name, bytes)| {
            String::from_utf8(bytes)
                .map(|text| (name, text))
                .map_err(|e| std::io::Error::other(e.to_string()))
        })
        .collect()
}

/// [`history_vtk`] with the data arrays of the `.vtu` files in the given [`VtkFormat`], the
/// files as bytes.
pub fn history_vtk_with(
    a: &HistoryAnalysis,
    format: VtkFormat,
) -> std::io::Result<Vec<(String, Vec<u8>)>> {
    check(&a.history)?;
    let model = a.condensed.model();
    // Every change of the working scheme strictly inside a stage, recovered (the evolution is
    // linear between them, so these and the stage ends are every corner of the history);
    // beyond `HISTORY_VTK_STEPS` of them, the stage ends only.
    // A failed stage (`StageStatus::has_states`) has no frame: its states are where the
    // engine went before it stopped, and its end where it stopped.
    let stages = &a.history.stages;
    let stages = &stages[..stages
        .iter()
        .take_while(|st| st.status.has_states())
        .count()];
    let inner: Vec<(usize, f64)> = stages
        .iter()
        .flat_map(|st| {
            let mut last = 0.0;
            st.steps
                .iter()
                .filter_map(move |p| {
                    let keep = p.s > last && p.s < st.s_end;
                    last = p.s;
                    keep.then_some((st.stage, p.s))
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut steps: Vec<(usize, f64, Vec<PairResult>, Results)> = Vec::new();
    if inner.len() <= HISTORY_VTK_STEPS {
        for &(stage, s) in &inner {
            let (pairs, r) = a
                .results_at(stage, s)
                .map_err(|e| std::io::Error::other(e.to_string()))?;
            check_results(model, &pairs, &r, stage)?;
            steps.push((stage, s, pairs, r));
        }
    }
    let mut states = vec![State {
        t: 0.0,
        stage: 0,
        pairs: None,
        results: None,
    }];
    let mut next = steps.iter().peekable();
    for (k, st) in stages.iter().enumerate() {
        while let Some((stage, s, pairs, r)) = next.peek() {
            if *stage != st.stage {
                break;
            }
            states.push(State {
                t: pseudo_time(*stage, *s),
                stage: *stage,
                pairs: Some(pairs),
                results: Some(r),
            });
            next.next();
        }
        let results = a.stage_results.get(k);
        if let Some(r) = results {
            check_results(model, &st.pairs, r, st.stage)?;
        }
        states.push(State {
            t: pseudo_time(st.stage, st.s_end),
            stage: st.stage,
            pairs: Some(&st.pairs),
            results,
        });
    }
    let width = (states.len() - 1).to_string().len().max(3);
    let mut files = Vec::with_capacity(2 * states.len() + 1);
    let mut pvd = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n\
         \x20 <Collection>\n",
    );
    let m = model.pairs().len();
    for (k, s) in states.iter().enumerate() {
        let mesh = format!("history_mesh_{k:0width$}.vtu");
        let _ = writeln!(
            pvd,
            "    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{mesh}\"/>",
            Num(s.t)
        );
        let text = mesh_vtu(model, s, format).finish(&mesh)?;
        files.push((mesh, text));
        if m > 0 {
            let pairs = format!("history_pairs_{k:0width$}.vtu");
            let _ = writeln!(
                pvd,
                "    <DataSet timestep=\"{}\" group=\"\" part=\"1\" file=\"{pairs}\"/>",
                Num(s.t)
            );
            let text = pairs_vtu(model, &a.zone.gap, s, format).finish(&pairs)?;
            files.push((pairs, text));
        }
    }
    pvd.push_str("  </Collection>\n</VTKFile>\n");
    files.push((HISTORY_PVD.to_string(), pvd.into_bytes()));
    Ok(files)
}

/// Every number of a stage's results that the files print is finite, and the sizes are the
/// model's.
fn check_results(
    model: &Model,
    pairs: &[PairResult],
    r: &Results,
    stage: usize,
) -> std::io::Result<()> {
    let (n, m) = (model.nodes().len(), model.pairs().len());
    if r.displacements.len() != n || pairs.len() != m {
        return Err(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!(
                "stage {stage} has results of {} nodes and {} pairs but the model {n} nodes \
                 and {m} pairs: not the analysed model (a fault of the program)",
                r.displacements.len(),
                pairs.len()
            ),
        ));
    }
    for (i, d) in r.displacements.iter().enumerate() {
        for (c, v) in d.iter().enumerate() {
            finite(*v, || {
                format!(
                    "history[{stage}].nodes[{}].{}",
                    i + 1,
                    ["ux", "uy", "rz"][c]
                )
            })?;
        }
    }
    Ok(())
}

fn header(s: &State, points: usize, cells: usize, format: VtkFormat) -> Body {
    let mut b = Body::new(format);
    let text = format!(
        "<?xml version=\"1.0\"?>\n{}\
         \x20 <UnstructuredGrid>\n\
         \x20   <FieldData>\n\
         \x20     <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray>\n\
         \x20     <DataArray type=\"Int32\" Name=\"stage\" NumberOfTuples=\"1\" format=\"ascii\">{}</DataArray>\n\
         \x20   </FieldData>\n\
         \x20   <Piece NumberOfPoints=\"{points}\" NumberOfCells=\"{cells}\">\n",
        b.file_tag(),
        Num(s.t),
        s.stage
    );
    b.push_str(&text);
    b.note_value("TimeValue", Some(s.t).filter(|t| !t.is_finite()));
    b
}

/// The end of an unstructured grid (the [`Body`] adds the appended data and `</VTKFile>`).
const FOOTER: &str = "    </Piece>\n  </UnstructuredGrid>\n";

/// A number in the text of the path's frames ([`crate::vtk::num`]: the shortest that reads
/// back as the same `f64`).
struct Num(f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut s = Vec::new();
        crate::vtk::num(&mut s, self.0);
        f.write_str(std::str::from_utf8(&s).unwrap_or("NaN"))
    }
}

/// A data array of `ty`, its tuples one a line (as text); integer types hold integers.
fn array(
    b: &mut Body,
    ty: &str,
    name: &str,
    components: usize,
    values: impl IntoIterator<Item = f64>,
) {
    let head = format!(
        "        <DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{components}\""
    );
    if !b.is_ascii() {
        b.binary_array(&head, name, ty, values);
        return;
    }
    let out = &mut b.xml;
    out.extend_from_slice(head.as_bytes());
    out.extend_from_slice(b" format=\"ascii\">");
    // The first non-finite value, refused by `Body::finish` (checked as written, as in the
    // binary arrays).
    let mut bad = None;
    for (k, v) in values.into_iter().enumerate() {
        out.push(if k % components.max(1) == 0 {
            b'\n'
        } else {
            b' '
        });
        if !v.is_finite() && bad.is_none() {
            bad = Some(v);
        }
        if ty == "Float64" {
            crate::vtk::num(out, v);
        } else {
            out.extend_from_slice(itoa::Buffer::new().format(v as i64).as_bytes());
        }
    }
    out.extend_from_slice(b"\n        </DataArray>\n");
    b.note_value(name, bad);
}

fn cells(out: &mut Body, connectivity: Vec<usize>, offsets: Vec<usize>, types: Vec<u8>) {
    let f = |v: Vec<usize>| v.into_iter().map(|x| x as f64);
    out.push_str("      <Cells>\n");
    array(out, "Int64", "connectivity", 1, f(connectivity));
    array(out, "Int64", "offsets", 1, f(offsets));
    array(out, "UInt8", "types", 1, types.into_iter().map(f64::from));
    out.push_str("      </Cells>\n");
}

fn mesh_vtu(model: &Model, s: &State, format: VtkFormat) -> Body {
    let nodes = model.nodes();
    let elements = model.elements();
    let mut out = header(s, nodes.len(), elements.len(), format);
    let disp = |i: usize| s.results.map_or([0.0; 3], |r| r.displacements[i]);
    out.push_str("      <PointData Vectors=\"displacement\">\n");
    array(
        &mut out,
        "Float64",
        "displacement",
        3,
        (0..nodes.len()).flat_map(|i| {
            let d = disp(i);
            [d[0], d[1], 0.0]
        }),
    );
    array(
        &mut out,
        "Float64",
        "rotation",
        1,
        (0..nodes.len()).map(|i| disp(i)[2]),
    );
    out.push_str("      </PointData>\n      <Points>\n");
    array(
        &mut out,
        "Float64",
        "Points",
        3,
        nodes.iter().flat_map(|&[x, y]| [x, y, 0.0]),
    );
    out.push_str("      </Points>\n");
    let (mut conn, mut offs, mut types) = (Vec::new(), Vec::new(), Vec::new());
    for e in elements {
        let (ns, ty): (&[unilateral_fem::NodeId], u8) = match e {
            Element::Frame { nodes, .. } | Element::Bar { nodes, .. } => (nodes, 3),
            Element::Plane { nodes, .. } => (nodes, 9),
            Element::Triangle { nodes, .. } => (nodes, 5),
        };
        conn.extend(ns.iter().map(|n| n.0));
        offs.push(conn.len());
        types.push(ty);
    }
    cells(&mut out, conn, offs, types);
    out.push_str("      <CellData Scalars=\"element\">\n");
    array(
        &mut out,
        "Int64",
        "element",
        1,
        (0..elements.len()).map(|e| e as f64),
    );
    out.push_str("      </CellData>\n");
    out.push_str(FOOTER);
    out
}

fn state_code(s: PairState) -> u8 {
    match s {
        PairState::Open => 0,
        PairState::Stick => 1,
        PairState::SlipPlus => 2,
        PairState::SlipMinus => 3,
    }
}

fn pairs_vtu(model: &Model, gaps: &[f64], s: &State, format: VtkFormat) -> Body {
    let specs = model.pairs();
    let m = specs.len();
    // Points 0..m are the B nodes; the A nodes of node-to-node pairs follow.
    // A point `(n1, n2, ξ)` is `(1 − ξ)·n1 + ξ·n2` (the A point of a node-to-segment pair).
    let mut point_node: Vec<(usize, usize, f64)> =
        specs.iter().map(|p| (p.b.0, p.b.0, 0.0)).collect();
    let (mut conn, mut offs, mut types) = (Vec::new(), Vec::new(), Vec::new());
    for (i, p) in specs.iter().enumerate() {
        match p.a {
            Endpoint::Ground => types.push(1u8),
            Endpoint::Node(n) => {
                conn.push(point_node.len());
                point_node.push(match p.segment {
                    Some((a2, xi)) => (n.0, a2.0, xi),
                    None => (n.0, n.0, 0.0),
                });
                types.push(3u8);
            }
        }
        conn.push(i);
        offs.push(conn.len());
    }
    let mut out = header(s, point_node.len(), m, format);
    out.push_str("      <Points>\n");
    let nodes = model.nodes();
    array(
        &mut out,
        "Float64",
        "Points",
        3,
        point_node.iter().flat_map(|&(n1, n2, xi)| {
            let ([x1, y1], [x2, y2]) = (nodes[n1], nodes[n2]);
            [(1.0 - xi) * x1 + xi * x2, (1.0 - xi) * y1 + xi * y2, 0.0]
        }),
    );
    out.push_str("      </Points>\n");
    cells(&mut out, conn, offs, types);
    out.push_str("      <CellData Scalars=\"state\">\n");
    // The unloaded start: no force, no slip, every pair at its initial gap (`z_n = gap`).
    let at = |i: usize| s.pairs.and_then(|p| p.get(i));
    let start = |i: usize| PairResult {
        name: String::new(),
        x_n: 0.0,
        x_t: 0.0,
        z_n: gaps.get(i).copied().unwrap_or(0.0),
        z_t: 0.0,
        state: if gaps.get(i).is_some_and(|g| *g > 0.0) {
            PairState::Open
        } else {
            PairState::Stick
        },
    };
    array(
        &mut out,
        "UInt8",
        "state",
        1,
        (0..m).map(|i| {
            f64::from(at(i).map_or_else(|| state_code(start(i).state), |r| state_code(r.state)))
        }),
    );
    for (name, f) in [
        ("x_n", (|r: &PairResult| r.x_n) as fn(&PairResult) -> f64),
        ("x_t", |r| r.x_t),
        ("z_n", |r| r.z_n),
        ("z_t", |r| r.z_t),
    ] {
        array(
            &mut out,
            "Float64",
            name,
            1,
            (0..m).map(|i| at(i).map_or_else(|| f(&start(i)), f)),
        );
    }
    array(&mut out, "Int64", "pair", 1, (0..m).map(|i| i as f64));
    out.push_str("      </CellData>\n");
    out.push_str(FOOTER);
    out
}

#[cfg(test)]
mod tests {
    use super::{array, header, State};
    use crate::vtk::VtkFormat;

    /// The first non-finite value of an ascii array, or a non-finite load in the header, is
    /// refused by `finish`, named by its array (checked as written, not read back); a finite
    /// file passes. Each case in ascii and in binary.
    #[test]
    fn non_finite_numbers_of_history_files_are_refused() {
        let state = |t: f64| State {
            t,
            stage: 2,
            pairs: None,
            results: None,
        };
        for format in [VtkFormat::Ascii, VtkFormat::Binary] {
            let mut b = header(&state(0.5), 2, 1, format);
            array(&mut b, "Float64", "u", 2, [1.0, -2.5e-3, 0.0, 3.0]);
            array(&mut b, "Int64", "k", 1, [3.0, 4.0]);
            assert!(b.finish("h.vtu").is_ok(), "{format:?}");
            for (t, values, name) in [
                (0.5, [1.0, f64::NAN, f64::INFINITY, 0.0], "u"),
                (f64::NEG_INFINITY, [1.0; 4], "TimeValue"),
            ] {
                let mut b = header(&state(t), 2, 1, format);
                array(&mut b, "Float64", "u", 2, values);
                let e = b.finish("h.vtu").unwrap_err();
                let n = crate::NonFiniteOutput::in_io_error(&e).expect("a NonFiniteOutput");
                assert_eq!(
                    n.field,
                    format!("the data array \"{name}\" in h.vtu"),
                    "{format:?}"
                );
            }
        }
    }
}
