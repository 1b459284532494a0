//! An independent small-step computation of a load history with **incremental** Coulomb
//! friction: the reference that the exact path of a history is checked against.
//!
//! The exact evolution (the engine's) follows each stage by parametric pivoting and locates every
//! change of the working scheme. This module does something deliberately different and much
//! simpler: it cuts every stage into equal increments of the stage parameter and solves, for each
//! increment, one LCP in the increments (backward Euler: the forces are taken at the end of the
//! increment) by enumerating its complementary index sets. It shares no code with the engine, and
//! its answer converges to the exact path as the step shrinks (it is exact where no working scheme
//! changes strictly inside a step).
//!
//! # The increment's LCP
//!
//! Signs as `docs/formulation.md` §1: `x_n` compression `> 0`, `z_n` opening `> 0`,
//! `x_t± = f·x_n ± x_t ≥ 0`; a slip increment `Δ+ > 0` forces `x_t = −f·x_n`, `Δ− > 0` forces
//! `x_t = +f·x_n`, and the accumulated slip is `z_t = z_t,prev + (Δ+ − Δ−)/2`. The link forces at
//! the load factors `φ` of the end of the increment are
//!
//! ```text
//! x_n = Σ_c φ_c·Rn_c + Rnn·(z_n − η) + Rnt·z_t
//! x_t = Σ_c φ_c·Rt_c + Rtn·(z_n − η) + Rtt·z_t
//! ```
//!
//! (`η` the initial gaps: at zero load `z_n = η`, `z_t = 0`, `x = 0`). The normal response is
//! elastic and unilateral, so the unknown on the normal rows is the **total** opening `z_n`
//! (complementary to `x_n`); only friction is incremental, so the unknowns on the tangential rows
//! are the slip increments `Δ±` (complementary to `x_t±`). With `u = [z_n; Δ+; Δ−]` and
//! `w = [x_n; x_t+; x_t−]` this is `w = q + M u ≥ 0`, `u ≥ 0`, `wᵀu = 0` with the `M` of
//! formulation.md §3 and
//!
//! ```text
//! b_n = Σ φ·Rn − Rnn·η + Rnt·z_t,prev,   b_t = Σ φ·Rt − Rtn·η + Rtt·z_t,prev,
//! q   = [ b_n ; F·b_n + b_t ; F·b_n − b_t ].
//! ```
//!
//! A slipping pair whose slip would reverse or stop gets `Δ± = 0` and keeps its slip; an open pair
//! (`x_n = 0`, hence `x_t = 0`) moves freely: its `z_t` is its current tangential mutual
//! displacement.
//!
//! # How each increment is solved
//!
//! Every complementary index set `S` (`u` may be non-zero only on `S`, `w = 0` on `S`) is tried
//! in `f64`: `M_SS u_S = −q_S` by Gaussian elimination with partial pivoting, kept if `u ≥ 0` and
//! `w ≥ 0` within tolerances relative to the data's scale (forces: the largest load a case can
//! bring, stiffness: the largest entry of the zone's matrices; so the answer does not change with
//! the units). Sets holding both `Δ+` and `Δ−` of one pair are skipped: their columns are
//! opposite, `M_SS` is singular. If no set gives a solution in `f64`, the increment is solved
//! again by the crate's exact enumeration ([`crate::enumerate`], which also decides the singular
//! sets). Among the solutions found, all must have the same forces `w` (otherwise the rate
//! problem is not unique and the answer would be a guess: an error); the one with the smallest
//! `Σ(Δ+ + Δ−)` is taken (the first in enumeration order among equals), which fixes the free
//! split of an open pair's motion deterministically.

use crate::enumerate;

/// The largest number of pairs [`small_steps`] accepts (`2^(3m) ≤ 4096` index sets per
/// increment).
pub const MAX_HISTORY_PAIRS: usize = 4;

/// Relative tolerance of the sign tests (`u ≥ 0`, `w ≥ 0`) against the data's scale.
const SIGN_TOL: f64 = 1e-9;
/// Relative tolerance for "the same forces" between two solutions of one increment.
const SAME_FORCES_TOL: f64 = 1e-7;
/// A pivot below this share of the largest entry of `M_SS` makes the set singular.
const PIVOT_TOL: f64 = 1e-11;

/// A contact zone with its load cases, as plain data (row-major `m × m` blocks; signs as
/// formulation.md §1–§2).
#[derive(Clone, Debug, PartialEq)]
pub struct HistoryZone {
    /// `Rnn`: normal link forces per unit normal dislocation.
    pub rnn: Vec<Vec<f64>>,
    /// `Rnt`: normal link forces per unit tangential dislocation.
    pub rnt: Vec<Vec<f64>>,
    /// `Rtn`: tangential link forces per unit normal dislocation.
    pub rtn: Vec<Vec<f64>>,
    /// `Rtt`: tangential link forces per unit tangential dislocation.
    pub rtt: Vec<Vec<f64>>,
    /// The friction coefficient of every pair (`≥ 0`).
    pub friction: Vec<f64>,
    /// The initial gap of every pair (`≥ 0`).
    pub gap: Vec<f64>,
    /// Per load case: the normal and the tangential link forces of the bonded structure under
    /// the case at factor 1.
    pub cases: Vec<(Vec<f64>, Vec<f64>)>,
}

/// The state of the zone at one load (per pair).
#[derive(Clone, Debug, PartialEq)]
pub struct OracleState {
    /// Normal force (compression `> 0`).
    pub x_n: Vec<f64>,
    /// Tangential force.
    pub x_t: Vec<f64>,
    /// Total normal opening (`= η` at zero load, `0` when closed).
    pub z_n: Vec<f64>,
    /// Accumulated slip (for an open pair: its current tangential mutual displacement).
    pub z_t: Vec<f64>,
}

