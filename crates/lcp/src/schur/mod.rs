//! The parametric LCP whose matrix is a Schur complement of sparse data, and the engine that
//! traces its path without forming the matrix (issue 11). A path to the target can be handed
//! to the dense solver ([`crate::PathSolver::adopt`], [`crate::PathSolver::follow_sparse`]),
//! which verifies what is reported on the condensed data (a ray's end on the structure's own
//! equations, where the solver has them); `unilateral solve` traces with it from 1000 contact
//! pairs on (`docs/engine.md`, "Which engine traces a structural model").
//!
//! ```text
//! x = q0 + p·d0 + D z − C y,   A y = qa + p·da + B z,   x ≥ 0, z ≥ 0, xᵀz = 0
//! ```
//!
//! with sparse `A` (`N × N`, nonsingular), `B` (`N × n`), `C` (`n × N`), `D` (`n × n`): the
//! parametric LCP `x = q + p·d + M z` with `M = D − C A⁻¹ B`, `q = q0 − C A⁻¹ qa`,
//! `d = d0 − C A⁻¹ da`, never formed. A structure condensed to its contact zone is of this
//! kind (`A` the stiffness of the DOFs off the links): the dense engine pays `O(n·k + k²)` a
//! pivot on the formed `M` (`k` the kernel), this one a few sparse solves with one
//! factorisation of the whole system (see `bordered`).
//!
//! What it does so far: the path from the slack basis (`q(0) ≥ 0`) with `p` as the driver, to
//! the target or to the end; lexicographic ties in a given order of the rows, computed a
//! priority column at a time for the candidates still tied; the rows of a relation decided
//! by it (a row alone among its relation's basic rows never leaves; two basic rows fall
//! together and the relation says which leaves); each direction refined once against the
//! data; the values formed afresh at each refactorisation and at near ties; with a dense
//! solver at hand ([`crate::PathSolver::trace_sparse`]), the rates of `x` that the sparse
//! data cannot tell from round-off judged on the dense `M`. What it does not do (the dense
//! engine does, and the callers fall back to it): a start by Lemke's method or a
//! tightening, equilibration, the verification of its breakpoints on the structure's
//! equations (its reported point is verified on the dense data, its ray's end on the
//! structure's equations: [`crate::PathSolver::follow_sparse`]), the sweep and the tableaux.
//! Measurements: `docs/performance.md`, rounds 27, 28 and 38.

mod bordered;
mod judge;

use faer::sparse::SparseColMat;
use faer::Mat;

use crate::{Breakpoint, Follow, ParametricLcp, PathStatus, Step, Var};
use bordered::Bordered;
pub use judge::StructureJudge;

/// A parametric LCP with `M = D − C A⁻¹ B` (see the module's documentation).
#[derive(Debug, Clone)]
pub struct SchurLcp {
    /// `A` (`N × N`), nonsingular.
    pub a: SparseColMat<usize, f64>,
    /// `B` (`N × n`).
    pub b: SparseColMat<usize, f64>,
    /// `C` (`n × N`).
    pub c: SparseColMat<usize, f64>,
    /// `D` (`n × n`).
    pub d: SparseColMat<usize, f64>,
    /// `q0` (`n`).
    pub q0: Vec<f64>,
    /// `qa` (`N`).
    pub qa: Vec<f64>,
    /// `d0` (`n`).
    pub d0: Vec<f64>,
    /// `da` (`N`).
    pub da: Vec<f64>,
}

impl SchurLcp {
    /// The order `n` of the LCP.
    pub fn order(&self) -> usize {
        self.q0.len()
    }

    /// The shapes agree, else a message saying which does not.
    pub fn check(&self) -> Result<(), String> {
        let (n, big_n) = (self.order(), self.a.nrows());
        let shapes = [
            ("A", self.a.nrows(), self.a.ncols(), big_n, big_n),
            ("B", self.b.nrows(), self.b.ncols(), big_n, n),
            ("C", self.c.nrows(), self.c.ncols(), n, big_n),
            ("D", self.d.nrows(), self.d.ncols(), n, n),
        ];
        for (name, r, c, er, ec) in shapes {
            if (r, c) != (er, ec) {
                return Err(format!("{name} is {r} × {c}, expected {er} × {ec}"));
            }
        }
        if self.qa.len() != big_n || self.da.len() != big_n || self.d0.len() != n {
            return Err("the vectors' lengths do not match the matrices".into());
        }
        Ok(())
    }

    /// The same structure at a fixed load `p`: `q0 + p·d0` and `qa + p·da` as its constant
    /// loads (for [`SchurLcp::basis_solution`] at `p`).
    pub fn at_load(&self, p: f64) -> SchurLcp {
        let mut at = self.clone();
        for (q, d) in at.q0.iter_mut().zip(&self.d0) {
            *q += p * d;
        }
        for (q, d) in at.qa.iter_mut().zip(&self.da) {
            *q += p * d;
        }
        at
    }

    /// The same problem with `M`, `q` and `d` formed densely (for tests and small problems).
    pub fn dense(&self) -> ParametricLcp {
        let n = self.order();
        let a = self.a.to_dense();
        let lu = a.partial_piv_lu();
        let b = self.b.to_dense();
        let c = self.c.to_dense();
        let mut rhs = Mat::<f64>::zeros(self.a.nrows(), n + 2);
        for j in 0..n {
            for i in 0..self.a.nrows() {
                rhs[(i, j)] = b[(i, j)];
            }
        }
        for i in 0..self.a.nrows() {
            rhs[(i, n)] = self.qa[i];
            rhs[(i, n + 1)] = self.da[i];
        }
        use faer::linalg::solvers::Solve;
        let sol = lu.solve(&rhs);
        let csol = &c * &sol;
        let dd = self.d.to_dense();
        let m = Mat::from_fn(n, n, |i, j| dd[(i, j)] - csol[(i, j)]);
        let q0 = (0..n).map(|i| self.q0[i] - csol[(i, n)]).collect();
        let d = (0..n).map(|i| self.d0[i] - csol[(i, n + 1)]).collect();
        ParametricLcp { m, q0, d }
    }
}

