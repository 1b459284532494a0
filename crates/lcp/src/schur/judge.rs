//! The structure's own equations as the judge of a load rate the dense engine cannot tell from
//! round-off.
//!
//! A condensed `M = D − C A⁻¹ B` carries the round-off of its condensation in every entry. Where
//! a segment of the path is a mechanism of the structure — a beam sliding on its bearings at
//! constant load, held sideways by springs a million times softer than itself — the formed
//! `M` gives the load a small rate (1e-10 of the column's largest on such beams) instead of
//! zero, the path runs on at that rate with slips of 1e10, and the answer beyond is refused. A
//! genuine soft spring gives a rate of the same size (1.2e-9 of its terms for a block on a
//! 300 N/m spring), so the condensed data cannot tell the two apart. The structure's sparse
//! equations can: there the sliding beam's equations are exact sums of its elements, and the
//! direction solved from them and refined in double-double arithmetic gives the load a rate of
//! round-off of the sums (a few `ε`) where the mechanism is real, and the spring's own where
//! it is not.

use std::sync::Mutex;

use faer::sparse::SparseColMat;

use super::bordered::Bordered;
use super::SchurLcp;

/// A load rate whose terms exceed it by more than this is zero: 2¹⁰ round-offs of the sums that
/// formed it. Measured: the sliding beams of the tests 1e-54 to 8e-18; the steel block on its
/// genuine 300 N/m spring 3.4e-10 (a spring softer than about 10⁻¹³ of the structure it holds
/// would be read as none).
const ZERO_LOAD_RATE: f64 = 1024.0 * f64::EPSILON;

/// What the structure's equations say of a direction (see [`StructureJudge::direction`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DirectionVerdict {
    /// The load's rate against the terms of the equations: the largest `w_i·|d_i·dp|` over the
    /// largest `w_i·Σ_j |a_ij v_j|`, each row weighted to common units ([`row_weights`]); zero
    /// where `dp` is within what the data's round-off makes of it.
    pub load: f64,
}

impl DirectionVerdict {
    /// The load has no rate beyond round-off of the structure's equations.
    pub fn load_holds(&self) -> bool {
        self.load <= ZERO_LOAD_RATE
    }
}

/// The structure's sparse equations, held to judge the dense engine's doubtful load rates
/// ([`crate::PathSolver::judged_on`]); the basis's factorisation is made when first asked
/// and kept for its column order.
pub struct StructureJudge {
    lcp: SchurLcp,
    basis: Mutex<Option<Bordered>>,
    /// The weights that make the equations' terms comparable whatever the units
    /// ([`row_weights`]).
    weights: Vec<f64>,
}

impl std::fmt::Debug for StructureJudge {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StructureJudge")
            .field("order", &self.lcp.order())
            .finish_non_exhaustive()
    }
}

impl StructureJudge {
    /// A judge on `lcp`, the same problem as the dense solver's (in the same units).
    pub fn new(lcp: SchurLcp) -> Self {
        Self {
            weights: row_weights(&lcp),
            lcp,
            basis: Mutex::new(None),
        }
    }

    /// The order of the problem judged.
    pub fn order(&self) -> usize {
        self.lcp.order()
    }

