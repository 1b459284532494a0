//! Exact linear algebra: Gaussian elimination and a phase-1 simplex (feasibility only).

use crate::Rat;
use num_bigint::BigInt;
use num_traits::{One, Signed, Zero};

/// Solves the square system `A y = b` exactly by Gaussian elimination.
///
/// Returns `None` if `A` is singular (whether or not the system happens to be consistent).
///
/// # Panics
/// If `A` is not square or `b` has the wrong length.
pub fn solve(a: &[Vec<Rat>], b: &[Rat]) -> Option<Vec<Rat>> {
    let n = b.len();
    assert_eq!(a.len(), n, "A must have as many rows as b");
    // Augmented matrix [A | b].
    let mut t: Vec<Vec<Rat>> = a
        .iter()
        .zip(b)
        .map(|(row, bi)| {
            assert_eq!(row.len(), n, "A must be square");
            let mut r = row.clone();
            r.push(bi.clone());
            r
        })
        .collect();
    for k in 0..n {
        // Any non-zero pivot will do in exact arithmetic.
        let piv = (k..n).find(|&i| !t[i][k].is_zero())?;
        t.swap(k, piv);
        let inv = t[k][k].recip();
        for v in t[k][k..].iter_mut() {
            *v *= &inv;
        }
        let (top, bottom) = t.split_at_mut(k + 1);
        let pivot_row = &top[k];
        for row in bottom.iter_mut() {
            eliminate(row, pivot_row, k);
        }
    }
    // Back substitution (the diagonal is 1).
    let mut y = vec![Rat::zero(); n];
    for k in (0..n).rev() {
        let mut v = t[k][n].clone();
        for j in k + 1..n {
            if !t[k][j].is_zero() {
                v -= &t[k][j] * &y[j];
            }
        }
        y[k] = v;
    }
    Some(y)
}

/// Solves the square integer system `A y = b` by fraction-free Gauss–Jordan elimination
/// (Bareiss): returns `(x, den)` with `den > 0` and `y = x / den`, or `None` if `A` is
/// singular. Only exact integer divisions occur (every intermediate entry is a minor of
/// `[A | b]`), so no gcd is ever computed: much faster than rational elimination.
pub(crate) fn solve_int(mut t: Vec<Vec<BigInt>>, b: &[BigInt]) -> Option<(Vec<BigInt>, BigInt)> {
    let n = b.len();
    for (row, bi) in t.iter_mut().zip(b) {
        row.push(bi.clone());
    }
    let mut prev = BigInt::one();
    for c in 0..n {
        let piv = (c..n).find(|&i| !t[i][c].is_zero())?;
        t.swap(c, piv);
        let (before, rest) = t.split_at_mut(c);
        let (pivot_row, after) = rest.split_first_mut().expect("c < n");
        for row in before.iter_mut().chain(after.iter_mut()) {
            let f = std::mem::take(&mut row[c]);
            for (j, x) in row.iter_mut().enumerate() {
                if j == c {
                    continue;
                }
                let v = &pivot_row[c] * &*x - &f * &pivot_row[j];
                debug_assert!((&v % &prev).is_zero());
                *x = v / &prev;
            }
        }
        prev = pivot_row[c].clone();
    }
    // Every diagonal entry now equals the determinant (up to the row order) `prev`.
    let mut x: Vec<BigInt> = t
        .into_iter()
        .map(|mut row| row.pop().expect("rhs"))
        .collect();
    if prev.is_negative() {
        prev = -prev;
        for v in x.iter_mut() {
            *v = -std::mem::take(v);
        }
    }
    Some((x, prev))
}

/// `row -= row[col] · pivot_row` (only from `col` on).
fn eliminate(row: &mut [Rat], pivot_row: &[Rat], col: usize) {
    let f = row[col].clone();
    if f.is_zero() {
        return;
    }
    for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
        if !p.is_zero() {
            *x -= &f * p;
        }
    }
}

/// Finds a vertex of `{ y ≥ 0 : A y = b }` (`A` is `n × k`, given by rows), or `None` if the set
/// is empty.
///
/// Phase 1 of the simplex method with one artificial variable per row, Bland's rule, exact
/// arithmetic: always terminates. The returned point is a basic feasible solution.
pub(crate) fn feasible_vertex(a: &[Vec<Rat>], b: &[Rat]) -> Option<Vec<Rat>> {
    let n = b.len();
    let k = a.first().map_or(0, Vec::len);
    let ncols = k + n; // original variables, then artificials; rhs last
    let mut t: Vec<Vec<Rat>> = Vec::with_capacity(n + 1);
    for (i, (row, bi)) in a.iter().zip(b).enumerate() {
        let s = if bi.is_negative() {
            -Rat::one()
        } else {
            Rat::one()
        };
        let mut r: Vec<Rat> = row.iter().map(|v| v * &s).collect();
        r.extend((0..n).map(|j| if j == i { Rat::one() } else { Rat::zero() }));
        r.push(bi * &s);
        t.push(r);
    }
    // Objective row: minimise the sum of the artificials. Stored as reduced costs c_j with the
    // (negated) objective value in the last column: obj = Σ rhs − Σ_j (Σ_i t_ij) y_j.
    let mut obj = vec![Rat::zero(); ncols + 1];
    for r in &t {
        for j in 0..k {
            obj[j] -= &r[j];
        }
        obj[ncols] -= &r[ncols];
    }
    t.push(obj);
    let mut basis: Vec<usize> = (k..k + n).collect();
    // Bland: the smallest column with a negative reduced cost enters.
    while let Some(c) = (0..ncols).find(|&j| t[n][j].is_negative()) {
        // Ratio test; ties broken by the smallest basic variable index (Bland).
        let mut best: Option<(usize, Rat)> = None;
        for i in 0..n {
            if t[i][c].is_positive() {
                let ratio = &t[i][ncols] / &t[i][c];
                let better = match &best {
                    None => true,
                    Some((bi, br)) => ratio < *br || (ratio == *br && basis[i] < basis[*bi]),
                };
                if better {
                    best = Some((i, ratio));
                }
            }
        }
        // Phase 1 is bounded below by 0, so some entry is positive.
        let (r, _) = best.expect("phase 1 cannot be unbounded");
        pivot(&mut t, r, c);
        basis[r] = c;
    }
    if !t[n][ncols].is_zero() {
        return None; // the minimum sum of artificials is positive
    }
    let mut y = vec![Rat::zero(); k];
    for (i, &bv) in basis.iter().enumerate() {
        if bv < k {
            y[bv] = t[i][ncols].clone();
        }
    }
    Some(y)
}

