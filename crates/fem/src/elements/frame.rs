//! Two-node line elements: the Euler–Bernoulli frame (3 DOF per node, optional end hinges)
//! and the pin-jointed bar (axial force only), with their distributed, body and temperature
//! loads and their end forces and internal force diagrams.

use super::dense::condense_dofs;
use super::{positive, ElementUnit, Recovered};
use crate::error::FemError;
use crate::model::{ElementId, FrameSection, Load, LoadFrame, Model, NodeId, Releases};
use crate::results::{DiagramPoint, LineResult, DIAGRAM_SAMPLES};

/// A frame ([`crate::Element::Frame`], `releases` given) or a bar ([`crate::Element::Bar`],
/// `releases` `None`): two nodes and a section.
#[derive(Clone, Copy)]
pub(crate) struct Line<'a> {
    pub nodes: &'a [NodeId; 2],
    pub section: &'a FrameSection,
    pub releases: Option<Releases>,
}

impl Line<'_> {
    fn is_frame(&self) -> bool {
        self.releases.is_some()
    }

    fn check(&self, model: &Model, id: ElementId) -> Result<(), FemError> {
        let (nodes, section) = (self.nodes, self.section);
        let [a, b] = [model.nodes[nodes[0].0], model.nodes[nodes[1].0]];
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let scale = a[0].abs().max(a[1].abs()).max(b[0].abs()).max(b[1].abs());
        if len <= 1e-12 * scale.max(1e-300) || len == 0.0 {
            return Err(FemError::ZeroLength {
                element: id,
                a: nodes[0],
                b: nodes[1],
            });
        }
        positive(id, "E", section.e)?;
        positive(id, "A", section.area)?;
        if self.is_frame() {
            positive(id, "I", section.inertia)?;
        }
        // The stiffnesses E·A/L and E·I/L³, by their binary exponents (their products could
        // underflow on the way): below the normal range the element would stiffen nothing (a
        // member at x = 4e150 read as a mechanism).
        let lg = |v: f64| v.log2();
        let axial = lg(section.e) + lg(section.area) - lg(len);
        let bending = lg(section.e) + lg(section.inertia) - 3.0 * lg(len);
        let floor = f64::MIN_POSITIVE.log2();
        if axial < floor || (self.is_frame() && bending < floor) {
            return Err(FemError::Underflow {
                element: Some(id),
                what: if axial < floor {
                    "its axial stiffness E·A/L".into()
                } else {
                    "its bending stiffness E·I/L³".into()
                },
            });
        }
        if !section.alpha.is_finite() || !section.depth.is_finite() {
            return Err(FemError::NotFinite {
                what: format!("section of element {}", id.0),
            });
        }
        Ok(())
    }

    /// Local stiffness after releases (6 × 6 or 4 × 4), with (L, c, s).
    ///
    /// On the stack: a structure's frames are recovered at every frame of a load path.
    fn local_k(&self, model: &Model) -> ([f64; 36], usize, f64, f64, f64) {
        let (nodes, section) = (self.nodes, self.section);
        let (l, c, s) = line_geometry(model, nodes[0].0, nodes[1].0);
        match self.releases {
            Some(releases) => {
                let mut k = frame_local_k(section.e, section.area, section.inertia, l);
                let (drop, nd) = release_dofs(releases);
                condense_dofs(&mut k, 6, None, &drop[..nd]);
                (k, 6, l, c, s)
            }
            None => {
                let ea = section.e * section.area / l;
                let mut k = [0.0; 36];
                k[0] = ea;
                k[2] = -ea;
                k[2 * 4] = -ea;
                k[2 * 4 + 2] = ea;
                (k, 4, l, c, s)
            }
        }
    }

    /// What the recovery of the element's end forces and diagram needs that does not depend
    /// on its displacements or its loads' factors: the local stiffness and geometry, and each
    /// of `loads` (in their order) as local equivalent nodal forces and local intensities.
    /// Kept by a structure whose frames are recovered at every frame of a load path.
    pub(crate) fn prepare<'l>(
        &self,
        model: &Model,
        loads: impl Iterator<Item = &'l Load>,
    ) -> LinePrepared {
        let (k, n, l, c, s) = self.local_k(model);
        let loads = loads
            .map(|load| PreparedLoad {
                local: self
                    .equivalent_load_array(model, load)
                    .map(|(fe, _)| to_local_vec(&fe[..n], c, s)),
                integrals: line_local_intensity(load, c, s).map(|(q1, q2)| {
                    let (da, dt) = ((q2[0] - q1[0]) / l, (q2[1] - q1[1]) / l);
                    std::array::from_fn(|i| {
                        let x = sample_at(l, i);
                        // ∫0^x q, ∫0^x q(x − s) ds for linear q
                        [
                            q1[0] * x + da * x * x / 2.0,
                            q1[1] * x + dt * x * x / 2.0,
                            q1[1] * x * x / 2.0 + dt * x.powi(3) / 6.0,
                        ]
                    })
                }),
            })
            .collect();
        LinePrepared {
            k,
            n,
            samples: std::array::from_fn(|i| sample_at(l, i)),
            c,
            s,
            loads,
        }
    }

    fn dofs(&self) -> Vec<usize> {
        if self.is_frame() {
            self.nodes
                .iter()
                .flat_map(|n| [3 * n.0, 3 * n.0 + 1, 3 * n.0 + 2])
                .collect()
        } else {
            self.nodes
                .iter()
                .flat_map(|n| [3 * n.0, 3 * n.0 + 1])
                .collect()
        }
    }

    fn stiffness(&self, model: &Model) -> Vec<f64> {
        let (k, n, _, c, s) = self.local_k(model);
        to_global_mat(&k[..n * n], n, c, s)
    }

    fn equivalent_load(&self, model: &Model, load: &Load) -> Option<Vec<f64>> {
        self.equivalent_load_array(model, load)
            .map(|(f, n)| f[..n].to_vec())
    }

    /// [`Line::equivalent_load`] on the stack: the global vector (6 for a frame, 4 for a bar)
    /// in the first `n` entries.
    fn equivalent_load_array(&self, model: &Model, load: &Load) -> Option<([f64; 6], usize)> {
        let section = self.section;
        let is_frame = self.is_frame();
        let (l, c, s) = line_geometry(model, self.nodes[0].0, self.nodes[1].0);
        let mut f = [0.0; 6];
        if let Some((q1, q2)) = line_local_intensity(load, c, s) {
            // 3-point Gauss on [0, 1]: exact for linear load × cubic shape.
            let g = (0.6f64).sqrt();
            for (xi, w) in [
                (0.5 * (1.0 - g), 5.0 / 18.0),
                (0.5, 8.0 / 18.0),
                (0.5 * (1.0 + g), 5.0 / 18.0),
            ] {
                let qa = q1[0] + (q2[0] - q1[0]) * xi;
                let qt = q1[1] + (q2[1] - q1[1]) * xi;
                let wl = w * l;
                f[0] += wl * qa * (1.0 - xi);
                f[3] += wl * qa * xi;
                if is_frame {
                    f[1] += wl * qt * (1.0 - 3.0 * xi * xi + 2.0 * xi.powi(3));
                    f[2] += wl * qt * l * (xi - 2.0 * xi * xi + xi.powi(3));
                    f[4] += wl * qt * (3.0 * xi * xi - 2.0 * xi.powi(3));
                    f[5] += wl * qt * l * (-xi * xi + xi.powi(3));
                } else {
                    f[1] += wl * qt * (1.0 - xi);
                    f[4] += wl * qt * xi;
                }
            }
        } else if let Load::Temperature {
            uniform, gradient, ..
        } = *load
        {
            let n_th = section.e * section.area * section.alpha * uniform;
            f[0] -= n_th;
            f[3] += n_th;
            if is_frame && gradient != 0.0 {
                // thermal curvature κ = −α·ΔT/h (hotter +y face elongates).
                let m_th = section.e * section.inertia * section.alpha * gradient / section.depth;
                f[2] += m_th;
                f[5] -= m_th;
            }
        } else {
            return None;
        }
        let (mut fl, n) = if is_frame {
            (f, 6)
        } else {
            ([f[0], f[1], f[3], f[4], 0.0, 0.0], 4)
        };
        if let Some(releases) = self.releases {
            let mut k0 = frame_local_k(section.e, section.area, section.inertia, l);
            let (drop, nd) = release_dofs(releases);
            condense_dofs(&mut k0, 6, Some(&mut fl[..n]), &drop[..nd]);
        }
        Some((to_global_vec(&fl[..n], c, s), n))
    }

    fn recover(
        &self,
        model: &Model,
        id: ElementId,
        ue: &[f64],
        loads: &[(f64, &Load)],
    ) -> Recovered {
        self.prepare(model, loads.iter().map(|&(_, load)| load))
            .recover(id, ue, loads.iter().map(|&(fc, _)| fc))
    }
}