    /// The direction of the segment on which the non-basic `entering` grows from the basis
    /// `basic` (`2n + 1` flags, `n` set, the driver among them), solved from the structure's
    /// equations with residuals refined in double-double arithmetic; `None` where the basis is
    /// singular on them or the arguments do not describe such a segment. The rates are those
    /// of every variable (`x`, `z`, then `p`; zero where non-basic, one for `entering`), with
    /// the decreases that are round-off of the data set to zero ([`verdict`]).
    pub(crate) fn direction(
        &self,
        basic: &[bool],
        entering: usize,
    ) -> Option<(Vec<f64>, DirectionVerdict)> {
        let lcp = &self.lcp;
        let n = lcp.order();
        let big_n = lcp.a.nrows();
        // The driver enters from a complementary basis (a load history's stage at its start):
        // the direction per unit load, whose rate is the load's own.
        let driver_enters = entering == 2 * n;
        if basic.len() != 2 * n + 1
            || entering > 2 * n
            || basic[entering]
            || !(driver_enters || basic[2 * n])
            || basic.iter().filter(|&&b| b).count() != n
        {
            return None;
        }
        let nonbasic: Vec<bool> = basic.iter().map(|b| !b).collect();
        let mut guard = self.factorised(&nonbasic)?;
        let bordered = guard.as_mut()?;
        // Every non-basic variable held at zero but the entering one, held at one.
        let (row, scale) = bordered.fix_row(entering)?;
        let mut rhs = vec![0.0; big_n + 2 * n + 1];
        rhs[row] = scale;
        let mut v = bordered.refined_base_solve(&rhs);
        let terms = Terms::of(bordered.base_matrix(), &v, &self.weights, big_n + 2 * n);
        // How far the stored data's own round-off moves the direction: each equation's terms
        // perturbed by one rounding, with signs that do not cancel by design (two sign
        // patterns), carried through the basis (first-order perturbation, `δv = −𝒜⁻¹ δ𝒜 v`).
        let mut spread = vec![0.0f64; v.len()];
        for pattern in [0x9e37_79b9_u64, 0x85eb_ca6b_u64] {
            let mut probe = vec![0.0f64; v.len()];
            for (i, (p, t)) in probe.iter_mut().zip(&terms.rows).enumerate() {
                let bit = (i as u64).wrapping_mul(pattern).rotate_left(17) & 1;
                *p = if bit == 0 { 1.0 } else { -1.0 } * f64::EPSILON * t;
            }
            bordered.base_solve(&mut probe);
            for (s, w) in spread.iter_mut().zip(&probe) {
                *s += w.abs();
            }
        }
        let judged = verdict(&mut v, &terms, &spread, basic, big_n, n, driver_enters);
        v.drain(..big_n);
        Some((v, judged))
    }

    /// The point of the complementary basis `basic` (`2n` flags, `n` set, one of each pair)
    /// at load `p`, solved from the structure's equations with residuals refined in
    /// double-double arithmetic: `(x, z)`, the non-basic variables zero. `None` where the
    /// basis is singular on them or the flags do not describe such a basis. For a segment
    /// whose direction came from these equations ([`crate::PathSolver::judged_on`]): the
    /// condensed `M` forms its points with the condensation's round-off times the basis's
    /// conditioning (a block sliding metres on a spring 10⁻⁹ of its stiffness: out of balance
    /// by 9.1e-7 of its forces, 7.6e-7 from these equations).
    pub(crate) fn point(&self, basic: &[bool], p: f64) -> Option<(Vec<f64>, Vec<f64>)> {
        let lcp = &self.lcp;
        let n = lcp.order();
        let big_n = lcp.a.nrows();
        if basic.len() != 2 * n || (0..n).any(|i| basic[i] == basic[n + i]) || !p.is_finite() {
            return None;
        }
        let mut nonbasic: Vec<bool> = basic.iter().map(|b| !b).collect();
        nonbasic.push(true);
        let mut guard = self.factorised(&nonbasic)?;
        let bordered = guard.as_mut()?;
        let (row, scale) = bordered.fix_row(2 * n)?;
        let mut rhs = vec![0.0; big_n + 2 * n + 1];
        rhs[..big_n].copy_from_slice(&lcp.qa);
        rhs[big_n..big_n + n].copy_from_slice(&lcp.q0);
        rhs[row] = p * scale;
        let v = bordered.refined_base_solve(&rhs);
        let x = v[big_n..big_n + n].to_vec();
        let z = v[big_n + n..big_n + 2 * n].to_vec();
        (x.iter().chain(&z).all(|v| v.is_finite())).then_some((x, z))
    }
}

impl StructureJudge {
    /// The structure's basis system with the non-basic variables `nonbasic` (`2n + 1` flags)
    /// held, factorised afresh (the column order made on the first call and kept).
    fn factorised(&self, nonbasic: &[bool]) -> Option<std::sync::MutexGuard<'_, Option<Bordered>>> {
        let mut guard = self.basis.lock().ok()?;
        if guard.is_none() {
            *guard = Some(Bordered::slack(&self.lcp).ok()?);
        }
        guard.as_mut()?.refactor(nonbasic).ok()?;
        Some(guard)
    }
}