impl SchurLcp {
    /// The equations of [`SchurLcp::basis_solution`] formed densely: the matrix, the right-hand
    /// side, and each variable's column among the unknowns (`None` where non-basic; the first
    /// `N` unknowns are `y`).
    #[allow(clippy::type_complexity)]
    pub fn basis_system(&self, basic: &[bool]) -> Option<(Mat<f64>, Mat<f64>, Vec<Option<usize>>)> {
        let n = self.order();
        let big_n = self.a.nrows();
        let vars: Vec<usize> = (0..=2 * n).filter(|&v| basic[v]).collect();
        if vars.len() != n || basic.len() != 2 * n + 1 {
            return None;
        }
        let mut pos = vec![None; 2 * n + 1];
        for (c, &v) in vars.iter().enumerate() {
            pos[v] = Some(big_n + c);
        }
        let size = big_n + n;
        let mut a = Mat::<f64>::zeros(size, size);
        let mut put = |m: &SparseColMat<usize, f64>,
                       r0: usize,
                       cmap: &dyn Fn(usize) -> Option<usize>,
                       sign: f64| {
            for j in 0..m.ncols() {
                if let Some(c) = cmap(j) {
                    for (&i, &v) in m.row_idx_of_col_raw(j).iter().zip(m.val_of_col(j)) {
                        a[(r0 + i, c)] += sign * v;
                    }
                }
            }
        };
        put(&self.a, 0, &|j| Some(j), 1.0);
        put(&self.b, 0, &|j| pos[n + j], -1.0);
        put(&self.c, big_n, &|j| Some(j), 1.0);
        put(&self.d, big_n, &|j| pos[n + j], -1.0);
        for (i, p) in pos.iter().enumerate().take(n) {
            if let Some(c) = *p {
                a[(big_n + i, c)] += 1.0;
            }
        }
        if let Some(c) = pos[2 * n] {
            for (i, v) in self.da.iter().enumerate() {
                a[(i, c)] -= v;
            }
            for (i, v) in self.d0.iter().enumerate() {
                a[(big_n + i, c)] -= v;
            }
        }
        let rhs = Mat::<f64>::from_fn(size, 1, |i, _| {
            if i < big_n {
                self.qa[i]
            } else {
                self.q0[i - big_n]
            }
        });
        Some((a, rhs, pos))
    }

    /// The values of every variable (`x`, then `z`, then `p`; zero where non-basic) on the
    /// basis marked in `basic` (length `2n + 1`, `n` basic), from a dense LU of its equations
    /// on the sparse data — `A y − B z_B − da·p = qa`, `x_B − D z_B + C y − d0·p = q0` — with
    /// no `M` formed, refined with residuals in double-double arithmetic: an independent check
    /// of a breakpoint (`O((N + n)³)`) to far below the round-off of a working-precision
    /// solve, which late on a long path (a basis's condition number of 1e10 and more) is what
    /// tells the two engines' data apart (`docs/engine.md`). `None` when `basic` does not
    /// mark `n` variables.
    pub fn basis_solution(&self, basic: &[bool]) -> Option<Vec<f64>> {
        let (a, rhs, pos) = self.basis_system(basic)?;
        let sol = refined_dense_solution(&a, &rhs);
        let mut out = vec![0.0; pos.len()];
        for (v, p) in pos.iter().enumerate() {
            if let Some(c) = *p {
                out[v] = sol[c];
            }
        }
        Some(out)
    }
}

/// The solution of the dense system `a x = b` refined with residuals in double-double
/// arithmetic ([`refined_in_double_double`]) on its partial-pivoting LU.
fn refined_dense_solution(a: &Mat<f64>, b: &Mat<f64>) -> Vec<f64> {
    use faer::linalg::solvers::SolveCore;
    let size = a.nrows();
    let lu = a.partial_piv_lu();
    let rhs: Vec<f64> = (0..size).map(|i| b[(i, 0)]).collect();
    refined_in_double_double(
        &rhs,
        |visit| {
            for j in 0..size {
                for i in 0..size {
                    visit(i, j, a[(i, j)]);
                }
            }
        },
        |r| {
            lu.solve_in_place_with_conj(
                faer::Conj::No,
                faer::MatMut::from_column_major_slice_mut(r, size, 1),
            )
        },
    )
}

