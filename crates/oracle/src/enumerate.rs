//! Exhaustive enumeration of the complementary index sets of a small LCP.

use crate::linalg::{feasible_vertex, solve_int};
use crate::{check_square, mz_plus_q, parametric_q, rat, rat_matrix, rat_vec, to_f64_vec, Rat};
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// The largest `n` that [`enumerate`] accepts (`2ⁿ` index sets).
pub const MAX_ENUMERATION_SIZE: usize = 12;

/// One solution of the LCP `w = M z + q ≥ 0, z ≥ 0, wᵀz = 0`, found by [`enumerate`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Solution {
    /// `z`, exact.
    pub z: Vec<Rat>,
    /// `w = M z + q`, exact.
    pub w: Vec<Rat>,
    /// The first complementary index set `S` (in enumeration order: subsets as bit masks,
    /// ascending) that produced this solution: `z_i = 0` off `S`, `w_i = 0` on `S`.
    pub set: Vec<usize>,
    /// Every index set that produced this solution (more than one for degenerate solutions,
    /// where some `z_i = w_i = 0`), `set` first.
    pub all_sets: Vec<Vec<usize>>,
    /// The index sets `S` of `all_sets` whose `M_SS` is **singular** (this solution was found as
    /// a vertex of the polyhedron of solutions with that pattern, which may hold a continuum of
    /// other solutions). If this is empty for every returned solution, the returned list is
    /// exactly the (finite) solution set.
    pub singular_sets: Vec<Vec<usize>>,
}

impl Solution {
    /// `z` rounded to `f64`.
    pub fn z_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.z)
    }

    /// `w` rounded to `f64`.
    pub fn w_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.w)
    }
}

/// All solutions of the LCP `w = M z + q ≥ 0, z ≥ 0, wᵀz = 0` (n ≤ 12), by enumerating the
/// `2ⁿ` complementary index sets; `m` is row-major `n × n`, the `f64` inputs are converted
/// exactly.
///
/// For every subset `S` of `0..n` (`z` may be non-zero only on `S`, `w` is zero on `S`):
///
/// * if `M_SS` is non-singular, `z_S = −M_SS⁻¹ q_S` (exact fraction-free Gaussian elimination
///   on the row-scaled integer data); it is kept if `z ≥ 0` and `w = M z + q ≥ 0`;
/// * if `M_SS` is singular, the set of solutions with this pattern,
///   `{ z_S ≥ 0, z_{S^c} = 0, (M z + q)_S = 0, (M z + q)_{S^c} ≥ 0 }`, is a polyhedron that may
///   be empty, one point or a continuum. An exact phase-1 simplex decides whether it is empty
///   and, if not, returns one of its vertices. So no solution *pattern* is missed, but when a
///   pattern holds a continuum only one representative is returned (recorded in
///   [`Solution::singular_sets`]); the list is then not "all" solutions. If no returned
///   solution has a singular set, every pattern holds at most one point and the list is
///   exactly the solution set (in particular whenever every principal minor is non-zero).
///
/// Solutions are returned once each (duplicates from degenerate patterns are merged), in the
/// order in which they were first found.
///
/// # Panics
/// If `n > 12`, the sizes disagree, or an input is not finite.
pub fn enumerate(m: &[Vec<f64>], q: &[f64]) -> Vec<Solution> {
    enumerate_exact(&rat_matrix(m), &rat_vec(q))
}

/// [`enumerate`] on rational data.
///
/// # Panics
/// If `n > 12` or the sizes disagree.
pub fn enumerate_exact(m: &[Vec<Rat>], q: &[Rat]) -> Vec<Solution> {
    let n = q.len();
    check_square(m, n);
    assert!(
        n <= MAX_ENUMERATION_SIZE,
        "enumeration is limited to n ≤ {MAX_ENUMERATION_SIZE} (n = {n})"
    );
    // Scale each row of [M | q] by the lcm of its denominators: an integer problem with the
    // same z-solutions (w_i is scaled by a positive factor), so that the 2ⁿ solves run in
    // fraction-free integer arithmetic.
    let (mi, qi): (Vec<Vec<BigInt>>, Vec<BigInt>) = m
        .iter()
        .zip(q)
        .map(|(row, qv)| {
            let l = row
                .iter()
                .chain(std::iter::once(qv))
                .fold(BigInt::one(), |acc, v| lcm(acc, v.denom()));
            let scale = |v: &Rat| v.numer() * (&l / v.denom());
            (row.iter().map(scale).collect(), scale(qv))
        })
        .unzip();
    let mut out: Vec<Solution> = Vec::new();
    for mask in 0u32..(1u32 << n) {
        let set: Vec<usize> = (0..n).filter(|&i| mask & (1 << i) != 0).collect();
        let (z, singular) = match candidate(&mi, &qi, m, q, &set) {
            Some(found) => found,
            None => continue,
        };
        let w = mz_plus_q(m, &z, q);
        if z.iter().any(Signed::is_negative) || w.iter().any(Signed::is_negative) {
            continue;
        }
        debug_assert!(set.iter().all(|&i| w[i].is_zero()));
        let singular_sets = if singular { vec![set.clone()] } else { vec![] };
        if let Some(s) = out.iter_mut().find(|s| s.z == z) {
            s.all_sets.push(set);
            s.singular_sets.extend(singular_sets);
        } else {
            out.push(Solution {
                z,
                w,
                set: set.clone(),
                all_sets: vec![set],
                singular_sets,
            });
        }
    }
    out
}

