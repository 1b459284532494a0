//! The `3m` LCP of `formulation.md` §3 built from a contact zone.

use faer::Mat;
use rayon::prelude::*;
use unilateral_lcp::{ParametricLcp, Tightening, Var};

use crate::ContactZone;

/// The parametric LCP of a contact zone with its tightening direction and the lexicographic
/// order that keeps friction degeneracies from ending in a false mechanism.
#[derive(Debug, Clone)]
pub struct ContactLcp {
    /// `x = q_c + p·d + M z` with `x = [x_n; x_t+; x_t-]`, `z = [z_n; z_t+; z_t-]`.
    pub problem: ParametricLcp,
    /// `[1; max(1, f); max(1, f)]`: the tightening per row (§3).
    pub tightening_direction: Vec<f64>,
    /// Tangential rows before normal rows (see [`ContactLcp::build`]).
    pub lexicographic_order: Vec<usize>,
    /// Number of pairs `m`.
    pub pairs: usize,
    /// The friction coefficient of each pair.
    pub friction: Vec<f64>,
}

impl ContactLcp {
    /// Builds `M`, `d` and `q_c` exactly as `formulation.md` §3.
    ///
    /// Ties in the ratio test are broken as if the tangential rows were perturbed more than the
    /// normal rows: then `x_t+ + x_t- − 2f·x_n` stays positive under the perturbation, so a
    /// pressed pair can never have both friction parts vanish (the false mechanism that a plain
    /// row order produces when a pair opens exactly while slipping).
    pub fn build(zone: &ContactZone) -> Self {
        let m = zone.pairs();
        let f = &zone.friction;
        let n = 3 * m;
        let mut mm = Mat::<f64>::zeros(n, n);
        // Column by column (faer's storage order, every write contiguous), on the pool: column
        // `b·m + j` holds pair j's normal (b = 0) or friction part (1: +, 2: −), each entry
        // formed from its own data alone.
        mm.as_mut()
            .par_col_iter_mut()
            .enumerate()
            .for_each(|(c, mut col)| {
                let (b, j) = (c / m, c % m);
                for i in 0..m {
                    let fi = f[i];
                    let (top, plus, minus) = match b {
                        0 => {
                            let (nn, tn) = (zone.rnn[(i, j)], zone.rtn[(i, j)]);
                            (nn, fi * nn + tn, fi * nn - tn)
                        }
                        1 => {
                            let (nt, tt) = (zone.rnt[(i, j)], zone.rtt[(i, j)]);
                            (nt / 2.0, (fi * nt + tt) / 2.0, (fi * nt - tt) / 2.0)
                        }
                        _ => {
                            let (nt, tt) = (zone.rnt[(i, j)], zone.rtt[(i, j)]);
                            (-nt / 2.0, -(fi * nt + tt) / 2.0, -(fi * nt - tt) / 2.0)
                        }
                    };
                    col[i] = top;
                    col[m + i] = plus;
                    col[2 * m + i] = minus;
                }
            });
        let (q0, d) = load_vectors(zone);
        let dir = tightening_direction(f);
        let lexicographic_order = lexicographic_order(m);
        Self {
            problem: ParametricLcp { m: mm, q0, d },
            tightening_direction: dir,
            lexicographic_order,
            pairs: m,
            friction: f.clone(),
        }
    }

    /// The rows that the formulation ties exactly, one relation a pair with friction:
    /// `x_t+ + x_t- − 2f·x_n = (2·max(1, f) − 2f)·c`, because the rows of `M`, `d` and `q_c` of
    /// the two friction parts add up to `2f` times the normal row. Given to the engine, they
    /// decide the tie of a slipping pair's normal row and opposite friction row from the data.
    pub fn row_relations(&self) -> Vec<unilateral_lcp::RowRelation> {
        friction_relations(&self.friction)
    }

    /// The tightening of amount `c` in this problem's direction (`None` for `c = 0`).
    pub fn tightening(&self, c: f64) -> Option<Tightening> {
        (c > 0.0).then(|| Tightening {
            amount: c,
            direction: self.tightening_direction.clone(),
        })
    }

    /// The paper's label of an LCP variable: `x_n1`, `x_t1+`, `x_t1-`, `z_n1`, …, `p`.
    pub fn label(&self, var: Var) -> String {
        label(self.pairs, var)
    }
}