/// The solution of `A x = b` refined with residuals in double-double arithmetic: each product
/// split exactly by a fused multiply-add, the sums by Knuth's two-sum, the unknowns kept as
/// unevaluated sums of two doubles through four rounds and rounded at the end. `entries`
/// visits the entries `(i, j, a_ij)` of `A` (a row's in increasing `j`), `solve` overwrites a
/// right-hand side with an approximate solution (a factorisation of `A`).
pub(crate) fn refined_in_double_double(
    b: &[f64],
    entries: impl Fn(&mut dyn FnMut(usize, usize, f64)),
    solve: impl Fn(&mut [f64]),
) -> Vec<f64> {
    let size = b.len();
    let mut hi = b.to_vec();
    solve(&mut hi);
    let mut lo = vec![0.0; size];
    let two_sum = |x: f64, y: f64| {
        let s = x + y;
        let v = s - x;
        (s, (x - (s - v)) + (y - v))
    };
    for _ in 0..4 {
        // b − A (hi + lo), row by row in double-double.
        let (mut s, mut e) = (b.to_vec(), vec![0.0; size]);
        entries(&mut |i, j, aij| {
            if aij == 0.0 {
                return;
            }
            let p = -aij * hi[j];
            let pe = (-aij).mul_add(hi[j], -p);
            let (t, te) = two_sum(s[i], p);
            s[i] = t;
            e[i] += te + pe - aij * lo[j];
        });
        let mut dx: Vec<f64> = s.iter().zip(&e).map(|(s, e)| s + e).collect();
        solve(&mut dx);
        for i in 0..size {
            let (t, te) = two_sum(hi[i], dx[i]);
            let (h, l) = two_sum(t, te + lo[i]);
            hi[i] = h;
            lo[i] = l;
        }
    }
    hi.iter().zip(&lo).map(|(h, l)| h + l).collect()
}

/// How a Schur path ended and what it found.
#[derive(Debug, Clone)]
pub struct SchurPath {
    /// How the path ended (`NoSolutionAtStart` when `q(0)` is not `≥ 0`: this engine does not
    /// yet find a start by Lemke's method).
    pub status: PathStatus,
    /// Every pivot.
    pub steps: Vec<Step>,
    /// The start and the point after every step.
    pub breakpoints: Vec<Breakpoint>,
    /// `(x, z)` at the target when the path reached it.
    pub at_target: Option<(Vec<f64>, Vec<f64>)>,
    /// The number of steps before the load first reached the target (the target lies on the
    /// segment after that many pivots), if it did.
    pub target_segment: Option<usize>,
    /// The variable entering on the last segment (for a ray or a mechanism: the one that
    /// grows without bound), as a column (`x_i` is `i`, `z_i` is `n + i`, the driver `2n`).
    pub last_entering: Option<usize>,
    /// On a mechanism, the rates of `x` and of `z` along it (per unit of the entering
    /// variable).
    pub mechanism_rates: Option<(Vec<f64>, Vec<f64>)>,
    /// Fresh factorisations of the base.
    pub refactorizations: usize,
    /// Of those, the ones forced by a singular border.
    pub singular_updates: usize,
}

/// Options of [`follow_schur_path`].
#[derive(Debug, Clone)]
pub struct SchurOptions {
    /// The target load.
    pub target: f64,
    /// How far the path is followed.
    pub follow: Follow,
    /// The pivot cap.
    pub max_pivots: usize,
    /// The border's size that triggers a refactorisation of the base.
    pub max_border: usize,
    /// The rows' lexicographic priority (as [`crate::Settings::lexicographic_order`]);
    /// `None` for `0, 1, …, n − 1`.
    pub order: Option<Vec<usize>>,
    /// Rows the formulation ties exactly (as [`crate::Settings::row_relations`]): a row alone
    /// among its relation's basic rows is fixed by the others and never leaves.
    pub relations: Vec<crate::RowRelation>,
    /// Where the path reports its steps (as [`crate::Settings::progress`]).
    pub progress: crate::Progress,
}

/// The current basis: basic variables and their values.
struct State {
    n: usize,
    basic: Vec<bool>,
    /// Values of all variables (zero for non-basic), `x` then `z` then `p`.
    val: Vec<f64>,
}

impl State {
    fn x(&self) -> &[f64] {
        &self.val[..self.n]
    }
    fn z(&self) -> &[f64] {
        &self.val[self.n..2 * self.n]
    }
    fn p(&self) -> f64 {
        self.val[2 * self.n]
    }
}

/// The rates of rows of `x` formed from a dense copy of the same problem (`x = q + p·d + M z`
/// with `M` formed): `rate = M_i·dz + d_i·dp` and the size of its terms
/// `Σ_j |M_ij dz_j| + |d_i dp|`. The sparse engine forms a rate of `x` as
/// `d0·dp + D dz − C dy`, whose terms are the structure's displacements (a beam's, under the
/// whole load) and can exceed the rate by 10¹⁵: a real start of slip then looks like
/// round-off. The condensed `M` carries that cancellation once, in its data, and a rate read
/// from it is judged as the dense engine judges it ([`crate::PathSolver::follow_sparse`]).
pub(crate) trait DenseRates {
    /// Row `i`'s rate and the size of its terms.
    fn row(&self, i: usize, dz: &[f64], dp: f64) -> (f64, f64);
    /// Every row's rate and terms.
    fn rows(&self, dz: &[f64], dp: f64) -> (Vec<f64>, Vec<f64>);
}

/// Follows the path of `lcp` from `p = 0`.
pub fn follow_schur_path(lcp: &SchurLcp, opts: &SchurOptions) -> SchurPath {
    follow(lcp, opts, None)
}