impl OracleState {
    /// The unloaded start: no force, every pair at its initial gap, no slip.
    pub fn unloaded(zone: &HistoryZone) -> OracleState {
        let m = zone.friction.len();
        OracleState {
            x_n: vec![0.0; m],
            x_t: vec![0.0; m],
            z_n: zone.gap.clone(),
            z_t: vec![0.0; m],
        }
    }
}

/// Follows a load history by `steps_per_stage` equal increments of every stage's parameter.
///
/// `stages[k]` holds the factor of every case (in the order of [`HistoryZone::cases`]) at the
/// end of stage `k`; every case starts at factor 0, and within a stage the factors move linearly
/// from where the previous stage ended. Returns, per stage, the state after each increment (the
/// last one is the stage's end, at exactly its factors).
///
/// # Errors
/// Bad sizes or values (non-finite data, negative friction or gap, more than
/// [`MAX_HISTORY_PAIRS`] pairs, no increment), or an increment whose LCP has no solution or
/// solutions with different forces: the message names the stage and the step (1-based).
pub fn small_steps(
    zone: &HistoryZone,
    stages: &[Vec<f64>],
    steps_per_stage: usize,
) -> Result<Vec<Vec<OracleState>>, String> {
    let problem = Problem::new(zone, stages)?;
    if steps_per_stage == 0 {
        return Err("steps_per_stage must be at least 1".into());
    }
    let mut state = OracleState::unloaded(zone);
    let mut start = vec![0.0; zone.cases.len()];
    let mut out = Vec::with_capacity(stages.len());
    for (k, end) in stages.iter().enumerate() {
        let mut states = Vec::with_capacity(steps_per_stage);
        for j in 1..=steps_per_stage {
            let phi: Vec<f64> = if j == steps_per_stage {
                end.clone()
            } else {
                let s = j as f64 / steps_per_stage as f64;
                start
                    .iter()
                    .zip(end)
                    .map(|(a, b)| a + s * (b - a))
                    .collect()
            };
            state = problem
                .increment(&phi, &state)
                .map_err(|why| format!("stage {}, step {j}: {why}", k + 1))?;
            states.push(state.clone());
        }
        start.clone_from(end);
        out.push(states);
    }
    Ok(out)
}

/// The zone, the increment's matrix and the tolerances of one history.
struct Problem<'a> {
    zone: &'a HistoryZone,
    m: usize,
    /// `M` of the increment's LCP, `3m × 3m`, row-major.
    mat: Vec<Vec<f64>>,
    /// Absolute tolerance on forces.
    tol_force: f64,
    /// Absolute tolerance on displacements.
    tol_disp: f64,
}

/// One solution of an increment: `u = [z_n; Δ+; Δ−]` and `w = [x_n; x_t+; x_t−]`.
struct Candidate {
    u: Vec<f64>,
    w: Vec<f64>,
}

impl<'a> Problem<'a> {
    fn new(zone: &'a HistoryZone, stages: &[Vec<f64>]) -> Result<Self, String> {
        let m = zone.friction.len();
        if m == 0 || m > MAX_HISTORY_PAIRS {
            return Err(format!(
                "the zone must have 1 to {MAX_HISTORY_PAIRS} pairs (it has {m})"
            ));
        }
        for (name, block) in [
            ("rnn", &zone.rnn),
            ("rnt", &zone.rnt),
            ("rtn", &zone.rtn),
            ("rtt", &zone.rtt),
        ] {
            if block.len() != m || block.iter().any(|row| row.len() != m) {
                return Err(format!("{name} must be {m} × {m}"));
            }
            if block.iter().flatten().any(|v| !v.is_finite()) {
                return Err(format!("{name} has a non-finite entry"));
            }
        }
        check_vector("friction", &zone.friction, m, true)?;
        check_vector("gap", &zone.gap, m, true)?;
        for (c, (rn, rt)) in zone.cases.iter().enumerate() {
            check_vector(&format!("case {} normal", c + 1), rn, m, false)?;
            check_vector(&format!("case {} tangential", c + 1), rt, m, false)?;
        }
        for (k, phi) in stages.iter().enumerate() {
            if phi.len() != zone.cases.len() {
                return Err(format!(
                    "stage {} has {} factors for {} cases",
                    k + 1,
                    phi.len(),
                    zone.cases.len()
                ));
            }
            if phi.iter().any(|v| !v.is_finite()) {
                return Err(format!("stage {} has a non-finite factor", k + 1));
            }
        }
        let stiffness = [&zone.rnn, &zone.rnt, &zone.rtn, &zone.rtt]
            .iter()
            .flat_map(|b| b.iter().flatten())
            .fold(0.0f64, |a, v| a.max(v.abs()));
        if stiffness == 0.0 {
            return Err("the zone has no stiffness (every matrix entry is zero)".into());
        }
        // The largest force the data can bring: every case at its largest factor, the gaps
        // closed; times max(1, f) for the rows x_t± = f·x_n ± x_t.
        let load: f64 = zone
            .cases
            .iter()
            .enumerate()
            .map(|(c, (rn, rt))| {
                let phi = stages.iter().fold(0.0f64, |a, s| a.max(s[c].abs()));
                phi * max_abs(rn).max(max_abs(rt))
            })
            .sum();
        let friction = zone.friction.iter().fold(1.0f64, |a, &f| a.max(f));
        let force = friction * (load + stiffness * m as f64 * max_abs(&zone.gap));
        Ok(Problem {
            zone,
            m,
            mat: increment_matrix(zone),
            tol_force: SIGN_TOL * force,
            tol_disp: SIGN_TOL * force / stiffness,
        })
    }

