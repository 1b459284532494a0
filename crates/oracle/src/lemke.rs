//! Lemke's method with a covering vector, exact, with the lexicographic ratio test.

use crate::tableau::Tableau;
use crate::{rat_matrix, rat_vec, to_f64, to_f64_vec, Rat, Var};
use num_traits::{Signed, Zero};

/// The pivot cap used by [`lemke()`]. Lexicographic Lemke always terminates; the cap is a
/// safety net only.
pub const DEFAULT_MAX_PIVOTS: usize = 100_000;

/// How Lemke's method ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LemkeStatus {
    /// `z0` left the basis (or `q ≥ 0` from the start): `(z, w)` solves the LCP.
    Solved,
    /// Secondary ray: the entering column had no positive entry. For a copositive-plus `M` (in
    /// particular a positive semidefinite one) this proves that the LCP has no solution; for a
    /// general `M` it proves nothing.
    Ray,
    /// The pivot cap was reached.
    IterationCap,
}

/// The secondary ray on which Lemke's method ended ([`LemkeStatus::Ray`]).
///
/// Moving along it by `t ≥ 0` from the final point, the point `(z + t·dz, w + t·dw,
/// z0 + t·dz0)` stays feasible and almost complementary.
#[derive(Clone, Debug, PartialEq)]
pub struct LemkeRay {
    /// The variable that could not enter (its column had no positive entry).
    pub entering: Var,
    /// Change of `z` per unit of the entering variable.
    pub dz: Vec<Rat>,
    /// Change of `w` per unit of the entering variable.
    pub dw: Vec<Rat>,
    /// Change of `z0` per unit of the entering variable.
    pub dz0: Rat,
}

/// The outcome of [`lemke()`].
#[derive(Clone, Debug, PartialEq)]
pub struct LemkeResult {
    /// How the method ended.
    pub status: LemkeStatus,
    /// `z` at the final basis (the solution if [`LemkeStatus::Solved`]).
    pub z: Vec<Rat>,
    /// `w = M z + q + z0·cover` at the final basis (`= M z + q` if solved).
    pub w: Vec<Rat>,
    /// The artificial variable at the final basis (zero if solved).
    pub z0: Rat,
    /// Number of pivots performed (0 if `q ≥ 0`).
    pub pivots: usize,
    /// The ray, if the status is [`LemkeStatus::Ray`].
    pub ray: Option<LemkeRay>,
}

impl LemkeResult {
    /// Whether the LCP was solved.
    pub fn is_solved(&self) -> bool {
        self.status == LemkeStatus::Solved
    }

    /// `z` rounded to `f64`.
    pub fn z_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.z)
    }

    /// `w` rounded to `f64`.
    pub fn w_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.w)
    }

    /// `z0` rounded to `f64`.
    pub fn z0_f64(&self) -> f64 {
        to_f64(&self.z0)
    }
}

/// Lemke's method for `w = M z + q ≥ 0, z ≥ 0, wᵀz = 0`, with covering vector `cover`
/// (all entries `> 0`), on a full tableau `[E | −M | −cover | q]` in exact arithmetic.
///
/// `m` is row-major `n × n`; the `f64` inputs are converted exactly. If `q ≥ 0` the answer is
/// `z = 0` with no pivot. Otherwise `z0` enters first (the lexicographically chosen most
/// violated row leaves), then the complement of the variable that just left enters, until `z0`
/// leaves (solved), the entering column has no positive entry (ray), or
/// [`DEFAULT_MAX_PIVOTS`] pivots were made.
///
/// Ratio test: the minimum ratio `rhs_i / col_i` over positive entries; if the row of `z0` is
/// among the rows attaining it, `z0` leaves (ends the method at once, which is always valid);
/// otherwise ties are broken lexicographically on the rows of `[rhs | B⁻¹]` divided by the pivot
/// entries — the classic rule, under which no basis repeats, so the method terminates.
///
/// # Panics
/// If the sizes disagree, an entry of `cover` is not positive, or an input is not finite.
pub fn lemke(m: &[Vec<f64>], q: &[f64], cover: &[f64]) -> LemkeResult {
    lemke_exact(
        &rat_matrix(m),
        &rat_vec(q),
        &rat_vec(cover),
        DEFAULT_MAX_PIVOTS,
    )
}

/// [`lemke()`] on rational data, with an explicit pivot cap.
///
/// # Panics
/// As [`lemke()`].
pub fn lemke_exact(m: &[Vec<Rat>], q: &[Rat], cover: &[Rat], max_pivots: usize) -> LemkeResult {
    let n = q.len();
    assert_eq!(cover.len(), n, "cover must have length {n}");
    assert!(
        cover.iter().all(|c| c.is_positive()),
        "every entry of the covering vector must be > 0"
    );
    let mut tab = Tableau::new(m, cover, q, Var::Z0, None);
    let z0col = tab.extra_col();
    let rc = tab.rhs_col();
    let finish = |tab: &Tableau, status, pivots, ray| {
        let (w, z, z0) = tab.values();
        LemkeResult {
            status,
            z,
            w,
            z0,
            pivots,
            ray,
        }
    };
    if q.iter().all(|v| !v.is_negative()) {
        return finish(&tab, LemkeStatus::Solved, 0, None);
    }
    if max_pivots == 0 {
        return finish(&tab, LemkeStatus::IterationCap, 0, None);
    }
    // First pivot: z0 enters at the level that makes every w non-negative; the leaving row is
    // the lexicographic minimum of [q_i | e_i] / cover_i (which keeps every row lexico-positive).
    let r = tab
        .lex_min(0..n, |i| cover[i].clone())
        .expect("n > 0 since some q_i < 0");
    let mut leaving = tab.pivot(r, z0col);
    let mut pivots = 1;
    loop {
        let entering = tab.var(leaving).complement().expect("x or z left");
        let c = tab.col(entering);
        if pivots >= max_pivots {
            return finish(&tab, LemkeStatus::IterationCap, pivots, None);
        }
        let rows = tab.positive_rows(c);
        if rows.is_empty() {
            let (dw, dz, dz0) = tab.direction(c);
            let ray = LemkeRay {
                entering,
                dz,
                dw,
                dz0,
            };
            return finish(&tab, LemkeStatus::Ray, pivots, Some(ray));
        }
        // Prefer z0 if it attains the minimum ratio.
        let z0row = tab.row_of(z0col).expect("z0 is basic during the loop");
        let min_ratio = rows
            .iter()
            .map(|&i| &tab.t[i][rc] / &tab.t[i][c])
            .min()
            .expect("non-empty");
        let r = if rows.contains(&z0row) && &tab.t[z0row][rc] / &tab.t[z0row][c] == min_ratio {
            z0row
        } else {
            tab.lex_min(rows, |i| tab.t[i][c].clone())
                .expect("non-empty")
        };
        leaving = tab.pivot(r, c);
        pivots += 1;
        if leaving == z0col {
            let mut res = finish(&tab, LemkeStatus::Solved, pivots, None);
            debug_assert!(res.z0.is_zero());
            res.z0 = Rat::zero();
            return res;
        }
    }
}