/// [`follow_schur_path`], the rates of `x` that the sparse data cannot tell from round-off
/// judged on `dense` where it is given (a row that decreases at a rate below the column's
/// tolerance; every row where the path would end in a ray).
pub(crate) fn follow(
    lcp: &SchurLcp,
    opts: &SchurOptions,
    dense: Option<&dyn DenseRates>,
) -> SchurPath {
    let n = lcp.order();
    let big_n = lcp.a.nrows();
    let mut out = SchurPath {
        status: PathStatus::NumericalFailure,
        steps: Vec::new(),
        breakpoints: Vec::new(),
        at_target: None,
        refactorizations: 0,
        singular_updates: 0,
        target_segment: None,
        last_entering: None,
        mechanism_rates: None,
    };
    let mut singular_updates = 0;
    let Ok(mut basis) = Bordered::slack(lcp) else {
        return out;
    };
    // Every direction and every set of values is refined once against the data.
    basis.refine_checks();
    let mut st = State {
        n,
        basic: (0..=2 * n).map(|v| v < n).collect(),
        val: vec![0.0; 2 * n + 1],
    };
    values(lcp, &basis, &mut st);
    let mut fresh = true;
    let xscale = st.x().iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if st.x().iter().any(|&v| v < -1e-12 * xscale) {
        out.status = PathStatus::NoSolutionAtStart;
        return out;
    }
    out.breakpoints.push(Breakpoint {
        p: 0.0,
        z: Vec::new(),
    });
    opts.progress.phase(crate::Phase::Path);
    // Rows of C and D, for the round-off of a row's rate.
    let ct = lcp
        .c
        .as_ref()
        .transpose()
        .to_col_major()
        .expect("memory for Cᵀ");
    let dt = lcp
        .d
        .as_ref()
        .transpose()
        .to_col_major()
        .expect("memory for Dᵀ");
    // Degenerate steps in a row (the load unchanged): a cycle the lexicographic rule did not
    // prevent in floating point ends the path (the caller falls back to the dense engine).
    let mut degenerate = 0usize;
    let mut entering = 2 * n;
    let order: Vec<usize> = opts.order.clone().unwrap_or_else(|| (0..n).collect());
    let mut position = vec![0; n];
    for (k, &i) in order.iter().enumerate() {
        position[i] = k;
    }
    let mut relation_of = vec![usize::MAX; n];
    for (r, rel) in opts.relations.iter().enumerate() {
        for &(i, _) in &rel.terms {
            relation_of[i] = r;
        }
    }
    // The other basic row of `v`'s relation when it has exactly two.
    let partner = |st: &State, v: usize| -> Option<usize> {
        if v >= n || relation_of[v] == usize::MAX {
            return None;
        }
        let rel = &opts.relations[relation_of[v]];
        let basic: Vec<usize> = rel
            .terms
            .iter()
            .map(|t| t.0)
            .filter(|&i| st.basic[i])
            .collect();
        (basic.len() == 2)
            .then(|| basic.into_iter().find(|&i| i != v))
            .flatten()
    };
    let alone = |st: &State, v: usize| -> bool {
        v < n
            && relation_of[v] != usize::MAX
            && opts.relations[relation_of[v]]
                .terms
                .iter()
                .filter(|&&(i, _)| st.basic[i])
                .count()
                == 1
    };
    let weight: Vec<f64> = (0..=2 * n)
        .map(|v| {
            if v < n {
                1.0
            } else if v < 2 * n {
                basis.fix_scale(v) / 4.0
            } else {
                lcp.d0
                    .iter()
                    .chain(&lcp.da)
                    .fold(0.0f64, |a, x| a.max(x.abs()))
            }
        })
        .collect();
    let mut rhs = vec![0.0; big_n + 2 * n + 1];
    // The direction and the refinement's vectors, reused from step to step.
    let (mut dv, mut work) = (Vec::new(), (Vec::new(), Vec::new()));
    // The base's own solution of the direction's right-hand side: the border column of the
    // pivot that frees the entering variable's fix row.
    let mut base_dir = Vec::new();
    loop {
        if out.steps.len() >= opts.max_pivots {
            out.status = PathStatus::IterationLimit;
            break;
        }
        // The direction: the entering variable at 1, every other non-basic at 0.
        rhs.fill(0.0);
        let entering_row = basis.fix_row(entering);
        if let Some((at, entry)) = entering_row {
            rhs[at] = entry;
        }
        basis.solve_into(
            &rhs,
            |v| f64::from(v == entering),
            &mut dv,
            Some(&mut base_dir),
            0,
        );
        // The structure's part `y` of the direction is left unrefined: besides the residual
        // it is read only for the sizes of the terms that form a row's rate (`sparse_terms`,
        // whose thresholds are 1e-9 of them), which the refinement moved by 1e-4 of their
        // size at most on the 2000-bearing beam (a reviewer's measurement; no decision of
        // that path or the 1000-bearing one changed).
        refine_in_place(
            lcp,
            &basis,
            &st.basic,
            None,
            Some(entering),
            &mut dv,
            (&mut work.0, &mut work.1),
        );
        let mut dir = dv[big_n..].to_vec();
        let dp = dir[2 * n];
        dir[entering] = 1.0;
        // Round-off of each kind (`x`, `z`) against the largest rate of that kind, the
        // entering variable's own among them; the driver's rate against the `x` rates it makes.
        let kind = |v: usize| usize::from(v >= n) + usize::from(v >= 2 * n);
        let mut big = [0.0f64; 3];
        for v in (0..=2 * n).filter(|&v| st.basic[v] || v == entering) {
            big[kind(v)] = big[kind(v)].max(dir[v].abs());
        }
        big[2] *= weight[2 * n];
        let scale = |v: usize| dir[v].abs() * if v == 2 * n { weight[v] } else { 1.0 };
        // The driver's rate, in the units of `x`, against the `x` rates and the entering
        // column's own scale (a mechanism moves no force: its `x` rates are round-off).
        // An `x` rate is round-off below 1e-13 of the entering column's largest entry too:
        // in a mechanism every `x` rate is round-off, and 1e-9 of the largest would take one.
        let x_scale = big[0].max(weight[entering]);
        let tol_of = |v: usize| match kind(v) {
            0 => (1e-9 * big[0]).max(1e-13 * weight[entering]),
            1 => 1e-9 * big[1],
            _ => 1e-9 * x_scale,
        };
        let tol = tol_of(2 * n);
        // Rows of `x` whose rates were judged apart from the column's tolerance (below).
        let mut judged: Vec<(usize, f64)> = Vec::new();
        // Rows of `x` above the column's tolerance whose rates the dense data call round-off.
        let mut rejected: Vec<usize> = Vec::new();
        let ratios =
            |st: &State, judged: &[(usize, f64)], rejected: &[usize]| -> (f64, Vec<(usize, f64)>) {
                let mut best = f64::INFINITY;
                let mut cands: Vec<(usize, f64)> = Vec::new();
                for (v, &rate) in dir.iter().enumerate() {
                    if !st.basic[v]
                        || v == entering
                        || rate >= 0.0
                        || scale(v) <= tol_of(v)
                        || alone(st, v)
                        || rejected.contains(&v)
                        || judged.iter().any(|j| j.0 == v)
                    {
                        continue;
                    }
                    let ratio = st.val[v].max(0.0) / -rate;
                    cands.push((v, ratio));
                    best = best.min(ratio);
                }
                for &(v, rate) in judged {
                    let ratio = st.val[v].max(0.0) / -rate;
                    cands.push((v, ratio));
                    best = best.min(ratio);
                }
                (best, cands)
            };
        let (mut best, mut cands) = ratios(&st, &judged, &rejected);
        // Rows of `x` decreasing at a rate below the tolerance that would block first (or at
        // all, on a ray): taken where the rate exceeds round-off of the terms that formed it
        // (`x_i = q0 + p·d0 + D z − C y`, row by row; or on the dense data where it is given).
        // A tolerance against the largest rates alone passed a start of slip and called the
        // path a ray (a 500-bearing beam).
        // The size of the terms that form row `v`'s rate on the sparse data.
        let sparse_terms = |v: usize| {
            row_terms(&dt, &ct, v, &dv[..big_n], &dir[n..2 * n]) + (lcp.d0[v] * dp).abs()
        };
        let doubtful: Vec<usize> = (0..n)
            .filter(|&v| {
                st.basic[v]
                    && v != entering
                    && dir[v] < 0.0
                    && scale(v) <= tol_of(v)
                    && !alone(&st, v)
                    && st.val[v] > 0.0
                    && st.val[v] / -dir[v] < best
            })
            .collect();
        for v in doubtful {
            let (rate, terms) = match dense {
                Some(dense) => dense.row(v, &dir[n..2 * n], dp),
                None => (dir[v], sparse_terms(v)),
            };
            if rate < 0.0 && -rate > crate::ACCEPT_RESIDUAL * terms {
                judged.push((v, rate));
            }
        }
        if !judged.is_empty() {
            (best, cands) = ratios(&st, &judged, &rejected);
        }
        // Candidates within 1e-7 of the smallest ratio are judged on values formed afresh from
        // the data (as the dense engine's near ties): the values moved along the segments
        // since the last refactorisation drift.
        if !fresh && cands.iter().filter(|c| c.1 <= best * (1.0 + 1e-7)).count() > 1 {
            values(lcp, &basis, &mut st);
            (best, cands) = ratios(&st, &judged, &rejected);
        }
        // The rows of `x` that would block first, at a rate within 1e-9 of the terms that
        // formed it on the sparse data, are judged on the dense data where it is given: a
        // friction row of a pair whose rows are all at round-off (an open pair's, 1e-3 against
        // terms of 1e11) "decreasing" at 1e-4 is no event (the dense engine does not take it).
        if let Some(dense) = dense {
            loop {
                let mut changed = false;
                let first: Vec<usize> = cands
                    .iter()
                    .filter(|c| c.0 < n && c.1 <= best * (1.0 + 1e-7))
                    .map(|c| c.0)
                    .filter(|v| !judged.iter().any(|j| j.0 == *v))
                    .collect();
                for v in first {
                    if -dir[v] <= crate::ACCEPT_RESIDUAL * sparse_terms(v) {
                        let (rate, terms) = dense.row(v, &dir[n..2 * n], dp);
                        if rate < 0.0 && -rate > crate::ACCEPT_RESIDUAL * terms {
                            judged.push((v, rate));
                        } else {
                            rejected.push(v);
                        }
                        changed = true;
                    }
                }
                if !changed {
                    break;
                }
                (best, cands) = ratios(&st, &judged, &rejected);
            }
        }
        // Where nothing blocks (a ray, or a mechanism) every row of `x` is judged on the dense
        // data: a rate the sparse data computed as round-off, or as rising, can be a real
        // decrease there (the 500-bearing beam's "ray from p = 627" had a start of slip at
        // p ≈ 6e5).
        if let (true, Some(dense)) = (cands.is_empty(), dense) {
            let (rates, terms) = dense.rows(&dir[n..2 * n], dp);
            for v in 0..n {
                if st.basic[v]
                    && v != entering
                    && !alone(&st, v)
                    && rates[v] < 0.0
                    && -rates[v] > crate::ACCEPT_RESIDUAL * terms[v]
                {
                    judged.push((v, rates[v]));
                }
            }
        }
        if cands.is_empty() && !judged.is_empty() {
            (best, cands) = ratios(&st, &judged, &rejected);
        }
        let p_sure = scale(2 * n) > tol;
        // The judged rows move at their judged rates (their ratios, ties and values).
        for &(v, rate) in &judged {
            dir[v] = rate;
        }
        // The target on this segment: the driver's rate counts where it is above round-off,
        // or where the step carries the load a real way (1e-6 of the target) — as the dense
        // engine judges it; a mechanism's round-off rate times an unbounded step is no load.
        let p0 = st.p();
        // A step whose load rate is round-off that would move the basic values of a kind by
        // more than RUNAWAY times their largest (to its blocking row, or to the target where
        // that comes first): a mechanism of the structure whose load rate the
        // working-precision direction cannot tell from zero. The dense engine judges such a
        // step on the structure's equations refined in double-double; here the path ends (and
        // the caller traces it with the dense engine). Followed, such steps passed the sliding
        // limit of a reviewer's beams on 1100 bearings, to the target with slips of 1e20 or
        // wandering on for hundreds to thousands of pivots (1667 and 6634 against the dense
        // engine's 1100 and 3593).
        if !p_sure && best.is_finite() {
            let to_target = if dp > 0.0 && p0 < opts.target {
                (opts.target - p0) / dp
            } else {
                f64::INFINITY
            };
            if runaway(&st, &dir, entering, best.min(to_target)) > RUNAWAY {
                out.last_entering = Some(entering);
                out.mechanism_rates = Some((dir[..n].to_vec(), dir[n..2 * n].to_vec()));
                out.status = PathStatus::Mechanism;
                break;
            }
        }
        let carried = best.is_finite() && best * dp > 1e-6 * opts.target;
        if dp > 0.0 && p0 < opts.target && p0 + best * dp >= opts.target && (p_sure || carried) {
            let theta = (opts.target - p0) / dp;
            let at: Vec<f64> = (0..2 * n).map(|v| st.val[v] + theta * dir[v]).collect();
            if out.at_target.is_none() {
                out.at_target = Some((at[..n].to_vec(), at[n..].to_vec()));
                out.target_segment = Some(out.steps.len());
            }
            if opts.follow == Follow::ToTarget {
                out.last_entering = Some(entering);
                out.status = PathStatus::TargetReached;
                break;
            }
        }
        if cands.is_empty() {
            out.last_entering = Some(entering);
            out.status = if dp > 0.0 && p_sure {
                PathStatus::Ray
            } else {
                out.mechanism_rates = Some((dir[..n].to_vec(), dir[n..2 * n].to_vec()));
                PathStatus::Mechanism
            };
            break;
        }
        let mut tied: Vec<usize> = cands
            .iter()
            .filter(|&&(_, r)| r <= best + 1e-9 * best.abs() + 1e-300)
            .map(|&(v, _)| v)
            .collect();
        // Two basic rows of a relation whose other rows are non-basic fall together: the
        // relation ties them exactly, their computed ratios only to round-off.
        for k in 0..tied.len() {
            if let Some(b) = partner(&st, tied[k]) {
                if !tied.contains(&b) && cands.iter().any(|c| c.0 == b) {
                    tied.push(b);
                }
            }
        }
        if tied.len() > 1 {
            decide_related(
                &mut tied,
                &st,
                &dir,
                &relation_of,
                &opts.relations,
                &position,
            );
        }
        let leaving = if tied.len() == 1 {
            tied[0]
        } else {
            lexicographic(&basis, &st.basic, &tied, &dir, big_n, &order)
        };
        let theta = cands.iter().find(|c| c.0 == leaving).map_or(best, |c| c.1);
        if leaving == 2 * n {
            out.last_entering = Some(entering);
            out.status = PathStatus::ReturnedToZero;
            break;
        }
        // Pivot.
        let turning = dp < 0.0 && theta > 0.0;
        st.basic[entering] = true;
        st.basic[leaving] = false;
        // The values move along the segment; they are formed afresh from the data (and
        // refined) at every refactorisation.
        for (v, val) in st.val.iter_mut().enumerate() {
            if st.basic[v] {
                *val += theta * dir[v];
            }
        }
        st.val[leaving] = 0.0;
        fresh = false;
        let known = entering_row.map(|(row, entry)| bordered::KnownColumn {
            row,
            entry,
            t: &base_dir,
        });
        let updated = basis.pivot_with(entering, leaving, known);
        if updated.is_err() {
            singular_updates += 1;
        }
        if updated.is_err() || basis.border() > opts.max_border {
            let nonbasic: Vec<bool> = st.basic.iter().map(|b| !b).collect();
            if basis.refactor(&nonbasic).is_err() {
                out.status = PathStatus::NumericalFailure;
                break;
            }
            values(lcp, &basis, &mut st);
            fresh = true;
        }
        if st.val.iter().any(|v| !v.is_finite()) {
            out.status = PathStatus::NumericalFailure;
            break;
        }
        let p_before = out.steps.last().map_or(0.0, |s| s.p);
        if (st.p() - p_before).abs() <= 1e-12 * st.p().abs().max(p_before.abs()) {
            degenerate += 1;
            if degenerate > n {
                out.status = PathStatus::NumericalFailure;
                break;
            }
        } else {
            degenerate = 0;
        }
        opts.progress.step(st.p());
        out.steps.push(Step {
            index: out.steps.len() + 1,
            p: st.p(),
            entering: Var::from_col(entering, n),
            leaving: Var::from_col(leaving, n),
            turning,
        });
        out.breakpoints.push(Breakpoint {
            p: st.p(),
            z: st
                .z()
                .iter()
                .enumerate()
                .filter(|(_, &v)| v != 0.0)
                .map(|(i, &v)| (i, v))
                .collect(),
        });
        entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
    }
    out.refactorizations = basis.refactorizations;
    out.singular_updates = singular_updates;
    out
}