    /// One backward-Euler increment from `prev` to the load at factors `phi`.
    fn increment(&self, phi: &[f64], prev: &OracleState) -> Result<OracleState, String> {
        let (m, z) = (self.m, self.zone);
        // The bonded structure's link forces at phi, after the gaps and the slip so far.
        let mut b_n = vec![0.0; m];
        let mut b_t = vec![0.0; m];
        for i in 0..m {
            let (mut bn, mut bt) = (0.0, 0.0);
            for (c, (rn, rt)) in z.cases.iter().enumerate() {
                bn += phi[c] * rn[i];
                bt += phi[c] * rt[i];
            }
            for j in 0..m {
                bn += z.rnt[i][j] * prev.z_t[j] - z.rnn[i][j] * z.gap[j];
                bt += z.rtt[i][j] * prev.z_t[j] - z.rtn[i][j] * z.gap[j];
            }
            b_n[i] = bn;
            b_t[i] = bt;
        }
        let mut q = vec![0.0; 3 * m];
        for i in 0..m {
            let f = z.friction[i];
            q[i] = b_n[i];
            q[m + i] = f * b_n[i] + b_t[i];
            q[2 * m + i] = f * b_n[i] - b_t[i];
        }
        let chosen = self.solve(&q)?;
        let u: Vec<f64> = chosen.u.iter().map(|v| v.max(0.0)).collect();
        let z_n = u[..m].to_vec();
        let z_t: Vec<f64> = (0..m)
            .map(|i| prev.z_t[i] + 0.5 * (u[m + i] - u[2 * m + i]))
            .collect();
        // The forces from their definition at the new state.
        let mut x_n = vec![0.0; m];
        let mut x_t = vec![0.0; m];
        for i in 0..m {
            let (mut xn, mut xt) = (0.0, 0.0);
            for (c, (rn, rt)) in z.cases.iter().enumerate() {
                xn += phi[c] * rn[i];
                xt += phi[c] * rt[i];
            }
            for j in 0..m {
                let open = z_n[j] - z.gap[j];
                xn += z.rnn[i][j] * open + z.rnt[i][j] * z_t[j];
                xt += z.rtn[i][j] * open + z.rtt[i][j] * z_t[j];
            }
            x_n[i] = xn;
            x_t[i] = xt;
        }
        let state = OracleState { x_n, x_t, z_n, z_t };
        let finite = [&state.x_n, &state.x_t, &state.z_n, &state.z_t]
            .iter()
            .all(|v| v.iter().all(|x| x.is_finite()));
        if !finite {
            return Err("the increment's solution is not finite".into());
        }
        Ok(state)
    }

    /// The chosen solution of `w = q + M u` (see the module documentation).
    fn solve(&self, q: &[f64]) -> Result<Candidate, String> {
        let m = self.m;
        let n = 3 * m;
        let mut found: Vec<Candidate> = Vec::new();
        let mut a = vec![0.0; n * n];
        let mut rhs = vec![0.0; n];
        for mask in 0u32..(1u32 << n) {
            let plus = (mask >> m) & ((1 << m) - 1);
            let minus = (mask >> (2 * m)) & ((1 << m) - 1);
            if plus & minus != 0 {
                continue; // opposite columns: singular
            }
            let set: Vec<usize> = (0..n).filter(|&i| mask & (1 << i) != 0).collect();
            let k = set.len();
            for (r, &i) in set.iter().enumerate() {
                for (c, &j) in set.iter().enumerate() {
                    a[r * k + c] = self.mat[i][j];
                }
                rhs[r] = -q[i];
            }
            if !gauss_solve(&mut a[..k * k], &mut rhs[..k], k) {
                continue;
            }
            let mut u = vec![0.0; n];
            for (r, &i) in set.iter().enumerate() {
                u[i] = rhs[r];
            }
            if let Some(c) = self.accept(q, u) {
                found.push(c);
            }
        }
        if found.is_empty() {
            // Every set that could hold a solution was singular in f64: decide exactly.
            for sol in enumerate(&self.mat, q) {
                if let Some(c) = self.accept(q, sol.z_f64()) {
                    found.push(c);
                }
            }
        }
        let first = found
            .first()
            .ok_or_else(|| format!("the increment's LCP (size {n}) has no solution"))?;
        let tol = SAME_FORCES_TOL / SIGN_TOL * self.tol_force;
        if let Some(other) = found.iter().find(|c| max_diff(&c.w, &first.w) > tol) {
            return Err(format!(
                "the increment's LCP has solutions with different forces \
                 (w differs by {:e}): the rate problem is not unique",
                max_diff(&other.w, &first.w)
            ));
        }
        let slip = |c: &Candidate| c.u[m..].iter().sum::<f64>();
        let mut best = 0;
        for (i, c) in found.iter().enumerate().skip(1) {
            if slip(c) < slip(&found[best]) - self.tol_disp {
                best = i;
            }
        }
        Ok(found.swap_remove(best))
    }

    /// `u` with its `w = q + M u` if both are non-negative within the tolerances.
    fn accept(&self, q: &[f64], u: Vec<f64>) -> Option<Candidate> {
        if !u.iter().all(|&v| v >= -self.tol_disp) {
            return None;
        }
        let w: Vec<f64> = self
            .mat
            .iter()
            .zip(q)
            .map(|(row, qi)| qi + row.iter().zip(&u).map(|(a, b)| a * b).sum::<f64>())
            .collect();
        if !w.iter().all(|&v| v >= -self.tol_force) {
            return None;
        }
        Some(Candidate { u, w })
    }
}