/// Pivots the tableau `t` (all rows, including any objective row) on entry `(r, c)`.
pub(crate) fn pivot(t: &mut [Vec<Rat>], r: usize, c: usize) {
    let inv = t[r][c].recip();
    for v in t[r].iter_mut() {
        if !v.is_zero() {
            *v *= &inv;
        }
    }
    let pivot_row = t[r].clone();
    for (i, row) in t.iter_mut().enumerate() {
        if i == r {
            continue;
        }
        let f = row[c].clone();
        if f.is_zero() {
            continue;
        }
        for (x, p) in row.iter_mut().zip(&pivot_row) {
            if !p.is_zero() {
                *x -= &f * p;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frac;

    fn m(rows: &[&[i64]]) -> Vec<Vec<Rat>> {
        rows.iter()
            .map(|r| r.iter().map(|&v| frac(v, 1)).collect())
            .collect()
    }

    #[test]
    fn solve_small() {
        let a = m(&[&[0, 2], &[3, 1]]);
        let y = solve(&a, &[frac(4, 1), frac(5, 1)]).unwrap();
        assert_eq!(y, vec![frac(1, 1), frac(2, 1)]);
        assert!(solve(&m(&[&[1, 2], &[2, 4]]), &[frac(1, 1), frac(2, 1)]).is_none());
        assert_eq!(solve(&[], &[]), Some(vec![]));
    }

    #[test]
    fn solve_int_matches_rational_solve() {
        let a: Vec<Vec<BigInt>> = [[2, -1, 0], [-1, 2, -1], [0, -3, 5]]
            .iter()
            .map(|r| r.iter().map(|&v| BigInt::from(v)).collect())
            .collect();
        let b: Vec<BigInt> = [1, 0, 4].iter().map(|&v| BigInt::from(v)).collect();
        let (x, den) = solve_int(a.clone(), &b).unwrap();
        assert!(den > BigInt::zero());
        let ar: Vec<Vec<Rat>> = a
            .iter()
            .map(|r| r.iter().map(|v| Rat::from_integer(v.clone())).collect())
            .collect();
        let br: Vec<Rat> = b.iter().map(|v| Rat::from_integer(v.clone())).collect();
        let y = solve(&ar, &br).unwrap();
        for (xi, yi) in x.iter().zip(&y) {
            assert_eq!(Rat::new(xi.clone(), den.clone()), *yi);
        }
        // Needs a row swap; and a singular one.
        let a2 = vec![
            vec![BigInt::from(0), BigInt::from(1)],
            vec![BigInt::from(-2), BigInt::from(0)],
        ];
        let (x, den) = solve_int(a2, &[BigInt::from(3), BigInt::from(4)]).unwrap();
        assert_eq!(
            Rat::new(x[0].clone(), den.clone()),
            Rat::from_integer((-2).into())
        );
        assert_eq!(Rat::new(x[1].clone(), den), Rat::from_integer(3.into()));
        let a3 = vec![
            vec![BigInt::from(1), BigInt::from(2)],
            vec![BigInt::from(2), BigInt::from(4)],
        ];
        assert!(solve_int(a3, &[BigInt::from(3), BigInt::from(4)]).is_none());
    }

    #[test]
    fn phase_one() {
        // y1 + y2 = 1, y1 − y2 = −3 → y2 = 2, y1 = −1: infeasible.
        let a = m(&[&[1, 1], &[1, -1]]);
        assert!(feasible_vertex(&a, &[frac(1, 1), frac(-3, 1)]).is_none());
        // y1 + y2 + y3 = 2, y1 − y3 = 1.
        let a = m(&[&[1, 1, 1], &[1, 0, -1]]);
        let b = [frac(2, 1), frac(1, 1)];
        let y = feasible_vertex(&a, &b).unwrap();
        assert!(y.iter().all(|v| !v.is_negative()));
        for (row, bi) in a.iter().zip(&b) {
            let s: Rat = row.iter().zip(&y).map(|(p, q)| p * q).sum();
            assert_eq!(&s, bi);
        }
    }
}