/// See the step's check in [`follow`]: far beyond the steps of genuine paths with small load
/// rates (at most 0.02 on a reviewer's 1200-bearing path, `pivoting/pivot.rs`), far below the
/// steps past a sliding limit (1.7e4 to 1e10).
const RUNAWAY: f64 = 100.0;

/// How far a step of length `theta` along `dir` moves the basic values of each kind (`x`,
/// `z`; the entering variable's rate one) against the largest of that kind: the larger. A kind
/// whose basic values are all zero (no slip or opening yet) is not counted: against zero every
/// step would be a runaway, and the first slip entering at a constant load would end the path
/// (a reviewer's reading of the code).
fn runaway(st: &State, dir: &[f64], entering: usize, theta: f64) -> f64 {
    let n = st.n;
    let (mut rate, mut value) = ([0.0f64; 2], [0.0f64; 2]);
    for v in (0..2 * n).filter(|&v| st.basic[v]) {
        let k = usize::from(v >= n);
        rate[k] = rate[k].max(dir[v].abs());
        value[k] = value[k].max(st.val[v].abs());
    }
    if entering < 2 * n {
        let k = usize::from(entering >= n);
        rate[k] = rate[k].max(1.0);
    }
    (0..2)
        .filter(|&k| rate[k] > 0.0 && value[k] > 0.0)
        .map(|k| theta * rate[k] / value[k])
        .fold(0.0f64, f64::max)
}