/// The least common multiple of two positive integers.
fn lcm(a: BigInt, b: &BigInt) -> BigInt {
    let (mut x, mut y) = (a.clone(), b.clone());
    while !y.is_zero() {
        let r = &x % &y;
        x = std::mem::replace(&mut y, r);
    }
    a / x * b
}

/// The candidate `z` of index set `set` (with a flag: was `M_SS` singular), or `None` if it
/// is certainly not a solution. `mi`, `qi` are the row-scaled integer data.
fn candidate(
    mi: &[Vec<BigInt>],
    qi: &[BigInt],
    m: &[Vec<Rat>],
    q: &[Rat],
    set: &[usize],
) -> Option<(Vec<Rat>, bool)> {
    let n = q.len();
    let a: Vec<Vec<BigInt>> = set
        .iter()
        .map(|&i| set.iter().map(|&j| mi[i][j].clone()).collect())
        .collect();
    let b: Vec<BigInt> = set.iter().map(|&i| -&qi[i]).collect();
    if let Some((x, den)) = solve_int(a, &b) {
        // z_S = x / den with den > 0: reject cheaply on signs, in integers.
        if x.iter().any(Signed::is_negative) {
            return None;
        }
        let mut zx = vec![BigInt::zero(); n];
        for (&i, v) in set.iter().zip(&x) {
            zx[i] = v.clone();
        }
        for i in (0..n).filter(|i| !set.contains(i)) {
            // den · (scaled w_i) = Σ_j mi_ij x_j + den · qi_i must be ≥ 0.
            let s = set
                .iter()
                .fold(&den * &qi[i], |acc, &j| acc + &mi[i][j] * &zx[j]);
            if s.is_negative() {
                return None;
            }
        }
        let z = zx.into_iter().map(|v| Rat::new(v, den.clone())).collect();
        return Some((z, false));
    }
    // Singular M_SS: M z − w = −q with variables z_S ≥ 0 and w_{S^c} ≥ 0.
    let off: Vec<usize> = (0..n).filter(|i| !set.contains(i)).collect();
    let rows: Vec<Vec<Rat>> = (0..n)
        .map(|i| {
            let mut row: Vec<Rat> = set.iter().map(|&j| m[i][j].clone()).collect();
            row.extend(
                off.iter()
                    .map(|&j| if i == j { -Rat::one() } else { Rat::zero() }),
            );
            row
        })
        .collect();
    let rhs: Vec<Rat> = q.iter().map(|v| -v).collect();
    let y = feasible_vertex(&rows, &rhs)?;
    let mut z = vec![Rat::zero(); n];
    for (&i, v) in set.iter().zip(y) {
        z[i] = v;
    }
    Some((z, true))
}

/// Whether the LCP `w = M z + q` has a solution (exhaustive; see [`enumerate`]).
pub fn has_solution(m: &[Vec<f64>], q: &[f64]) -> bool {
    has_solution_exact(&rat_matrix(m), &rat_vec(q))
}

/// [`has_solution`] on rational data.
pub fn has_solution_exact(m: &[Vec<Rat>], q: &[Rat]) -> bool {
    !enumerate_exact(m, q).is_empty()
}

/// [`enumerate`] for the parametric LCP at load `p`: `x = q0 + p·d + M z` (the returned
/// [`Solution::w`] is `x`).
pub fn enumerate_parametric(m: &[Vec<f64>], q0: &[f64], d: &[f64], p: f64) -> Vec<Solution> {
    enumerate_parametric_exact(&rat_matrix(m), &rat_vec(q0), &rat_vec(d), &rat(p))
}

/// [`enumerate_parametric`] on rational data (`p` exact, e.g. a breakpoint of a [`crate::Path`]).
pub fn enumerate_parametric_exact(m: &[Vec<Rat>], q0: &[Rat], d: &[Rat], p: &Rat) -> Vec<Solution> {
    enumerate_exact(m, &parametric_q(q0, d, p))
}