/// `M` of formulation.md §3 (the increment's LCP has the same matrix as the total one):
///
/// ```text
/// [ Rnn          Rnt/2              −Rnt/2           ]
/// [ F·Rnn + Rtn  (F·Rnt + Rtt)/2    −(F·Rnt + Rtt)/2 ]
/// [ F·Rnn − Rtn  (F·Rnt − Rtt)/2    −(F·Rnt − Rtt)/2 ]
/// ```
fn increment_matrix(z: &HistoryZone) -> Vec<Vec<f64>> {
    let m = z.friction.len();
    let mut a = vec![vec![0.0; 3 * m]; 3 * m];
    for i in 0..m {
        let f = z.friction[i];
        for j in 0..m {
            let (nn, nt, tn, tt) = (z.rnn[i][j], z.rnt[i][j], z.rtn[i][j], z.rtt[i][j]);
            a[i][j] = nn;
            a[i][m + j] = 0.5 * nt;
            a[i][2 * m + j] = -0.5 * nt;
            a[m + i][j] = f * nn + tn;
            a[m + i][m + j] = 0.5 * (f * nt + tt);
            a[m + i][2 * m + j] = -0.5 * (f * nt + tt);
            a[2 * m + i][j] = f * nn - tn;
            a[2 * m + i][m + j] = 0.5 * (f * nt - tt);
            a[2 * m + i][2 * m + j] = -0.5 * (f * nt - tt);
        }
    }
    a
}

/// Solves `A y = b` in place (`A` row-major `k × k`, `y` replaces `b`) by Gaussian elimination
/// with partial pivoting; `false` if a pivot is below [`PIVOT_TOL`] times the largest entry of
/// `A` (singular for this purpose).
fn gauss_solve(a: &mut [f64], b: &mut [f64], k: usize) -> bool {
    let scale = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    if k == 0 {
        return true;
    }
    if scale == 0.0 {
        return false;
    }
    for c in 0..k {
        let p = (c..k)
            .max_by(|&i, &j| a[i * k + c].abs().total_cmp(&a[j * k + c].abs()))
            .expect("c < k");
        if a[p * k + c].abs() <= PIVOT_TOL * scale {
            return false;
        }
        if p != c {
            for j in 0..k {
                a.swap(c * k + j, p * k + j);
            }
            b.swap(c, p);
        }
        let piv = a[c * k + c];
        for r in c + 1..k {
            let l = a[r * k + c] / piv;
            if l != 0.0 {
                for j in c..k {
                    a[r * k + j] -= l * a[c * k + j];
                }
                b[r] -= l * b[c];
            }
        }
    }
    for c in (0..k).rev() {
        let s: f64 = (c + 1..k).map(|j| a[c * k + j] * b[j]).sum();
        b[c] = (b[c] - s) / a[c * k + c];
    }
    true
}

fn check_vector(name: &str, v: &[f64], m: usize, non_negative: bool) -> Result<(), String> {
    if v.len() != m {
        return Err(format!("{name} must have {m} entries (it has {})", v.len()));
    }
    if v.iter().any(|x| !x.is_finite()) {
        return Err(format!("{name} has a non-finite entry"));
    }
    if non_negative && v.iter().any(|&x| x < 0.0) {
        return Err(format!("{name} has a negative entry"));
    }
    Ok(())
}

fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::{example1, frictional_lcp, random::Lcg};
    use crate::{enumerate_exact, frac, rat_matrix, rat_vec, Rat};
    use num_traits::Zero;

    /// A single pair on rigid ground: `Rnn = k_n`, `Rtt = k_t`, no coupling; case 1 presses it
    /// with `N`, case 2 pushes it sideways with `T` (bonded link forces at factor 1).
    fn single_pair(k_n: f64, k_t: f64, f: f64, gap: f64, n: f64, t: f64) -> HistoryZone {
        HistoryZone {
            rnn: vec![vec![k_n]],
            rnt: vec![vec![0.0]],
            rtn: vec![vec![0.0]],
            rtt: vec![vec![k_t]],
            friction: vec![f],
            gap: vec![gap],
            cases: vec![(vec![n], vec![0.0]), (vec![0.0], vec![t])],
        }
    }

    /// Stage ends as `[x_n, x_t, z_n, z_t]` of the single pair.
    fn ends(states: &[Vec<OracleState>]) -> Vec<[f64; 4]> {
        states
            .iter()
            .map(|s| {
                let e = s.last().expect("a stage has steps");
                [e.x_n[0], e.x_t[0], e.z_n[0], e.z_t[0]]
            })
            .collect()
    }

    /// Compares stage ends with hand values: forces relative to `force`, displacements to
    /// `disp` (the data's scales, so the check does not depend on the units).
    fn assert_ends(got: &[[f64; 4]], want: &[[f64; 4]], force: f64, disp: f64, what: &str) {
        assert_eq!(got.len(), want.len());
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            for (c, scale) in [force, force, disp, disp].into_iter().enumerate() {
                assert!(
                    (g[c] - w[c]).abs() <= 1e-12 * scale,
                    "{what}: stage {} component {c}: got {:?}, want {:?}",
                    k + 1,
                    g,
                    w
                );
            }
        }
    }

    /// Reference: hand calculation. The pair is pressed by `N` (closed, `x_n = N`, `z_n = 0`
    /// throughout, as nothing else acts normally), so the friction limit is `L = f·N`. With
    /// `x_t = φ_T·T + k_t·z_t`, the pair sticks (`z_t` constant) while `|x_t| < L`; when the
    /// elastic trial `φ_T·T + k_t·z_t,prev` passes `±L` it slips with `x_t = ±L`,
    /// `z_t = (±L − φ_T·T)/k_t`. A single pair whose load moves monotonically within a stage has
    /// a rate that does not change sign within the stage, so the backward-Euler step (which is
    /// exactly this trial-and-return) is exact at every step, whatever their number.
    ///
    /// `T = L` at factor 1, stages `φ_T`: 0 (N on), `a`, 0, `−a`, 0.
    ///
    /// * `a = 1.5` (`L < T* < 2L`): push to `1.5L`: slides, `x_t = L`, `z_t = (L − 1.5L)/k_t =
    ///   −L/(2k_t)`; release: trial `−L/2`, inside the cone: sticks, residual force `−L/2`, slip
    ///   kept; pull to `−1.5L`: trial `−2L` passes `−L`: `x_t = −L`, `z_t = (−L + 1.5L)/k_t =
    ///   L/(2k_t)`; release: trial `L/2`: sticks, residual `L/2`, slip `L/(2k_t)`.
    /// * `a = 3` (`T* > 2L`, reverse slip during unloading): push: `x_t = L`, `z_t = −2L/k_t`;
    ///   release: trial `−2L`: slips back, `x_t = −L`, `z_t = −L/k_t`; pull to `−3L`: `x_t = −L`,
    ///   `z_t = (−L + 3L)/k_t = 2L/k_t`; release: trial `2L`: `x_t = L`, `z_t = L/k_t`.
    #[test]
    fn single_pair_loaded_released_reversed_released() {
        // N·m, then kN·mm (forces × 1e-3, lengths × 1e3, stiffness × 1e-6): the same answer.
        for (force_unit, length_unit) in [(1.0, 1.0), (1e-3, 1e3)] {
            let (k_n, k_t, f, n) = (
                2.0e8 * force_unit / length_unit,
                5.0e7 * force_unit / length_unit,
                0.4,
                1.0e5 * force_unit,
            );
            let l = f * n;
            let zone = single_pair(k_n, k_t, f, 0.0, n, l);
            for a in [1.5, 3.0] {
                let stages = [
                    vec![1.0, 0.0],
                    vec![1.0, a],
                    vec![1.0, 0.0],
                    vec![1.0, -a],
                    vec![1.0, 0.0],
                ];
                let want: Vec<[f64; 4]> = if a == 1.5 {
                    vec![
                        [n, 0.0, 0.0, 0.0],
                        [n, l, 0.0, -l / (2.0 * k_t)],
                        [n, -l / 2.0, 0.0, -l / (2.0 * k_t)],
                        [n, -l, 0.0, l / (2.0 * k_t)],
                        [n, l / 2.0, 0.0, l / (2.0 * k_t)],
                    ]
                } else {
                    vec![
                        [n, 0.0, 0.0, 0.0],
                        [n, l, 0.0, -2.0 * l / k_t],
                        [n, -l, 0.0, -l / k_t],
                        [n, -l, 0.0, 2.0 * l / k_t],
                        [n, l, 0.0, l / k_t],
                    ]
                };
                for steps in [1, 3, 10] {
                    let got = ends(&small_steps(&zone, &stages, steps).unwrap());
                    let what = format!("a = {a}, {steps} steps, force unit {force_unit}");
                    assert_ends(&got, &want, n, l / k_t, &what);
                }
            }
        }
    }

    /// Reference: hand calculation, as above with `T* = 0.8·f·N < f·N`: the elastic trial never
    /// leaves the cone, so nothing slips and `x_t = φ_T·T` at every stage end.
    #[test]
    fn single_pair_below_the_friction_limit_never_slips() {
        let (k_n, k_t, f, n) = (3.0e6, 1.0e6, 0.5, 2.0e3);
        let l = f * n;
        let zone = single_pair(k_n, k_t, f, 0.0, n, l);
        let stages = [
            vec![1.0, 0.0],
            vec![1.0, 0.8],
            vec![1.0, 0.0],
            vec![1.0, -0.8],
            vec![1.0, 0.0],
        ];
        let states = small_steps(&zone, &stages, 4).unwrap();
        for stage in &states {
            for s in stage {
                assert_eq!(s.z_t[0], 0.0, "a stick never changes the slip");
            }
        }
        let want = [
            [n, 0.0, 0.0, 0.0],
            [n, 0.8 * l, 0.0, 0.0],
            [n, 0.0, 0.0, 0.0],
            [n, -0.8 * l, 0.0, 0.0],
            [n, 0.0, 0.0, 0.0],
        ];
        assert_ends(&ends(&states), &want, n, l / k_t, "T* < fN");
    }

    /// Reference: hand calculation for a pair with a gap `η`, `k_n·η = N` (it closes at
    /// `φ_N = 1`), `T = f·N`, stages `(φ_N, φ_T)`:
    ///
    /// 1. `(0.5, 0)`: open, `z_n = η − 0.5·N/k_n = η/2`, no force.
    /// 2. `(0.5, 1)`: open, free tangential motion: `x_t = T + k_t·z_t = 0`, `z_t = −T/k_t`.
    /// 3. `(2, 1)`: closes at `φ_N = 1`, then `x_n = 2N − k_n·η = N`; the trial
    ///    `x_t = T + k_t·z_t = 0`: sticks with the tangential displacement it closed with.
    /// 4. `(2, 1.5)`: trial `0.5·T = L/2 < L = f·N`: sticks, `z_t = −T/k_t`.
    /// 5. `(2, 3)`: trial `2T = 2L`: slips, `x_t = L`, `z_t = (L − 3T)/k_t = −2T/k_t`.
    /// 6. `(0, 3)`: opens again (at `φ_N = 1`), `z_n = η`, free: `x_t = 0`, `z_t = −3T/k_t`.
    #[test]
    fn gap_opening_free_motion_and_closing() {
        let (k_n, k_t, f, n) = (4.0e5, 1.0e5, 0.3, 8.0e2);
        let eta = n / k_n;
        let t = f * n;
        let zone = single_pair(k_n, k_t, f, eta, n, t);
        let stages = [
            vec![0.5, 0.0],
            vec![0.5, 1.0],
            vec![2.0, 1.0],
            vec![2.0, 1.5],
            vec![2.0, 3.0],
            vec![0.0, 3.0],
        ];
        let want = [
            [0.0, 0.0, eta / 2.0, 0.0],
            [0.0, 0.0, eta / 2.0, -t / k_t],
            [n, 0.0, 0.0, -t / k_t],
            [n, t / 2.0, 0.0, -t / k_t],
            [n, t, 0.0, -2.0 * t / k_t],
            [0.0, 0.0, eta, -3.0 * t / k_t],
        ];
        for steps in [1, 2, 7] {
            let got = ends(&small_steps(&zone, &stages, steps).unwrap());
            assert_ends(&got, &want, n, eta, &format!("{steps} steps"));
        }
    }

    /// The stiffness of a small spring structure at the `m` pairs' dofs `(t_i, n_i)`: every pair
    /// node has a normal and a tangential spring to the ground; consecutive nodes are joined by a
    /// horizontal spring and, if `inclined`, by one at 45° (stiffness 3), and node 0 has one more
    /// to the ground at −45° (stiffness 2; these couple normal and tangential). Symmetric
    /// positive definite by construction (a sum of `k·eeᵀ` with the ground springs on every dof),
    /// as a bonded structure's contact stiffness is (formulation.md §2). The entries are small
    /// dyadic rationals, so the exact reference stays cheap.
    fn spring_chain(m: usize, inclined: bool) -> [Vec<Vec<f64>>; 4] {
        let mut k = vec![vec![0.0; 2 * m]; 2 * m]; // dofs [t_0..t_m, n_0..n_m]
        let mut spring = |stiff: f64, e: &[(usize, f64)]| {
            for &(a, ea) in e {
                for &(b, eb) in e {
                    k[a][b] += stiff * ea * eb;
                }
            }
        };
        for i in 0..m {
            spring(4.0, &[(m + i, 1.0)]);
            spring(2.0, &[(i, 1.0)]);
        }
        for i in 0..m - 1 {
            spring(1.0, &[(i, -1.0), (i + 1, 1.0)]);
            if inclined {
                // e = (1, 1)/√2 in (t, n): k·eeᵀ = (k/2)·(1, 1)(1, 1)ᵀ.
                let e = [(i, -1.0), (m + i, -1.0), (i + 1, 1.0), (m + i + 1, 1.0)];
                spring(1.5, &e);
            }
        }
        if inclined {
            spring(1.0, &[(0, 1.0), (m, -1.0)]);
        }
        let block = |r0: usize, c0: usize| -> Vec<Vec<f64>> {
            (0..m)
                .map(|i| (0..m).map(|j| k[r0 + i][c0 + j]).collect())
                .collect()
        };
        [block(m, m), block(m, 0), block(0, m), block(0, 0)]
    }

    fn chain_zone(m: usize, inclined: bool, friction: &[f64], seed: u64) -> HistoryZone {
        let [rnn, rnt, rtn, rtt] = spring_chain(m, inclined);
        let mut rng = Lcg::new(seed);
        let cases = (0..2)
            .map(|_| {
                // Quarters: normal loads in [−1, 3] (mostly compression), tangential in [−2, 2].
                let n = (0..m).map(|_| rng.int(-4, 12) as f64 / 4.0).collect();
                let t = (0..m).map(|_| rng.int(-8, 8) as f64 / 4.0).collect();
                (n, t)
            })
            .collect();
        HistoryZone {
            rnn,
            rnt,
            rtn,
            rtt,
            friction: friction.to_vec(),
            gap: vec![0.0; m],
            cases,
        }
    }

    /// The paper's total-slip LCP of formulation.md §3 at a load `(R_n, R_t)`, no gaps, no
    /// tightening, in exact rationals (the `f64` data taken exactly, so that the rows
    /// `x_t+ + x_t− = 2f·x_n` hold exactly and a degenerate open pair stays a solution):
    /// `x = q + M z` with `q = [R_n; F·R_n + R_t; F·R_n − R_t]`. Without coupling it is the
    /// hand-built fixture [`frictional_lcp`] (at `p = 1`); with coupling it is written out here
    /// from §3.
    fn total_lcp(z: &HistoryZone, r_n: &[f64], r_t: &[f64]) -> (Vec<Vec<Rat>>, Vec<Rat>) {
        let m = r_n.len();
        let (rnn, rnt, rtn, rtt) = (
            rat_matrix(&z.rnn),
            rat_matrix(&z.rnt),
            rat_matrix(&z.rtn),
            rat_matrix(&z.rtt),
        );
        let (fr, rn, rt) = (rat_vec(&z.friction), rat_vec(r_n), rat_vec(r_t));
        let coupled = z.rnt.iter().chain(&z.rtn).flatten().any(|&v| v != 0.0);
        if !coupled {
            let lcp = frictional_lcp(&rnn, &rtt, &fr, &rn, &rt);
            return (lcp.m, lcp.d);
        }
        let half = frac(1, 2);
        let mut a = vec![vec![Rat::zero(); 3 * m]; 3 * m];
        let mut q = vec![Rat::zero(); 3 * m];
        for i in 0..m {
            let f = &fr[i];
            q[i] = rn[i].clone();
            q[m + i] = f * &rn[i] + &rt[i];
            q[2 * m + i] = f * &rn[i] - &rt[i];
            for j in 0..m {
                let t_plus = (f * &rnt[i][j] + &rtt[i][j]) * &half;
                let t_minus = (f * &rnt[i][j] - &rtt[i][j]) * &half;
                a[i][j] = rnn[i][j].clone();
                a[i][m + j] = &rnt[i][j] * &half;
                a[i][2 * m + j] = -&rnt[i][j] * &half;
                a[m + i][j] = f * &rnn[i][j] + &rtn[i][j];
                a[m + i][m + j] = t_plus.clone();
                a[m + i][2 * m + j] = -t_plus;
                a[2 * m + i][j] = f * &rnn[i][j] - &rtn[i][j];
                a[2 * m + i][m + j] = t_minus.clone();
                a[2 * m + i][2 * m + j] = -t_minus;
            }
        }
        (a, q)
    }

    /// `[x_n, x_t, z_n, z_t]` (each of length m) of a solution `(z, x)` of the total LCP.
    fn total_state(m: usize, z: &[f64], x: &[f64]) -> OracleState {
        OracleState {
            x_n: x[..m].to_vec(),
            x_t: (0..m).map(|i| (x[m + i] - x[2 * m + i]) / 2.0).collect(),
            z_n: z[..m].to_vec(),
            z_t: (0..m).map(|i| (z[m + i] - z[2 * m + i]) / 2.0).collect(),
        }
    }

    fn state_diff(a: &OracleState, b: &OracleState, force: f64, disp: f64) -> f64 {
        let f = max_diff(&a.x_n, &b.x_n).max(max_diff(&a.x_t, &b.x_t));
        let d = max_diff(&a.z_n, &b.z_n).max(max_diff(&a.z_t, &b.z_t));
        (f / force).max(d / disp)
    }

    fn scaled(s: &OracleState, by: f64) -> OracleState {
        let sc = |v: &[f64]| v.iter().map(|x| by * x).collect();
        OracleState {
            x_n: sc(&s.x_n),
            x_t: sc(&s.x_t),
            z_n: sc(&s.z_n),
            z_t: sc(&s.z_t),
        }
    }

    /// Reference: the paper's total-slip LCP solved by exhaustive exact enumeration
    /// ([`crate::enumerate`]). One stage applying the cases proportionally from zero (no gaps)
    /// is a positively homogeneous problem: if `X` solves the total LCP at the stage's end, `s·X`
    /// solves it at `s` and every slip only grows, so the incremental law and the total one
    /// agree — the oracle must return `(k/N)·X` after each of its `N` steps. The reference is
    /// required to be unambiguous (all enumerated solutions have the same forces and
    /// displacements) and, over the zones, to contain open, sticking and slipping pairs.
    #[test]
    fn proportional_single_stage_equals_the_total_slip_lcp() {
        let zones = [
            chain_zone(2, false, &[0.25, 0.5], 11),
            chain_zone(2, true, &[0.375, 0.25], 5),
            chain_zone(3, false, &[0.25, 0.25, 0.625], 3),
            chain_zone(3, true, &[0.5, 0.25, 0.375], 7),
            chain_zone(3, true, &[0.125, 0.625, 0.25], 21),
        ];
        let (mut open, mut slipping, mut sticking) = (0, 0, 0);
        for (zi, zone) in zones.iter().enumerate() {
            let m = zone.friction.len();
            let phi = [1.0, 0.75];
            let r_n: Vec<f64> = (0..m)
                .map(|i| phi[0] * zone.cases[0].0[i] + phi[1] * zone.cases[1].0[i])
                .collect();
            let r_t: Vec<f64> = (0..m)
                .map(|i| phi[0] * zone.cases[0].1[i] + phi[1] * zone.cases[1].1[i])
                .collect();
            let (a, q) = total_lcp(zone, &r_n, &r_t);
            let sols = enumerate_exact(&a, &q);
            assert!(!sols.is_empty(), "zone {zi}: the total LCP has a solution");
            let reference = total_state(m, &sols[0].z_f64(), &sols[0].w_f64());
            let force = max_abs(&r_n).max(max_abs(&r_t));
            let disp = force / 4.0;
            for s in &sols[1..] {
                let other = total_state(m, &s.z_f64(), &s.w_f64());
                assert!(
                    state_diff(&other, &reference, force, disp) < 1e-12,
                    "zone {zi}: the reference is ambiguous"
                );
            }
            for i in 0..m {
                let (xn, xt) = (reference.x_n[i], reference.x_t[i]);
                if xn <= 1e-12 * force {
                    open += 1;
                } else if (xt.abs() - zone.friction[i] * xn).abs() <= 1e-12 * force
                    && reference.z_t[i] != 0.0
                {
                    slipping += 1;
                } else {
                    sticking += 1;
                }
            }
            let steps = 5;
            let states = small_steps(zone, &[phi.to_vec()], steps).unwrap();
            for (k, got) in states[0].iter().enumerate() {
                let want = scaled(&reference, (k + 1) as f64 / steps as f64);
                let e = state_diff(got, &want, force, disp);
                assert!(e < 1e-9, "zone {zi}, step {}: off by {e:e}", k + 1);
            }
        }
        assert!(
            open > 0 && slipping > 0 && sticking > 0,
            "{open} {slipping} {sticking}"
        );
    }

    /// Reference: the paper's Example 1 (fixtures::example1, formulation.md §5): at `p = 1`
    /// without tightening support 1 lifts by 0.5 and supports 2 and 3 carry 0.5 each.
    #[test]
    fn example1_in_one_proportional_stage() {
        let m = example1::PAIRS;
        let zone = HistoryZone {
            rnn: example1::rows(&example1::RNN),
            rnt: vec![vec![0.0; m]; m],
            rtn: vec![vec![0.0; m]; m],
            rtt: example1::rows(&example1::RTT),
            friction: vec![example1::FRICTION; m],
            gap: vec![0.0; m],
            cases: vec![(example1::RV_N.to_vec(), example1::RV_T.to_vec())],
        };
        let states = small_steps(&zone, &[vec![example1::TARGET]], 4).unwrap();
        let want = total_state(m, &example1::Z_AT_TARGET, &example1::X_AT_TARGET);
        let got = states[0].last().unwrap();
        assert!(state_diff(got, &want, 1.0, 1.0) < 1e-12, "{got:?}");
    }

    /// Reference: the oracle's own limit, and the nesting of its grids. One backward-Euler step
    /// is exact unless the working scheme changes inside it in a way the end of the step does
    /// not see (here: pair 2, lifted by the push, closes again during the reversal after moving
    /// freely; the free motion between the last grid point and the closing is lost). The error is
    /// then bounded by the step times the rate, and refining a grid by halving keeps every old
    /// grid point, so the error at the stage ends must not grow when the step is halved and must
    /// shrink to nothing: checked against a much finer run (`3·2¹¹` steps per stage), on grids
    /// `3·2^k` nested in it. The coarsest grid must be really wrong (the test can fail).
    #[test]
    fn halving_the_step_converges_through_a_reversal() {
        let [rnn, rnt, rtn, rtt] = spring_chain(2, true);
        let zone = HistoryZone {
            rnn,
            rnt,
            rtn,
            rtt,
            friction: vec![0.3, 0.5],
            gap: vec![0.0, 0.0],
            cases: vec![
                (vec![2.0, 1.5], vec![0.0, 0.0]),  // dead load: presses both pairs
                (vec![1.2, -2.0], vec![1.0, 0.7]), // push: lifts pair 2, shears both
            ],
        };
        let stages = [
            vec![1.0, 0.0],  // dead load on
            vec![1.0, 1.0],  // push
            vec![1.0, -1.0], // reverse
            vec![1.0, 0.5],  // push again
            vec![0.5, 0.0],  // unload
        ];
        let (force, disp) = (2.0, 0.5); // the largest load, and over the smallest spring (4)
        let fine = small_steps(&zone, &stages, 3 << 11).unwrap();
        let errors: Vec<f64> = (0..8)
            .map(|k| {
                let got = small_steps(&zone, &stages, 3 << k).unwrap();
                got.iter()
                    .zip(&fine)
                    .map(|(a, b)| state_diff(a.last().unwrap(), b.last().unwrap(), force, disp))
                    .fold(0.0, f64::max)
            })
            .collect();
        assert!(
            errors[0] > 1e-2,
            "the coarse grid should be visibly off: {errors:?}"
        );
        for w in errors.windows(2) {
            assert!(
                w[1] <= w[0] + 1e-12,
                "halving the step made it worse: {errors:?}"
            );
        }
        assert!(errors[7] < errors[0] / 100.0, "no convergence: {errors:?}");
    }

    /// Reference: the data and the LCP itself. Bad data is an error naming the problem, and an
    /// increment without solution names the stage and the step: a pair pulled open (`x_n = 0`,
    /// so `x_t` must vanish) under a tangential load with no tangential stiffness to balance it.
    #[test]
    fn bad_data_and_unsolvable_increments_are_errors() {
        let zone = single_pair(1.0, 1.0, 0.5, 0.0, 1.0, 1.0);
        let err = |z: &HistoryZone, st: &[Vec<f64>], n: usize| small_steps(z, st, n).unwrap_err();
        assert!(err(&zone, &[vec![1.0]], 2).contains("stage 1 has 1 factors for 2 cases"));
        assert!(err(&zone, &[vec![1.0, f64::NAN]], 2).contains("non-finite factor"));
        assert!(err(&zone, &[vec![1.0, 0.0]], 0).contains("at least 1"));
        let mut bad = zone.clone();
        bad.friction[0] = -0.1;
        assert!(err(&bad, &[vec![1.0, 0.0]], 1).contains("friction has a negative entry"));
        let mut bad = zone.clone();
        bad.rtt = vec![vec![1.0, 0.0]];
        assert!(err(&bad, &[vec![1.0, 0.0]], 1).contains("rtt must be 1 × 1"));
        let big = HistoryZone {
            rnn: vec![vec![0.0; 5]; 5],
            rnt: vec![vec![0.0; 5]; 5],
            rtn: vec![vec![0.0; 5]; 5],
            rtt: vec![vec![0.0; 5]; 5],
            friction: vec![0.0; 5],
            gap: vec![0.0; 5],
            cases: vec![],
        };
        assert!(err(&big, &[], 1).contains("1 to 4 pairs"));
        let loose = single_pair(1.0, 0.0, 0.5, 0.0, -1.0, 1.0);
        let e = err(&loose, &[vec![0.0, 0.0], vec![1.0, 1.0]], 3);
        assert!(
            e.starts_with("stage 2, step 1: ") && e.contains("no solution"),
            "{e}"
        );
    }

    /// Reference: hand calculation of a rate problem with three answers (large friction with
    /// normal–tangential coupling, the 2D case where uniqueness fails). One pair, `Rnn = Rtt = 1`,
    /// `Rnt = Rtn = c = 1/2`, `f = 3`, load `(N, T) = (1, 5/2)` from zero:
    ///
    /// * stick: `x = (1, 5/2)`, `|x_t| = 5/2 ≤ f·x_n = 3`;
    /// * slip with `x_t = f·x_n`: `z_t = −d`, `x_n = 1 − d/2`, `x_t = 5/2 − d`, so
    ///   `5/2 − d = 3 − 3d/2`, `d = 1`: `x = (1/2, 3/2)`;
    /// * open: `x = 0`, `1 + z_n + z_t/2 = 0`, `5/2 + z_n/2 + z_t = 0`: `z_n = 1/3 ≥ 0`.
    ///
    /// The oracle must not pick one: it is an error naming the stage and the step.
    #[test]
    fn several_answers_with_different_forces_are_an_error() {
        let zone = HistoryZone {
            rnn: vec![vec![1.0]],
            rnt: vec![vec![0.5]],
            rtn: vec![vec![0.5]],
            rtt: vec![vec![1.0]],
            friction: vec![3.0],
            gap: vec![0.0],
            cases: vec![(vec![1.0], vec![2.5])],
        };
        let e = small_steps(&zone, &[vec![1.0]], 4).unwrap_err();
        assert!(
            e.starts_with("stage 1, step 1: ") && e.contains("not unique"),
            "{e}"
        );
    }
}
