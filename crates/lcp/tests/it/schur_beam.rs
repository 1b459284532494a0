//! A continuous beam on `m` frictional elastic bearings as a Schur-complement LCP: the
//! beam's nodes (spans 1 m) each on a sole held by a vertical and a horizontal spring, a
//! contact pair between sole and beam. Written from the formulation (formulation.md §2–3)
//! independently of the finite-element crate: the links' dislocations are the contact DOFs
//! (`u_beam = u_sole + δ_t`, `v_beam = v_sole + δ_n`), the soles' DOFs and the beam's
//! rotations the others.

use faer::sparse::{SparseColMat, Triplet};
use unilateral_lcp::SchurLcp;

/// The beam's data: `EA`, `EI`, the springs' stiffnesses, the soles' tie `EA`.
pub struct BeamData {
    pub ea: f64,
    pub ei: f64,
    pub k_vertical: f64,
    pub k_horizontal: f64,
    pub tie_ea: f64,
    pub friction: f64,
    /// Units: forces multiplied by `force`, lengths by `length`.
    pub force: f64,
    pub length: f64,
}

impl Default for BeamData {
    fn default() -> Self {
        Self {
            ea: 1.5e10,
            ei: 1.2e9,
            k_vertical: 1e9,
            k_horizontal: 2e6,
            tie_ea: 2e4,
            friction: 0.3,
            force: 1.0,
            length: 1.0,
        }
    }
}

/// The beam on `m` bearings with a dead load of 1e4 N a node down and a variable load of
/// 1e3 N a node horizontally and from 4e4 N down to 1e4 N up along the beam.
pub fn beam_schur(m: usize, data: &BeamData) -> SchurLcp {
    let (fu, lu) = (data.force, data.length);
    // Transformed DOFs: interior (us_i, vs_i, θ_i) at 3i.., links δn_i at 3m + i, δt_i at 4m + i.
    let ni = 3 * m;
    let nz = 2 * m;
    let us = |i: usize| 3 * i;
    let vs = |i: usize| 3 * i + 1;
    let th = |i: usize| 3 * i + 2;
    let dn = |i: usize| ni + i;
    let dt = |i: usize| ni + m + i;
    // Original DOFs as combinations of transformed ones.
    #[derive(Clone, Copy)]
    enum Dof {
        U(usize),
        V(usize),
        Th(usize),
        Us(usize),
        Vs(usize),
    }
    let map = |d: Dof| -> Vec<(usize, f64)> {
        match d {
            Dof::U(i) => vec![(us(i), 1.0), (dt(i), 1.0)],
            Dof::V(i) => vec![(vs(i), 1.0), (dn(i), 1.0)],
            Dof::Th(i) => vec![(th(i), 1.0)],
            Dof::Us(i) => vec![(us(i), 1.0)],
            Dof::Vs(i) => vec![(vs(i), 1.0)],
        }
    };
    let mut k: Vec<Triplet<usize, usize, f64>> = Vec::new();
    let mut add = |dofs: &[Dof], ke: &[&[f64]]| {
        for (a, &da) in dofs.iter().enumerate() {
            for (b, &db) in dofs.iter().enumerate() {
                for &(ta, ca) in &map(da) {
                    for &(tb, cb) in &map(db) {
                        k.push(Triplet::new(ta, tb, ca * cb * ke[a][b]));
                    }
                }
            }
        }
    };
    let l = lu;
    let (ea, ei) = (data.ea * fu, data.ei * fu * lu * lu);
    for e in 0..m - 1 {
        let a = ea / l;
        add(&[Dof::U(e), Dof::U(e + 1)], &[&[a, -a], &[-a, a]]);
        let c0 = 12.0 * ei / (l * l * l);
        let c1 = 6.0 * ei / (l * l);
        let c2 = 4.0 * ei / l;
        let c3 = 2.0 * ei / l;
        add(
            &[Dof::V(e), Dof::Th(e), Dof::V(e + 1), Dof::Th(e + 1)],
            &[
                &[c0, c1, -c0, c1],
                &[c1, c2, -c1, c3],
                &[-c0, -c1, c0, -c1],
                &[c1, c3, -c1, c2],
            ],
        );
        let t = data.tie_ea * fu / l;
        add(&[Dof::Us(e), Dof::Us(e + 1)], &[&[t, -t], &[-t, t]]);
    }
    for i in 0..m {
        add(&[Dof::Us(i)], &[&[data.k_horizontal * fu / lu]]);
        add(&[Dof::Vs(i)], &[&[data.k_vertical * fu / lu]]);
    }
    let ntot = ni + nz;
    let kt = SparseColMat::<usize, f64>::try_new_from_triplets(ntot, ntot, &k).unwrap();
    // Loads on the original DOFs, transformed: b' = Pᵀ b.
    let mut bc = vec![0.0; ntot];
    let mut bv = vec![0.0; ntot];
    for i in 0..m {
        let s = if m > 1 {
            i as f64 / (m - 1) as f64
        } else {
            0.0
        };
        for &(t, c) in &map(Dof::V(i)) {
            bc[t] += c * -1e4 * fu;
            bv[t] += c * (-4e4 + 5e4 * s) * fu;
        }
        for &(t, c) in &map(Dof::U(i)) {
            bv[t] += c * 1e3 * fu;
        }
    }
    let f = data.friction;
    // T (3m × 2m) and U (2m × 3m) of formulation.md §3, by the link `z` (normal `i`,
    // tangential `m + i`): the rows of T in its column `z`, the columns of U in its row `z`.
    let t_col = |z: usize| -> Vec<(usize, f64)> {
        let i = z % m;
        if z < m {
            vec![(i, 1.0), (m + i, f), (2 * m + i, f)]
        } else {
            vec![(m + i, 1.0), (2 * m + i, -1.0)]
        }
    };
    let u_row = |z: usize| -> Vec<(usize, f64)> {
        let i = z % m;
        if z < m {
            vec![(i, 1.0)]
        } else {
            vec![(m + i, 0.5), (2 * m + i, -0.5)]
        }
    };
    let n = 3 * m;
    let (mut ta, mut tb, mut tc, mut td) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for j in 0..ntot {
        for (&i, &v) in kt.row_idx_of_col_raw(j).iter().zip(kt.val_of_col(j)) {
            match (i < ni, j < ni) {
                (true, true) => ta.push(Triplet::new(i, j, v)),
                (true, false) => {
                    for (c, w) in u_row(j - ni) {
                        tb.push(Triplet::new(i, c, v * w));
                    }
                }
                (false, true) => {
                    for (r, w) in t_col(i - ni) {
                        tc.push(Triplet::new(r, j, w * v));
                    }
                }
                (false, false) => {
                    for (r, wr) in t_col(i - ni) {
                        for (c, wc) in u_row(j - ni) {
                            td.push(Triplet::new(r, c, wr * v * wc));
                        }
                    }
                }
            }
        }
    }
    let sparse = |r: usize, c: usize, t: &[Triplet<usize, usize, f64>]| {
        SparseColMat::<usize, f64>::try_new_from_triplets(r, c, t).unwrap()
    };
    let tz = |b: &[f64]| -> Vec<f64> {
        let mut out = vec![0.0; n];
        for z in 0..nz {
            for (r, w) in t_col(z) {
                out[r] -= w * b[ni + z];
            }
        }
        out
    };
    SchurLcp {
        a: sparse(ni, ni, &ta),
        b: sparse(ni, n, &tb),
        c: sparse(n, ni, &tc),
        d: sparse(n, n, &td),
        q0: tz(&bc),
        qa: bc[..ni].iter().map(|v| -v).collect(),
        d0: tz(&bv),
        da: bv[..ni].iter().map(|v| -v).collect(),
    }
}

