//! The parametric Lemke method of formulation.md §4, exact.

use crate::tableau::Tableau;
use crate::{rat, rat_matrix, rat_vec, to_f64, to_f64_vec, Rat, Var};
use num_traits::{One, Signed, Zero};

/// The step cap used by [`parametric_path`].
pub const DEFAULT_MAX_STEPS: usize = 100_000;

/// How the parametric path ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathStatus {
    /// Criterion 1: the next step would have taken `p` beyond the target (or a step reached it
    /// exactly). The last point of [`Path::points`] is the solution at `p = target`.
    TargetReached,
    /// Criterion 2a: the entering column has no positive entry and its entry in `p`'s row is
    /// negative: `p` grows without bound along [`Path::ray`] (`dp = 1`), the scheme no longer
    /// changes. Also used when no entry of `p`'s own column is positive at the very first step.
    Ray,
    /// Criterion 2b: the entering column has no positive entry and its entry in `p`'s row is
    /// zero: a mechanism at `p_lim` = the last point's `p`; [`Path::ray`] is the direction in
    /// which the variables grow without bound at fixed `p` (`dp = 0`).
    Mechanism,
    /// `p` left the basis: the path came back to `p = 0`.
    ReturnedToZero,
    /// The step cap was reached.
    IterationCap,
    /// `q0` has a negative entry: the start `z = 0, x = q0` is not feasible. No step was made.
    InfeasibleStart,
}

/// One pivot step of the path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Step {
    /// The variable that entered the basis.
    pub entering: Var,
    /// The variable that left the basis.
    pub leaving: Var,
    /// The value of `p` after the step.
    pub p: Rat,
    /// Whether `p` decreased during this step (a turning point of the load path).
    pub p_decreased: bool,
}

impl Step {
    /// `p` rounded to `f64`.
    pub fn p_f64(&self) -> f64 {
        to_f64(&self.p)
    }
}

/// A point of the path: a solution of the parametric LCP at load `p`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PathPoint {
    /// The load parameter.
    pub p: Rat,
    /// `x = q0 + p·d + M z`.
    pub x: Vec<Rat>,
    /// `z`.
    pub z: Vec<Rat>,
}

impl PathPoint {
    /// `p` rounded to `f64`.
    pub fn p_f64(&self) -> f64 {
        to_f64(&self.p)
    }

    /// `x` rounded to `f64`.
    pub fn x_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.x)
    }

    /// `z` rounded to `f64`.
    pub fn z_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.z)
    }
}

/// The unbounded direction on which the path ended ([`PathStatus::Ray`] or
/// [`PathStatus::Mechanism`]): from the last point, `(x + t·dx, z + t·dz)` at load `p + t·dp`
/// solves the parametric LCP for every `t ≥ 0`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PathRay {
    /// The variable whose column had no positive entry.
    pub entering: Var,
    /// The entry of the entering column in `p`'s row (of the tableau `B⁻¹[E | −M | −d | q0]`):
    /// negative for a ray (criterion 2a), zero for a mechanism (2b). By convention `−1` when
    /// `p` itself could not leave the start (it was the entering variable).
    pub p_entry: Rat,
    /// Change of `x`: per unit of `p` for a ray, per unit of the entering variable for a
    /// mechanism.
    pub dx: Vec<Rat>,
    /// Change of `z`, with the same normalisation as `dx`.
    pub dz: Vec<Rat>,
    /// Change of `p`: `1` for a ray, `0` for a mechanism.
    pub dp: Rat,
}

impl PathRay {
    /// `dx` rounded to `f64`.
    pub fn dx_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.dx)
    }

    /// `dz` rounded to `f64`.
    pub fn dz_f64(&self) -> Vec<f64> {
        to_f64_vec(&self.dz)
    }
}

/// The result of [`parametric_path`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Path {
    /// How the path ended.
    pub status: PathStatus,
    /// The pivot steps, in order (the first has `entering == Var::P`).
    pub steps: Vec<Step>,
    /// The breakpoints: the start (`p = 0`, `x = q0`, `z = 0`), the point after each step, and,
    /// for [`PathStatus::TargetReached`] when the target fell inside a segment, the solution at
    /// the target. Consecutive points are joined by straight segments. Empty for
    /// [`PathStatus::InfeasibleStart`].
    pub points: Vec<PathPoint>,
    /// The variable that was about to enter when the path stopped (criteria 1, 2 and the cap);
    /// `None` for [`PathStatus::ReturnedToZero`] and [`PathStatus::InfeasibleStart`].
    pub final_entering: Option<Var>,
    /// The unbounded direction for [`PathStatus::Ray`] and [`PathStatus::Mechanism`].
    pub ray: Option<PathRay>,
}