/// Ties between two rows of one relation whose other rows are non-basic, decided from the
/// relation: along the segment `λ_a x_a + λ_b x_b = Σ λ_i ε_i` (the rows' lexicographic
/// perturbations), and the rates obey `λ_a α_a = −λ_b α_b`, so the ratios differ by
/// `Σ λ_i ε_i / (λ_a α_a)`, whose sign is that of the relation's first row in the order. The
/// row with the larger ratio is dropped from the tie; computed ratios differ only by round-off.
fn decide_related(
    tied: &mut Vec<usize>,
    st: &State,
    dir: &[f64],
    relation_of: &[usize],
    relations: &[crate::RowRelation],
    position: &[usize],
) {
    let n = st.n;
    let mut k = 0;
    while k < tied.len() {
        let a = tied[k];
        let partner = (a < n && relation_of[a] != usize::MAX)
            .then(|| {
                let rel = &relations[relation_of[a]];
                let basic: Vec<usize> = rel
                    .terms
                    .iter()
                    .map(|&(i, _)| i)
                    .filter(|&i| st.basic[i])
                    .collect();
                (basic.len() == 2)
                    .then(|| basic.into_iter().find(|&i| i != a))
                    .flatten()
                    .filter(|b| tied.contains(b))
                    .map(|b| (b, rel))
            })
            .flatten();
        if let Some((b, rel)) = partner {
            let lambda = |i: usize| rel.terms.iter().find(|t| t.0 == i).map_or(0.0, |t| t.1);
            let first = rel
                .terms
                .iter()
                .min_by_key(|t| position[t.0])
                .map_or(0.0, |t| t.1);
            // r_a − r_b has the sign of first / (λ_a α_a), α = −dir.
            let diff = first / (lambda(a) * -dir[a]);
            let drop = if diff > 0.0 { a } else { b };
            tied.retain(|&v| v != drop);
            k = 0;
            continue;
        }
        k += 1;
    }
}