/// The dense problem of `lcp` formed as the contact crate forms it from a contact zone: `R`
/// and `R_F` read off the normal and `+` blocks of `M = D − C A⁻¹ B`, then
/// `M = [Rnn, Rnt/2, −Rnt/2; F·Rnn ± Rtn, (F·Rnt ± Rtt)/2, …]` and `q`, `d` likewise
/// (formulation.md §3), so that each pair's friction rows add up to `2f` times its normal row
/// to round-off of those terms, as the engine's row relations expect.
pub fn contact_dense(lcp: &SchurLcp, friction: f64) -> unilateral_lcp::ParametricLcp {
    let p = lcp.dense();
    let n = p.q0.len();
    let m = n / 3;
    let f = friction;
    let rnn = |i: usize, j: usize| p.m[(i, j)];
    let rnt = |i: usize, j: usize| 2.0 * p.m[(i, m + j)];
    let rtn = |i: usize, j: usize| p.m[(m + i, j)] - f * rnn(i, j);
    let rtt = |i: usize, j: usize| 2.0 * p.m[(m + i, m + j)] - f * rnt(i, j);
    let mm = faer::Mat::<f64>::from_fn(n, n, |r, c| {
        let (bi, i) = (r / m, r % m);
        let (bj, j) = (c / m, c % m);
        let (top, plus, minus) = match bj {
            0 => (
                rnn(i, j),
                f * rnn(i, j) + rtn(i, j),
                f * rnn(i, j) - rtn(i, j),
            ),
            1 => (
                rnt(i, j) / 2.0,
                (f * rnt(i, j) + rtt(i, j)) / 2.0,
                (f * rnt(i, j) - rtt(i, j)) / 2.0,
            ),
            _ => (
                -rnt(i, j) / 2.0,
                -(f * rnt(i, j) + rtt(i, j)) / 2.0,
                -(f * rnt(i, j) - rtt(i, j)) / 2.0,
            ),
        };
        [top, plus, minus][bi]
    });
    let vector = |v: &[f64]| -> Vec<f64> {
        let (vn, vt): (Vec<f64>, Vec<f64>) = (0..m).map(|i| (v[i], v[m + i] - f * v[i])).unzip();
        (0..n)
            .map(|r| {
                let i = r % m;
                [vn[i], f * vn[i] + vt[i], f * vn[i] - vt[i]][r / m]
            })
            .collect()
    };
    unilateral_lcp::ParametricLcp {
        m: mm,
        q0: vector(&p.q0),
        d: vector(&p.d),
    }
}

/// The contact crate's lexicographic order (tangential rows first) and each pair's friction
/// relation `x_t+ + x_t- − 2f·x_n = 0`, for `m` pairs of friction `f`.
pub fn contact_order_and_relations(
    m: usize,
    f: f64,
) -> (Vec<usize>, Vec<unilateral_lcp::RowRelation>) {
    let relations = (0..m)
        .map(|i| unilateral_lcp::RowRelation {
            terms: vec![(m + i, 1.0), (2 * m + i, 1.0), (i, -2.0 * f)],
        })
        .collect();
    ((m..3 * m).chain(0..m).collect(), relations)
}