/// The weights of the equations `A y − B z − da·p` (the structure's DOFs) and
/// `x − D z + C y − d0·p` (the links' forces) that make their terms comparable whatever the
/// units: `1/√A_ii` for a DOF's row, `1/√max_j |D_kj|` for a link's. A row's terms are a force
/// (a DOF's that translates, a link's) or a moment (a DOF's that rotates); weighted so, both are
/// of the units `√(force·length)`, and a change of units scales every weighted term alike.
/// Compared unweighted, the moments' rows of a frame in kN·mm outweighed its forces' a thousand
/// times more than in N·m, and a T-footing's genuine 1 N/m spring read as a mechanism in kN·mm
/// only (a reviewer's sweep).
fn row_weights(lcp: &SchurLcp) -> Vec<f64> {
    let (big_n, n) = (lcp.a.nrows(), lcp.order());
    let mut w = vec![0.0f64; big_n + n];
    for j in 0..lcp.a.ncols().min(big_n) {
        for (&i, &aij) in lcp.a.row_idx_of_col_raw(j).iter().zip(lcp.a.val_of_col(j)) {
            if i == j && aij != 0.0 {
                w[i] = 1.0 / aij.abs().sqrt();
            }
        }
    }
    let mut dmax = vec![0.0f64; n];
    for j in 0..lcp.d.ncols() {
        for (&k, &dkj) in lcp.d.row_idx_of_col_raw(j).iter().zip(lcp.d.val_of_col(j)) {
            if k < n {
                dmax[k] = dmax[k].max(dkj.abs());
            }
        }
    }
    // A link's row without a stiffness of its own takes the largest of the links' (the same
    // units).
    let dall = dmax.iter().fold(0.0f64, |m, &d| m.max(d));
    for (k, d) in dmax.iter().enumerate() {
        let d = if *d > 0.0 { *d } else { dall };
        w[big_n + k] = if d > 0.0 { 1.0 / d.sqrt() } else { 1.0 };
    }
    // A DOF's row without a diagonal (none in a stiffness) keeps its terms as they are.
    for x in w.iter_mut().take(big_n) {
        if *x == 0.0 {
            *x = 1.0;
        }
    }
    w
}

/// The terms of a direction `v` in the equations (the first `weights.len()` rows of the base
/// system): `Σ_j |a_ij v_j|` by row, the largest of them weighted ([`row_weights`]), and the
/// largest weighted term of the load's column `pcol`.
struct Terms<'w> {
    rows: Vec<f64>,
    /// The rows' weights.
    weights: &'w [f64],
    /// The largest `w_i·Σ_j |a_ij v_j|`.
    largest: f64,
    /// The largest `w_i·|a_i,pcol v_pcol|`.
    load: f64,
}

impl<'w> Terms<'w> {
    fn of(a: &SparseColMat<usize, f64>, v: &[f64], weights: &'w [f64], pcol: usize) -> Self {
        let rows = weights.len();
        let (mut terms, mut load) = (vec![0.0f64; rows], 0.0f64);
        for (j, &vj) in v.iter().enumerate() {
            if vj == 0.0 {
                continue;
            }
            for (&i, &aij) in a.row_idx_of_col_raw(j).iter().zip(a.val_of_col(j)) {
                if i < rows {
                    terms[i] += (aij * vj).abs();
                    if j == pcol {
                        load = load.max(weights[i] * (aij * vj).abs());
                    }
                }
            }
        }
        let largest = terms
            .iter()
            .zip(weights)
            .fold(0.0f64, |m, (t, w)| m.max(w * t));
        Self {
            rows: terms,
            weights,
            largest,
            load,
        }
    }
}