impl ElementUnit for Line<'_> {
    fn nodes(&self) -> &[NodeId] {
        self.nodes
    }
    fn dofs(&self) -> Vec<usize> {
        Line::dofs(self)
    }
    fn rotation_nodes(&self) -> Vec<NodeId> {
        match self.releases {
            Some(r) => [
                (!r.start).then_some(self.nodes[0]),
                (!r.end).then_some(self.nodes[1]),
            ]
            .into_iter()
            .flatten()
            .collect(),
            None => Vec::new(),
        }
    }
    fn check(&self, model: &Model, id: ElementId) -> Result<(), FemError> {
        Line::check(self, model, id)
    }
    fn refuses(&self, load: &Load) -> Option<String> {
        match *load {
            Load::Temperature { gradient, .. } if gradient != 0.0 => {
                if !self.is_frame() {
                    Some("a temperature gradient applies to frames only".into())
                } else if self.section.depth > 0.0 {
                    None
                } else {
                    Some("a temperature gradient needs the section depth > 0".into())
                }
            }
            _ => None,
        }
    }
    fn stiffness(&self, model: &Model) -> Vec<f64> {
        Line::stiffness(self, model)
    }
    fn equivalent_load(&self, model: &Model, load: &Load) -> Option<Vec<f64>> {
        Line::equivalent_load(self, model, load)
    }
    fn recover(
        &self,
        model: &Model,
        id: ElementId,
        ue: &[f64],
        loads: &[(f64, &Load)],
    ) -> Recovered {
        Line::recover(self, model, id, ue, loads)
    }
}