/// The paper's label of a variable of the `3m` LCP of `m` pairs: `x_n1`, `x_t1+`, `x_t1-`,
/// `z_n1`, …, `p`.
pub(crate) fn label(m: usize, var: Var) -> String {
    let part = |i: usize| match i / m {
        0 => format!("n{}", i % m + 1),
        1 => format!("t{}+", i % m + 1),
        _ => format!("t{}-", i % m + 1),
    };
    match var {
        Var::X(i) => format!("x_{}", part(i)),
        Var::Z(i) => format!("z_{}", part(i)),
        Var::Driver => "p".to_string(),
    }
}

/// `q_c` and `d` of the `3m` LCP of `zone` (`formulation.md` §3), without forming `M`: the
/// friction rows `f·R_n ± R_t` stacked under the normal ones, the constant loads less the link
/// forces `R·η` of the opened gaps. [`ContactLcp::build`] takes its vectors from here.
pub(crate) fn load_vectors(zone: &ContactZone) -> (Vec<f64>, Vec<f64>) {
    let m = zone.pairs();
    let f = &zone.friction;
    let stack = |rn: &[f64], rt: &[f64]| -> Vec<f64> {
        let mut v = Vec::with_capacity(3 * m);
        v.extend_from_slice(rn);
        v.extend((0..m).map(|i| f[i] * rn[i] + rt[i]));
        v.extend((0..m).map(|i| f[i] * rn[i] - rt[i]));
        v
    };
    let d = stack(&zone.variable.normal, &zone.variable.tangential);
    // Gaps: R_c ← R_c − R·η (normal and tangential link forces of the opened gaps).
    let mut rcn = zone.constant.normal.clone();
    let mut rct = zone.constant.tangential.clone();
    // The sizes of the terms of each sum, for its round-off.
    let mut sn: Vec<f64> = rcn.iter().map(|v| v.abs()).collect();
    let mut st: Vec<f64> = rct.iter().map(|v| v.abs()).collect();
    let mut gaps = false;
    for j in 0..m {
        let eta = zone.gap[j];
        if eta != 0.0 {
            gaps = true;
            for i in 0..m {
                rcn[i] -= zone.rnn[(i, j)] * eta;
                rct[i] -= zone.rtn[(i, j)] * eta;
                sn[i] += (zone.rnn[(i, j)] * eta).abs();
                st[i] += (zone.rtn[(i, j)] * eta).abs();
            }
        }
    }
    // Gaps that a rigid motion of a body held only by the pairs closes (a block over a base
    // with the same gap everywhere) have no forces: R·η cancels to the round-off of R, which
    // carries the condensation's (`roundoff_of_zero`: 1e-10·m of the entries, at most 1e-9
    // here so that the verified residuals stay far below their tolerance). Such a sum is zero;
    // a round-off "tension" of 1e-17 made the unloaded structure one that no equilibrium holds.
    if gaps {
        let rel = (1e-10 * m as f64).min(1e-9);
        for (v, s) in rcn.iter_mut().zip(&sn).chain(rct.iter_mut().zip(&st)) {
            if v.abs() <= rel * s {
                *v = 0.0;
            }
        }
    }
    (stack(&rcn, &rct), d)
}

/// `[1; max(1, f); max(1, f)]`: the tightening per row (§3).
pub(crate) fn tightening_direction(friction: &[f64]) -> Vec<f64> {
    let m = friction.len();
    let mut dir = vec![1.0; 3 * m];
    for (i, f) in friction.iter().enumerate() {
        dir[m + i] = f.max(1.0);
        dir[2 * m + i] = f.max(1.0);
    }
    dir
}

/// The rows of `m` pairs in the formulation's lexicographic priority: tangential rows before
/// normal rows (see [`ContactLcp::build`]).
pub(crate) fn lexicographic_order(m: usize) -> Vec<usize> {
    (m..3 * m).chain(0..m).collect()
}

/// Each pair's friction relation `x_t+ + x_t- − 2f·x_n` (see [`ContactLcp::row_relations`]).
pub(crate) fn friction_relations(friction: &[f64]) -> Vec<unilateral_lcp::RowRelation> {
    let m = friction.len();
    (0..m)
        .map(|i| {
            let mut terms = vec![(m + i, 1.0), (2 * m + i, 1.0)];
            if friction[i] != 0.0 {
                terms.push((i, -2.0 * friction[i]));
            }
            unilateral_lcp::RowRelation { terms }
        })
        .collect()
}