/// `Σ_j |D_ij| |dz_j| + Σ_k |C_ik| |dy_k|`: the size of the terms that form row `i`'s rate.
fn row_terms(
    dt: &SparseColMat<usize, f64>,
    ct: &SparseColMat<usize, f64>,
    i: usize,
    dy: &[f64],
    dz: &[f64],
) -> f64 {
    let dot = |m: &SparseColMat<usize, f64>, u: &[f64]| -> f64 {
        m.row_idx_of_col_raw(i)
            .iter()
            .zip(m.val_of_col(i))
            .map(|(&j, &a)| (a * u[j]).abs())
            .sum()
    };
    dot(dt, dz) + dot(ct, dy)
}

/// The basic values from the data.
fn values(lcp: &SchurLcp, basis: &Bordered, st: &mut State) {
    let n = st.n;
    let big_n = lcp.a.nrows();
    let mut r = vec![0.0; big_n + 2 * n + 1];
    r[..big_n].copy_from_slice(&lcp.qa);
    r[big_n..big_n + n].copy_from_slice(&lcp.q0);
    let mut v = basis.solve(&r, |_| 0.0);
    refine_in_place(
        lcp,
        basis,
        &st.basic,
        Some((&lcp.qa, &lcp.q0)),
        None,
        &mut v,
        (&mut Vec::new(), &mut Vec::new()),
    );
    for i in 0..=2 * n {
        st.val[i] = if st.basic[i] { v[big_n + i] } else { 0.0 };
    }
}