/// Geometry of a two-node line element: length, cos, sin.
pub(crate) fn line_geometry(model: &Model, a: usize, b: usize) -> (f64, f64, f64) {
    let (pa, pb) = (model.nodes[a], model.nodes[b]);
    let (dx, dy) = (pb[0] - pa[0], pb[1] - pa[1]);
    let l = dx.hypot(dy);
    (l, dx / l, dy / l)
}

/// Local frame stiffness (u1, v1, θ1, u2, v2, θ2), before releases.
fn frame_local_k(e: f64, a: f64, i: f64, l: f64) -> [f64; 36] {
    let mut k = [0.0; 36];
    let ea = e * a / l;
    let (b1, b2, b3, b4) = (
        12.0 * e * i / l.powi(3),
        6.0 * e * i / (l * l),
        4.0 * e * i / l,
        2.0 * e * i / l,
    );
    let mut set = |r: usize, c: usize, v: f64| {
        k[r * 6 + c] = v;
        k[c * 6 + r] = v;
    };
    set(0, 0, ea);
    set(3, 3, ea);
    set(0, 3, -ea);
    set(1, 1, b1);
    set(4, 4, b1);
    set(1, 4, -b1);
    set(1, 2, b2);
    set(1, 5, b2);
    set(2, 4, -b2);
    set(4, 5, -b2);
    set(2, 2, b3);
    set(5, 5, b3);
    set(2, 5, b4);
    k
}

/// The released rotations of a frame, in the first `nd` entries.
fn release_dofs(r: Releases) -> ([usize; 2], usize) {
    let mut d = [0; 2];
    let mut nd = 0;
    if r.start {
        d[nd] = 2;
        nd += 1;
    }
    if r.end {
        d[nd] = 5;
        nd += 1;
    }
    (d, nd)
}

/// Rotates a local 6-vector (frame) or 4-vector (bar) to global (in the first `v.len()`
/// entries).
fn to_global_vec(v: &[f64], c: f64, s: f64) -> [f64; 6] {
    let mut g = [0.0; 6];
    g[..v.len()].copy_from_slice(v);
    let step = if v.len() == 6 { 3 } else { 2 };
    for node in 0..2 {
        let o = node * step;
        g[o] = c * v[o] - s * v[o + 1];
        g[o + 1] = s * v[o] + c * v[o + 1];
    }
    g
}

/// Rotates a global 6-vector (frame) or 4-vector (bar) to local (in the first `v.len()`
/// entries).
pub(crate) fn to_local_vec(v: &[f64], c: f64, s: f64) -> [f64; 6] {
    let mut g = [0.0; 6];
    g[..v.len()].copy_from_slice(v);
    let step = if v.len() == 6 { 3 } else { 2 };
    for node in 0..2 {
        let o = node * step;
        g[o] = c * v[o] + s * v[o + 1];
        g[o + 1] = -s * v[o] + c * v[o + 1];
    }
    g
}