impl Path {
    /// The last `p` reached on the path (`p_lim` for a mechanism); `None` for an infeasible
    /// start.
    pub fn last_p(&self) -> Option<&Rat> {
        self.points.last().map(|pt| &pt.p)
    }

    /// The solution on the path at load `p`, exactly.
    ///
    /// The path is piecewise linear between [`Path::points`]. The first point (in path order)
    /// at load `p` is returned: a breakpoint with this exact `p`, or the interpolation on the
    /// first segment whose `p`-range contains it. Segments with constant `p` (degenerate or
    /// non-unique stretches) and turning points are handled by this "first occurrence" rule.
    /// For [`PathStatus::Ray`], any `p` beyond the last point is evaluated on the ray.
    /// `None` if `p` is not on the path (e.g. beyond the target, a mechanism's `p_lim`, or the
    /// point where the path returned to zero).
    pub fn solution_at(&self, p: &Rat) -> Option<PathPoint> {
        for (k, a) in self.points.iter().enumerate() {
            if &a.p == p {
                return Some(a.clone());
            }
            if let Some(b) = self.points.get(k + 1) {
                let inside = (a.p < *p && *p < b.p) || (b.p < *p && *p < a.p);
                if inside {
                    let s = (p - &a.p) / (&b.p - &a.p);
                    let lerp = |u: &[Rat], v: &[Rat]| -> Vec<Rat> {
                        u.iter().zip(v).map(|(x, y)| x + &s * (y - x)).collect()
                    };
                    return Some(PathPoint {
                        p: p.clone(),
                        x: lerp(&a.x, &b.x),
                        z: lerp(&a.z, &b.z),
                    });
                }
            }
        }
        if self.status == PathStatus::Ray {
            let last = self.points.last()?;
            let ray = self.ray.as_ref()?;
            if *p > last.p {
                let t = p - &last.p;
                let step = |u: &[Rat], du: &[Rat]| -> Vec<Rat> {
                    u.iter().zip(du).map(|(x, dx)| x + &t * dx).collect()
                };
                return Some(PathPoint {
                    p: p.clone(),
                    x: step(&last.x, &ray.dx),
                    z: step(&last.z, &ray.dz),
                });
            }
        }
        None
    }

    /// [`Path::solution_at`] for an `f64` load (converted exactly).
    pub fn solution_at_f64(&self, p: f64) -> Option<PathPoint> {
        self.solution_at(&rat(p))
    }

    /// The loads `p` after each step, rounded to `f64`.
    pub fn step_loads_f64(&self) -> Vec<f64> {
        self.steps.iter().map(Step::p_f64).collect()
    }
}

/// The parametric Lemke method (formulation.md §4) for `x = q0 + p·d + M z, x ≥ 0, z ≥ 0,
/// xᵀz = 0`, in exact arithmetic on the full tableau `[E | −M | −d | q0]` with basis `x`.
///
/// * Requires `q0 ≥ 0`; otherwise returns [`PathStatus::InfeasibleStart`] at once.
/// * Step 1: `p` enters; then the complement of the variable that just left enters. Every
///   ratio test runs over the positive entries of the entering column (the row of `p`
///   included), with lexicographic tie-breaking on the rows of `[rhs | B⁻¹]` divided by the
///   pivot entries. The columns of `B⁻¹` are those of the initial basis `x`, compared in the
///   order `priority` (a permutation of `0..n`; default identity).
/// * Stops on: criterion 1 (`target` given and the step would take `p` beyond it: the
///   solution at `p = target` on this segment is added to the points; if a step lands exactly
///   on the target, the path stops after it); criterion 2a/2b (no positive entry; see
///   [`PathStatus`]); `p` leaving the basis; the step cap [`DEFAULT_MAX_STEPS`].
///
/// `m` is row-major `n × n`; the `f64` inputs are converted exactly.
///
/// # Panics
/// If the sizes disagree, `priority` is not a permutation, `target` is negative, or an input is
/// not finite.
pub fn parametric_path(
    m: &[Vec<f64>],
    q0: &[f64],
    d: &[f64],
    target: Option<f64>,
    priority: Option<&[usize]>,
) -> Path {
    parametric_path_exact(
        &rat_matrix(m),
        &rat_vec(q0),
        &rat_vec(d),
        target.map(rat).as_ref(),
        priority,
        DEFAULT_MAX_STEPS,
    )
}