/// One step of iterative refinement, in place, of a solution `v` of the basis system whose
/// equations' right-hand side is `(qa, q0)` (`None` for zero), whose non-basic variables are
/// zero but `unit` (one): the residual of the two blocks of equations formed from the data,
/// solved for the correction. The bordered solve's round-off grows with the border and the
/// mixed sizes of forces and displacements; one step brings it back to the data's. `res` and
/// `dv` are work vectors of the base's size (reused from step to step). Only the tableau's
/// part (`x`, `z`, `p`) is corrected — what the engine decides on; the structure's `y` is left
/// as the first solve gave it (the correction for it would stream two thirds of the border's
/// columns).
fn refine_in_place(
    lcp: &SchurLcp,
    basis: &Bordered,
    basic: &[bool],
    rhs: Option<(&[f64], &[f64])>,
    unit: Option<usize>,
    v: &mut [f64],
    (res, dv): (&mut Vec<f64>, &mut Vec<f64>),
) {
    let n = lcp.order();
    let big_n = lcp.a.nrows();
    for (k, val) in v[big_n..].iter_mut().enumerate() {
        if !basic[k] {
            *val = f64::from(Some(k) == unit);
        }
    }
    res.clear();
    res.resize(big_n + 2 * n + 1, 0.0);
    if let Some((qa, q0)) = rhs {
        res[..big_n].copy_from_slice(qa);
        res[big_n..big_n + n].copy_from_slice(q0);
    }
    let (y, rest) = v.split_at(big_n);
    let (x, rest) = rest.split_at(n);
    let (z, p) = rest.split_at(n);
    let p = p[0];
    let sub = |out: &mut [f64], m: &SparseColMat<usize, f64>, u: &[f64], sign: f64| {
        for (j, &uj) in u.iter().enumerate() {
            if uj != 0.0 {
                for (&i, &a) in m.row_idx_of_col_raw(j).iter().zip(m.val_of_col(j)) {
                    out[i] -= sign * a * uj;
                }
            }
        }
    };
    {
        let (r1, r2) = res.split_at_mut(big_n);
        sub(r1, &lcp.a, y, 1.0);
        sub(r1, &lcp.b, z, -1.0);
        for (r, d) in r1.iter_mut().zip(&lcp.da) {
            *r += d * p;
        }
        let r2 = &mut r2[..n];
        for (r, xi) in r2.iter_mut().zip(x) {
            *r -= xi;
        }
        sub(r2, &lcp.d, z, -1.0);
        sub(r2, &lcp.c, y, 1.0);
        for (r, d) in r2.iter_mut().zip(&lcp.d0) {
            *r += d * p;
        }
    }
    basis.solve_into(res, |_| 0.0, dv, None, big_n);
    for (a, b) in v[big_n..].iter_mut().zip(&dv[big_n..]) {
        *a += b;
    }
}

/// The tied candidate that leaves by the lexicographic rule: the smallest row of
/// `B⁻¹ / (−α)` over the tableau's rows in their priority order. The rows are never formed:
/// the entries are computed one priority column at a time for the candidates still tied —
/// a unit column where the row's `x` is basic (it appears in its own equation alone), else
/// one solve of the basis — so a tie costs a few solves, where a row of `B⁻¹` a candidate
/// cost two whole solves (a 500-bearing beam's degenerate stretch: 47 s of ties for a path
/// the dense engine traced in 0.2 s).
fn lexicographic(
    basis: &Bordered,
    basic: &[bool],
    tied: &[usize],
    dir: &[f64],
    big_n: usize,
    order: &[usize],
) -> usize {
    let n = order.len();
    let mut alive: Vec<usize> = tied.to_vec();
    let mut rhs = vec![0.0; big_n + 2 * n + 1];
    for &i in order {
        // (entry / (−α), its round-off) for each candidate still tied.
        let vals: Vec<(f64, f64)> = if basic[i] {
            alive
                .iter()
                .map(|&v| (if v == i { 1.0 / -dir[v] } else { 0.0 }, 0.0))
                .collect()
        } else {
            rhs.fill(0.0);
            rhs[big_n + i] = 1.0;
            let t = basis.solve(&rhs, |_| 0.0);
            // Round-off against the column's largest entry of `x` and `z`.
            let scale = t[big_n..big_n + 2 * n]
                .iter()
                .fold(0.0f64, |a, v| a.max(v.abs()));
            alive
                .iter()
                .map(|&v| {
                    let a = -dir[v];
                    (t[basis.unknown(v)] / a, 1e-9 * scale / a.abs())
                })
                .collect()
        };
        if vals.iter().all(|&(v, t)| v.abs() <= t) {
            continue;
        }
        let (best, tb) =
            vals.iter().copied().fold(
                (f64::INFINITY, 0.0),
                |acc, (v, t)| if v < acc.0 { (v, t) } else { acc },
            );
        let mut keep = vals.iter().map(|&(v, t)| (v - best).abs() <= t.max(tb));
        alive.retain(|_| keep.next().unwrap_or(false));
        if alive.len() == 1 {
            break;
        }
    }
    alive[0]
}

/// Data shared by the sparse engine's unit tests.
#[cfg(test)]
pub(crate) mod test_data {
    use super::SchurLcp;
    use faer::sparse::{SparseColMat, Triplet};
    use faer::Mat;

    /// `m` as a sparse matrix (its non-zero entries).
    pub fn sparse(m: &Mat<f64>) -> SparseColMat<usize, f64> {
        let mut t = Vec::new();
        for j in 0..m.ncols() {
            for i in 0..m.nrows() {
                if m[(i, j)] != 0.0 {
                    t.push(Triplet::new(i, j, m[(i, j)]));
                }
            }
        }
        SparseColMat::try_new_from_triplets(m.nrows(), m.ncols(), &t).unwrap()
    }

    /// A small problem (`n = 4`, `N = 5`): a well-conditioned `A` and arbitrary couplings.
    pub fn small_lcp() -> SchurLcp {
        let (n, big_n) = (4, 5);
        let a = Mat::<f64>::from_fn(big_n, big_n, |i, j| {
            if i == j {
                6.0 + i as f64
            } else {
                1.0 / (1.0 + (i + 2 * j) as f64)
            }
        });
        let b = Mat::<f64>::from_fn(big_n, n, |i, j| ((i * 3 + j * 5) % 7) as f64 - 3.0);
        let c = Mat::<f64>::from_fn(n, big_n, |i, j| ((i * 5 + j * 2) % 5) as f64 - 2.0);
        let d = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 9.0 } else { 0.5 });
        SchurLcp {
            a: sparse(&a),
            b: sparse(&b),
            c: sparse(&c),
            d: sparse(&d),
            q0: vec![1.0; n],
            qa: vec![0.5; big_n],
            d0: vec![-1.0, 2.0, 0.5, 1.5],
            da: vec![0.3, -0.2, 0.1, 0.0, 0.7],
        }
    }
}