/// `Tᵀ k T` for a local line-element matrix.
fn to_global_mat(k: &[f64], n: usize, c: f64, s: f64) -> Vec<f64> {
    // T is block diagonal with [[c, s], [-s, c]] on the translations.
    let mut t = vec![0.0; n * n];
    let step = if n == 6 { 3 } else { 2 };
    for node in 0..2 {
        let o = node * step;
        t[o * n + o] = c;
        t[o * n + o + 1] = s;
        t[(o + 1) * n + o] = -s;
        t[(o + 1) * n + o + 1] = c;
        if step == 3 {
            t[(o + 2) * n + o + 2] = 1.0;
        }
    }
    // Tᵀ (k T): two products of small row-major matrices, `a` read transposed or not.
    let product = |a: &[f64], a_transposed: bool, b: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                out[i * n + j] = (0..n)
                    .map(|m| {
                        let aim = if a_transposed {
                            a[m * n + i]
                        } else {
                            a[i * n + m]
                        };
                        aim * b[m * n + j]
                    })
                    .sum();
            }
        }
        out
    };
    product(&t, true, &product(k, false, &t))
}

/// A line element prepared for recovery ([`Line::prepare`]).
#[derive(Debug, Clone)]
pub(crate) struct LinePrepared {
    /// Local stiffness after releases (`n × n` in the first entries).
    k: [f64; 36],
    n: usize,
    /// The diagram's sample positions.
    samples: [f64; DIAGRAM_SAMPLES],
    c: f64,
    s: f64,
    loads: Vec<PreparedLoad>,
}

/// One load of a prepared line element: its local equivalent nodal forces (per unit factor)
/// and, for a load with intensities, at each of the diagram's samples `x` the integrals of its
/// local intensities (per unit factor): `∫0^x q_axial`, `∫0^x q_transverse` and
/// `∫0^x q_transverse(x − s) ds` — what each recovery multiplies by the load's factor.
#[derive(Debug, Clone)]
struct PreparedLoad {
    local: Option<[f64; 6]>,
    integrals: Option<[[f64; 3]; DIAGRAM_SAMPLES]>,
}

/// The `i`-th of the diagram's samples along an element of length `l`.
fn sample_at(l: f64, i: usize) -> f64 {
    l * i as f64 / (DIAGRAM_SAMPLES - 1) as f64
}

impl LinePrepared {
    /// End forces and diagram for the element displacements `ue` (global, the element's DOF
    /// order) with the factors of the prepared loads, in their order.
    pub(crate) fn recover(
        &self,
        id: ElementId,
        ue: &[f64],
        factors: impl ExactSizeIterator<Item = f64> + Clone,
    ) -> Recovered {
        assert_eq!(
            factors.len(),
            self.loads.len(),
            "a factor for every prepared load of element {}",
            id.0
        );
        let (k, n, c, s) = (&self.k, self.n, self.c, self.s);
        let ul = to_local_vec(ue, c, s);
        let mut fl = [0.0; 6];
        for (fc, load) in factors.clone().zip(&self.loads) {
            if let Some(fe) = &load.local {
                for a in 0..n {
                    fl[a] += fc * fe[a];
                }
            }
        }
        let mut end = [0.0; 6];
        for a in 0..n {
            end[a] = (0..n).map(|b| k[a * n + b] * ul[b]).sum::<f64>() - fl[a];
        }
        let end6 = if n == 6 {
            [end[0], end[1], end[2], end[3], end[4], end[5]]
        } else {
            [end[0], end[1], 0.0, end[2], end[3], 0.0]
        };
        let mut diagram = self.samples.map(|x| DiagramPoint {
            s: x,
            n: 0.0,
            q: 0.0,
            m: 0.0,
        });
        // The loads' integrals summed over the loads in their order, each times its factor
        // (`n`, `q`, `m` hold the sums until the end forces are added).
        for (fc, load) in factors.zip(&self.loads) {
            if let Some(integrals) = &load.integrals {
                for (d, g) in diagram.iter_mut().zip(integrals) {
                    d.n += fc * g[0];
                    d.q += fc * g[1];
                    d.m += fc * g[2];
                }
            }
        }
        for d in &mut diagram {
            let (ia, it, im) = (d.n, d.q, d.m);
            d.n = -end6[0] - ia;
            d.q = end6[1] + it;
            d.m = -end6[2] + end6[1] * d.s + im;
        }
        Recovered::Line(LineResult {
            element: id,
            end_forces: end6,
            diagram,
        })
    }
}

/// Local distributed load on a line element: intensities (axial, transverse) at start and end.
pub(crate) fn line_local_intensity(load: &Load, c: f64, s: f64) -> Option<([f64; 2], [f64; 2])> {
    let rot = |v: [f64; 2]| [c * v[0] + s * v[1], -s * v[0] + c * v[1]];
    match *load {
        Load::Distributed {
            start, end, frame, ..
        } => Some(match frame {
            LoadFrame::Local => (start, end),
            LoadFrame::Global => (rot(start), rot(end)),
        }),
        Load::BodyForce { force, .. } => {
            let f = rot(force);
            Some((f, f))
        }
        _ => None,
    }
}