/// [`parametric_path`] on rational data, with an explicit step cap.
///
/// # Panics
/// As [`parametric_path`].
pub fn parametric_path_exact(
    m: &[Vec<Rat>],
    q0: &[Rat],
    d: &[Rat],
    target: Option<&Rat>,
    priority: Option<&[usize]>,
    max_steps: usize,
) -> Path {
    if let Some(t) = target {
        assert!(!t.is_negative(), "the target load must be ≥ 0");
    }
    let mut tab = Tableau::new(m, d, q0, Var::P, priority);
    let mut path = Path {
        status: PathStatus::InfeasibleStart,
        steps: Vec::new(),
        points: Vec::new(),
        final_entering: None,
        ray: None,
    };
    if q0.iter().any(Signed::is_negative) {
        return path;
    }
    let pcol = tab.extra_col();
    let rc = tab.rhs_col();
    let point = |tab: &Tableau| {
        let (x, z, p) = tab.values();
        PathPoint { p, x, z }
    };
    path.points.push(point(&tab));
    let mut entering = Var::P;
    loop {
        let c = tab.col(entering);
        path.final_entering = Some(entering);
        if path.steps.len() >= max_steps {
            path.status = PathStatus::IterationCap;
            return path;
        }
        // p's row entry of the entering column; p changes by −p_entry per unit of `entering`.
        let p_entry = match tab.row_of(pcol) {
            Some(r) => tab.t[r][c].clone(),
            None => {
                debug_assert_eq!(entering, Var::P);
                -Rat::one()
            }
        };
        let dp_dt = -&p_entry;
        let current = point(&tab);
        let Some(r) = tab.ratio_test(c) else {
            // Criterion 2: no positive entry, so p_entry ≤ 0.
            let (mut dx, mut dz, mut dp) = tab.direction(c);
            if dp_dt.is_positive() {
                let inv = dp_dt.recip();
                for v in dx.iter_mut().chain(dz.iter_mut()) {
                    *v *= &inv;
                }
                dp = Rat::one();
                path.status = PathStatus::Ray;
            } else {
                debug_assert!(dp.is_zero());
                path.status = PathStatus::Mechanism;
            }
            path.ray = Some(PathRay {
                entering,
                p_entry,
                dx,
                dz,
                dp,
            });
            return path;
        };
        let t = &tab.t[r][rc] / &tab.t[r][c];
        let p_new = &current.p + &dp_dt * &t;
        if let Some(target) = target {
            if p_new > *target {
                // Criterion 1: stop on this segment at p = target (dp_dt > 0 here, since
                // p_new > target ≥ current p).
                let s = (target - &current.p) / &dp_dt;
                let (dx, dz, _) = tab.direction(c);
                let mv = |u: &[Rat], du: &[Rat]| -> Vec<Rat> {
                    u.iter().zip(du).map(|(x, dx)| x + &s * dx).collect()
                };
                path.points.push(PathPoint {
                    p: target.clone(),
                    x: mv(&current.x, &dx),
                    z: mv(&current.z, &dz),
                });
                path.status = PathStatus::TargetReached;
                return path;
            }
        }
        let left_col = tab.pivot(r, c);
        let leaving = tab.var(left_col);
        let after = point(&tab);
        debug_assert_eq!(after.p, p_new);
        path.steps.push(Step {
            entering,
            leaving,
            p_decreased: after.p < current.p,
            p: after.p.clone(),
        });
        path.points.push(after);
        if leaving == Var::P {
            path.final_entering = None;
            path.status = PathStatus::ReturnedToZero;
            return path;
        }
        if target == Some(&p_new) {
            path.final_entering = leaving.complement();
            path.status = PathStatus::TargetReached;
            return path;
        }
        entering = leaving.complement().expect("x or z left the basis");
    }
}