/// The verdict on the direction `v` (the base's unknowns `y, x, z, p`; `N = big_n`) with its
/// `terms` in the `N + n` equations. A basic variable's decrease within
/// [`crate::ACCEPT_RESIDUAL`] of the terms that formed it (an `x` its row's, but not below 8
/// round-offs of the direction's largest terms; a `z` the largest rate of a `z`), or within
/// eight times `spread` (what one rounding of each equation's terms moves it by), is set to
/// zero in `v`: on a mechanism of the structure the exact direction's rates are round-off of
/// its data — a sliding beam's normal forces decreasing at 1e-17 of the direction's largest
/// terms, a 700-bearing beam's gaps closing at 1e-9 of its slips — and taken as rates they
/// blocked the slide after slips of 1e13 to 1e14, from where the path wandered to a false
/// mechanism at a lower load.
fn verdict(
    v: &mut [f64],
    terms: &Terms,
    spread: &[f64],
    basic: &[bool],
    big_n: usize,
    n: usize,
    driver_enters: bool,
) -> DirectionVerdict {
    // The load's rate against the largest terms of the direction, every row weighted to the
    // same units ([`row_weights`]) — a row the direction hardly moves (a beam's vertical DOF
    // while it slides) has the load's share as its only term.
    let largest = terms.largest;
    // With the driver entering, the load moves by definition. A load rate within what the
    // data's round-off makes of it (`spread`, eight times over, as for the decreases below) is
    // none, however large its weighted share: a row of a node on a soft spring weighs its
    // terms by `1/√A_ii`, so a beam sliding on its bearings beside a bar held up by a 1e-4 N/m
    // spring gave the load's round-off (1.4e-15 against a spread of 8.8e-14) a share of 5e-13
    // of the direction's terms, read as genuine: the path turned back to zero from the beam's
    // limit (N·m) or ran on as a ray that no point verified (kN·mm).
    let dp = v[big_n + 2 * n];
    let verdict = DirectionVerdict {
        load: if driver_enters {
            f64::INFINITY
        } else if terms.load == 0.0 || dp.abs() <= 8.0 * spread[big_n + 2 * n] {
            0.0
        } else {
            terms.load / largest
        },
    };
    let z_scale = v[big_n + n..big_n + 2 * n]
        .iter()
        .fold(0.0f64, |m, r| m.max(r.abs()));
    for (i, _) in basic.iter().enumerate().take(2 * n).filter(|(_, &b)| b) {
        let at = big_n + i;
        if v[at] >= 0.0 {
            continue;
        }
        // An `x` against its row's terms, and never below 8 round-offs of the direction's
        // largest terms: the data hold those to their last bit, and a row the direction hardly
        // touches (a pair's normal force while the beam slides) carries that much of them.
        let roundoff = if i < n {
            (crate::ACCEPT_RESIDUAL * terms.rows[at])
                .max(8.0 * f64::EPSILON * largest / terms.weights[at])
        } else {
            crate::ACCEPT_RESIDUAL * z_scale
        };
        // Nor below what the data's round-off makes of it (`spread`), eight times over.
        // Where the load has a genuine rate (a soft spring's), the segment is no mechanism:
        // every rate is the structure's own, the heel of a block unloading as the push grows
        // among them (at 1e-10 of the direction's terms, dominated by metres of slip), and
        // only what the data's round-off makes of a rate is zero.
        let roundoff = if verdict.load_holds() { roundoff } else { 0.0 };
        let roundoff = roundoff.max(8.0 * spread[at]);
        if -v[at] <= roundoff {
            v[at] = 0.0;
        }
    }
    verdict
}

#[cfg(test)]
mod tests {
    use super::StructureJudge;
    use crate::schur::test_data::{small_lcp, sparse};
    use crate::SchurLcp;
    use faer::Mat;

    /// `got` against the dense LU solution of `sys · v = rhs`, entry by entry to 1e-12.
    fn agrees_with_dense_solve(sys: &Mat<f64>, rhs: &Mat<f64>, got: &[f64], what: &str) {
        use faer::linalg::solvers::Solve;
        let sol = sys.partial_piv_lu().solve(rhs);
        for (k, g) in got.iter().enumerate() {
            assert!(
                (g - sol[(k, 0)]).abs() <= 1e-12 * sol[(k, 0)].abs().max(1.0),
                "{what} {k}: {g} against {}",
                sol[(k, 0)]
            );
        }
    }

    /// Reference: the direction solved from the formed `M` (`lcp.dense()`) by a dense LU of
    /// the basis's columns — the same rates as the judge's solve of the sparse equations.
    #[test]
    fn the_direction_is_that_of_the_formed_problem() {
        let n = 4;
        let lcp = small_lcp();
        let dense = lcp.dense();
        let judge = StructureJudge::new(lcp);
        // Basic: x0, z1, x2, z3 and p; entering z0 (its pair's x0 is basic? no: x0 left).
        // Pairs: 0 missing (x0, z0 both non-basic), entering z0.
        let mut basic = vec![false; 2 * n + 1];
        for v in [n + 1, 2, n + 3, 2 * n] {
            basic[v] = true;
        }
        // One more basic to make n: x1 is non-basic (z1 basic), so add nothing; n = 4 needs
        // four basic variables: z1, x2, z3, p.
        assert_eq!(basic.iter().filter(|&&b| b).count(), n);
        let entering = n; // z0
        let (v, _) = judge.direction(&basic, entering).unwrap();
        // Dense: x = q + p d + M z, rates with z0 = 1: unknowns dz1, dx2, dz3, dp.
        // Rows i: dx_i − M_i1 dz1 − M_i3 dz3 − d_i dp = M_i0 (x0, x1, x3 non-basic: 0; x2 free).
        let mut sys = Mat::<f64>::zeros(n, n);
        let mut rhs = Mat::<f64>::zeros(n, 1);
        for i in 0..n {
            sys[(i, 0)] = -dense.m[(i, 1)];
            sys[(i, 1)] = if i == 2 { 1.0 } else { 0.0 };
            sys[(i, 2)] = -dense.m[(i, 3)];
            sys[(i, 3)] = -dense.d[i];
            rhs[(i, 0)] = dense.m[(i, 0)];
        }
        agrees_with_dense_solve(&sys, &rhs, &[v[n + 1], v[2], v[n + 3], v[2 * n]], "rate");
        assert_eq!(v[n], 1.0);
    }

    /// Reference: the point of a complementary basis solved from the formed problem
    /// `x = q + p·d + M z` by a dense LU — the judge's point, solved from the sparse equations.
    #[test]
    fn the_point_is_that_of_the_formed_problem() {
        let (n, big_n) = (4, 5);
        let a = Mat::<f64>::from_fn(big_n, big_n, |i, j| {
            if i == j {
                5.0 + 2.0 * i as f64
            } else {
                1.0 / (2.0 + (2 * i + j) as f64)
            }
        });
        let b = Mat::<f64>::from_fn(big_n, n, |i, j| ((i * 2 + j * 3) % 5) as f64 - 2.0);
        let c = Mat::<f64>::from_fn(n, big_n, |i, j| ((i * 3 + j) % 4) as f64 - 1.5);
        let d = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 8.0 } else { -0.25 });
        let lcp = SchurLcp {
            a: sparse(&a),
            b: sparse(&b),
            c: sparse(&c),
            d: sparse(&d),
            q0: vec![1.0, -2.0, 0.5, 3.0],
            qa: vec![0.5, -1.0, 0.0, 2.0, 1.5],
            d0: vec![-1.0, 2.0, 0.5, 1.5],
            da: vec![0.3, -0.2, 0.1, 0.0, 0.7],
        };
        let dense = lcp.dense();
        let judge = StructureJudge::new(lcp);
        // Basic: x0, z1, x2, z3 (one of each pair); at p = 0.7.
        let p = 0.7;
        let mut basic = vec![false; 2 * n];
        for v in [0, n + 1, 2, n + 3] {
            basic[v] = true;
        }
        let (x, z) = judge.point(&basic, p).unwrap();
        // Dense: rows i: x_i − M_i1 z1 − M_i3 z3 = q_i + p d_i, x1 = x3 = 0, z0 = z2 = 0;
        // unknowns x0, z1, x2, z3.
        let mut sys = Mat::<f64>::zeros(n, n);
        let mut rhs = Mat::<f64>::zeros(n, 1);
        for i in 0..n {
            sys[(i, 0)] = if i == 0 { 1.0 } else { 0.0 };
            sys[(i, 1)] = -dense.m[(i, 1)];
            sys[(i, 2)] = if i == 2 { 1.0 } else { 0.0 };
            sys[(i, 3)] = -dense.m[(i, 3)];
            rhs[(i, 0)] = dense.q0[i] + p * dense.d[i];
        }
        agrees_with_dense_solve(&sys, &rhs, &[x[0], z[1], x[2], z[3]], "value");
        assert_eq!([x[1], x[3], z[0], z[2]], [0.0; 4]);
        // Not a complementary basis (x0 and z0 both basic): refused.
        let mut both = basic.clone();
        both[n] = true;
        both[n + 1] = false;
        assert!(judge.point(&both, p).is_none());
    }
}
