//! Rows that the formulation ties exactly ([`crate::RowRelation`]), in the equilibrated rows, and
//! the ratio test's use of them.
//!
//! For a relation `Σ λ_i x_i = κ` (`λᵀM = 0`, `λᵀg = 0`, `κ = λᵀh`), on a basis where the
//! relation's rows other than `a` and `b` are non-basic (zero) and the entering variable is none
//! of them, the rates of the two basic rows satisfy `λ_a α_a + λ_b α_b = 0` and their ratios
//! differ by exactly `κ / (λ_b α_b)`. The perturbed right-hand side `h + B_start ε` of the
//! lexicographic rule adds `(λᵀB_start) ε` to `κ`, so when `κ` is zero the sign of the first
//! non-zero entry of `λᵀB_start` in the priority order decides. Either way one of the two rows
//! can never leave before the other: it is no candidate. A row alone among its relation's basic
//! rows has the rate zero exactly: it is no candidate either. Judged on basic values and columns
//! computed with the updated inverse, these rows differ by round-off instead, which on long
//! paths let the opposite friction part of a slipping pair leave before its normal row: its
//! complement then enters with the column of the basic friction part negated, and the basis
//! turns singular.

use crate::pivoting::prepare::Prepared;
use crate::RowRelation;

/// A sum that cancels to within this fraction of its terms is zero by the data (the rows of a
/// relation are formed with a few roundings each: `f·a + b`, `f·a − b`).
const EXACT: f64 = 1e-13;

/// The absolute round-off of a sum among subnormal numbers (a few units of the least one):
/// there the relative bounds above do not hold, and the far entries of an equilibrated
/// contact stiffness can be subnormal (`1e-311`).
const SUBNORMAL: f64 = 64.0 * f64::from_bits(1);

/// The relations that the data satisfy, in the equilibrated rows: `(row, λ_i / E_i)`.
#[derive(Debug, Clone, Default)]
pub(crate) struct Relations {
    list: Vec<Vec<(usize, f64)>>,
    /// The relation of each row (`usize::MAX`: none).
    of_row: Vec<usize>,
}

/// `Σ λ_i v_i` and `Σ |λ_i v_i|`.
fn combine(terms: &[(usize, f64)], v: impl Fn(usize) -> f64) -> (f64, f64) {
    terms.iter().fold((0.0, 0.0), |(s, t), &(i, l)| {
        let x = l * v(i);
        (s + x, t + x.abs())
    })
}

/// `−1`, `0` or `1`: the sign of a combination, zero when it cancels to round-off of its terms.
fn sign_of((s, t): (f64, f64)) -> i8 {
    if s.abs() <= EXACT * t + SUBNORMAL {
        0
    } else if s > 0.0 {
        1
    } else {
        -1
    }
}

impl Relations {
    /// The given relations that the equilibrated `M` satisfies (`λᵀM = 0` to round-off of each
    /// column's terms); a relation that shares a row with an earlier kept one is dropped. One
    /// pass over the columns.
    pub fn new(prep: &Prepared, given: &[RowRelation]) -> Self {
        let n = prep.n;
        let list: Vec<Vec<(usize, f64)>> = given
            .iter()
            .map(|r| {
                r.terms
                    .iter()
                    .map(|&(i, l)| (i, l / prep.scaling.row[i]))
                    .collect::<Vec<_>>()
            })
            .filter(|t| t.len() >= 2 && t.iter().all(|&(i, l)| i < n && l.is_finite() && l != 0.0))
            .collect();
        if list.is_empty() {
            return Self::default();
        }
        let mut holds = vec![true; list.len()];
        for j in 0..n {
            let (col, _) = prep.m_scaled.col(j);
            for (k, terms) in list.iter().enumerate() {
                if holds[k] && sign_of(combine(terms, |i| col[i])) != 0 {
                    holds[k] = false;
                }
            }
        }
        let mut of_row = vec![usize::MAX; n];
        let mut kept = Vec::new();
        for (terms, ok) in list.into_iter().zip(holds) {
            if ok && terms.iter().all(|&(i, _)| of_row[i] == usize::MAX) {
                for &(i, _) in &terms {
                    of_row[i] = kept.len();
                }
                kept.push(terms);
            }
        }
        if kept.is_empty() {
            return Self::default();
        }
        Self { list: kept, of_row }
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The relations, each as its `(row, λ_i / E_i)` terms in the equilibrated rows.
    pub fn list(&self) -> &[Vec<(usize, f64)>] {
        &self.list
    }

    /// The candidate slots that the relations do not exclude (see the module documentation).
    ///
    /// `var_of` gives the basic variable of a slot, `slot_of` the slot of a basic `x_i`,
    /// `entering` is the entering column, `driver` the driver's column, `driver_basic` whether it
    /// is basic, `h` and `g` the tableau's right-hand side (`None`: every `κ = λᵀh` is zero, as
    /// the data make it) and driver column, and `lex` the
    /// sign of the first non-zero entry of `λᵀB_start` in the priority order for a relation.
    #[allow(clippy::too_many_arguments)]
    pub fn filter(
        &self,
        cand: Vec<usize>,
        var_of: impl Fn(usize) -> usize,
        slot_of: impl Fn(usize) -> Option<usize>,
        entering: usize,
        driver: usize,
        driver_basic: bool,
        h: Option<&[f64]>,
        g: &[f64],
        lex: impl Fn(&[(usize, f64)], i8) -> i8,
    ) -> Vec<usize> {
        if self.list.is_empty() || cand.is_empty() {
            return cand;
        }
        let n = self.of_row.len();
        let mut seen = vec![false; self.list.len()];
        let mut excluded: Vec<usize> = Vec::new();
        for &s in &cand {
            let v = var_of(s);
            if v >= n || self.of_row[v] == usize::MAX {
                continue;
            }
            let k = self.of_row[v];
            if std::mem::replace(&mut seen[k], true) {
                continue;
            }
            let terms = &self.list[k];
            if terms.iter().any(|&(i, _)| i == entering) {
                continue;
            }
            // The driver moves with the entering column: the relation pins the rows only if
            // it does not involve the driver.
            let g_sign = sign_of(combine(terms, |i| g[i]));
            if (driver_basic || entering == driver) && g_sign != 0 {
                continue;
            }
            let basic: Vec<(usize, f64)> = terms
                .iter()
                .filter_map(|&(i, l)| slot_of(i).map(|s| (s, l)))
                .collect();
            match basic[..] {
                // Alone: its rate is zero by the data.
                [(a, _)] => excluded.push(a),
                [(a, la), (b, lb)] if (la > 0.0) != (lb > 0.0) => {
                    let kappa = match h.map_or(0, |h| sign_of(combine(terms, |i| h[i]))) {
                        0 => lex(terms, -g_sign),
                        s => s,
                    };
                    // ratio_b − ratio_a has the sign of κ·λ_b.
                    match kappa as f64 * lb {
                        d if d > 0.0 => excluded.push(b),
                        d if d < 0.0 => excluded.push(a),
                        _ => {}
                    }
                }
                _ => {}
            }
        }
        if excluded.is_empty() {
            return cand;
        }
        let mut cand = cand;
        cand.retain(|s| !excluded.contains(s));
        cand
    }
}

/// Rows that the pass over the kernel's columns of `M` need not read
/// ([`Basis`](crate::pivoting::basis::Basis)'s slack rows `v − A[:, S] y_S`): a tail of rows
/// `read..n`, each the last row of a relation whose other rows are all read. After the pass over
/// rows `..read` each is formed from its relation: `λᵀ v` is unchanged by the pass (`λᵀM = 0`),
/// so `v_r = (λᵀ v_before − Σ_{i≠r} λ_i v_i) / λ_r`. For the contact LCP these are the `m` rows
/// `x_t-` (`x_t+ + x_t- = 2f·x_n` row by row of `M`): the pass reads two thirds of each column.
/// A derived value differs from the one summed over the columns by round-off of the relation's
/// terms, and it satisfies the relation to round-off, which a summed one satisfies only to the
/// pass's own round-off.
#[derive(Debug, Clone)]
pub(crate) struct DerivedRows {
    /// The rows the pass reads: `..read`.
    pub read: usize,
    /// For row `read + t`: its relation's terms and its own `λ`.
    rows: Vec<(Vec<(usize, f64)>, f64)>,
}

impl DerivedRows {
    /// The longest tail of the `n` rows that `relations` let the pass skip; `None` if there is
    /// none. A row is derived only if its `λ` is at least `10⁻³` of the relation's largest (a
    /// division by it magnifies the relation's own round-off, which [`Relations::new`] allows
    /// up to `10⁻¹³` of its terms) and only from a relation that names each row once.
    pub fn new(n: usize, relations: &Relations) -> Option<Self> {
        let list = relations.list();
        let mut relation_of = vec![usize::MAX; n];
        for (k, terms) in list.iter().enumerate() {
            let Some(&(r, l)) = terms.iter().max_by_key(|&&(i, _)| i) else {
                continue;
            };
            let largest = terms.iter().fold(0.0f64, |a, &(_, l)| a.max(l.abs()));
            let distinct = terms
                .iter()
                .enumerate()
                .all(|(a, &(i, _))| terms[..a].iter().all(|&(j, _)| j != i));
            if r < n && distinct && l.abs() >= 1e-3 * largest {
                relation_of[r] = k;
            }
        }
        let mut read = n;
        while read > 0 && relation_of[read - 1] != usize::MAX {
            read -= 1;
        }
        // Every other row of a derived row's relation must be read: else read more rows.
        loop {
            let needed = (read..n)
                .flat_map(|r| {
                    list[relation_of[r]]
                        .iter()
                        .map(|&(i, _)| i)
                        .filter(move |&i| i != r)
                })
                .max();
            match needed {
                Some(i) if i >= read => read = i + 1,
                _ => break,
            }
        }
        (read < n).then(|| Self {
            read,
            rows: (read..n)
                .map(|r| {
                    let terms = list[relation_of[r]].clone();
                    let l = terms.iter().find(|&&(i, _)| i == r).map_or(1.0, |t| t.1);
                    (terms, l)
                })
                .collect(),
        })
    }

    /// `λᵀ v` of each derived row's relation, before the pass.
    pub fn before(&self, v: &[f64]) -> Vec<f64> {
        self.rows
            .iter()
            .map(|(terms, _)| terms.iter().map(|&(i, l)| l * v[i]).sum())
            .collect()
    }

    /// The derived rows of `v` after the pass over its rows `..read`, from [`DerivedRows::before`].
    pub fn derive(&self, v: &mut [f64], before: &[f64]) {
        for (t, ((terms, l), c)) in self.rows.iter().zip(before).enumerate() {
            let r = self.read + t;
            let others: f64 = terms
                .iter()
                .filter(|&&(i, _)| i != r)
                .map(|&(i, li)| li * v[i])
                .sum();
            v[r] = (c - others) / l;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::mat;

    /// Friction rows formed as `fl(f·a) ∓ b` among subnormal numbers (the far entries of an
    /// equilibrated contact stiffness): with `f = 0.3`, `a = 8u`, `b = u` (`u` the least
    /// subnormal) `fl(0.3·8u) = 2u`, so the rows are `u` and `3u` and their sum misses
    /// `fl(0.6·8u) = 5u` by `u`: a rounding, not a failed relation. Before, 914 of the 1000
    /// relations of the benchmark's zone at m = 1000 were dropped this way. A real difference
    /// among subnormals, and any relative one among normal numbers, keep their sign.
    #[test]
    fn subnormal_rounding_does_not_break_a_relation() {
        let u = f64::from_bits(1);
        let terms = [(1, 1.0), (2, 1.0), (0, -0.6)];
        let a = 8.0 * u;
        let row = |sign: f64| 0.3 * a + sign * u;
        assert_eq!(row(-1.0), u);
        assert_eq!(row(1.0), 3.0 * u);
        let col = [a, row(-1.0), row(1.0)];
        let (s, _) = combine(&terms, |i| col[i]);
        assert_eq!(s, -u, "the sum misses by one rounding");
        assert_eq!(sign_of(combine(&terms, |i| col[i])), 0);
        let off = [a, row(-1.0), row(1.0) + 1000.0 * u];
        assert_eq!(sign_of(combine(&terms, |i| off[i])), 1);
        let normal = [5.0, 1.5, 1.5 + 1e-12];
        assert!(combine(&terms, |i| normal[i]).0.abs() < 2e-12);
        assert_eq!(sign_of(combine(&terms, |i| normal[i])), 1);
    }

    /// Rows 1 and 2 add up to twice row 0 (by hand); rows 0 and 1 do not add up to zero.
    #[test]
    fn only_relations_that_the_data_satisfy_are_kept() {
        let m = mat![[1.0, 2.0, -3.0], [0.5, 3.0, 1.0], [1.5, 1.0, -7.0]];
        let prep = Prepared::new(&m);
        let holds = RowRelation {
            terms: vec![(1, 1.0), (2, 1.0), (0, -2.0)],
        };
        let fails = RowRelation {
            terms: vec![(0, 1.0), (1, 1.0)],
        };
        let r = Relations::new(&prep, std::slice::from_ref(&holds));
        assert_eq!(r.list.len(), 1);
        assert_eq!(r.of_row, vec![0, 0, 0]);
        assert!(Relations::new(&prep, std::slice::from_ref(&fails)).is_empty());
        // A failing relation takes no rows; a row already in a relation is not taken again.
        let r = Relations::new(&prep, &[fails, holds.clone(), holds]);
        assert_eq!(r.list.len(), 1);
    }

    /// The derived rows are the longest tail of relations' last rows whose other rows are
    /// read: all of `2m..3m` for the friction rows of `m` pairs; from the row after a pair
    /// without a relation; none when a relation's last row is not at the end.
    #[test]
    fn the_derived_rows_are_a_tail_of_relations_last_rows() {
        let m = 4;
        let n = 3 * m;
        let pair = |i: usize| vec![(m + i, 1.0), (2 * m + i, 1.0), (i, -0.6)];
        let relations = |pairs: &[usize]| Relations {
            list: pairs.iter().map(|&i| pair(i)).collect(),
            of_row: Vec::new(),
        };
        let all = DerivedRows::new(n, &relations(&[0, 1, 2, 3])).expect("a tail");
        assert_eq!(all.read, 2 * m);
        let gap = DerivedRows::new(n, &relations(&[0, 2, 3])).expect("a tail");
        assert_eq!(gap.read, 2 * m + 2);
        assert!(DerivedRows::new(n, &relations(&[0, 1, 2])).is_none());
        // A relation naming its last row twice, or with a tiny λ there, derives nothing.
        let twice = Relations {
            list: vec![vec![(0, 1.0), (n - 1, 0.5), (n - 1, 0.5)]],
            of_row: Vec::new(),
        };
        assert!(DerivedRows::new(n, &twice).is_none());
        let tiny = Relations {
            list: vec![vec![(0, 1.0), (n - 1, 1e-4)]],
            of_row: Vec::new(),
        };
        assert!(DerivedRows::new(n, &tiny).is_none());
        // A derived row whose relation needs another row of the tail: that row is read.
        let mut odd = relations(&[0, 1, 2]);
        odd.list.push(vec![(2 * m + 1, 1.0), (2 * m + 3, 1.0)]);
        let d = DerivedRows::new(n, &odd).expect("a tail");
        assert_eq!(d.read, 2 * m + 2);
        // Forming a derived row from the others and λᵀv before the pass.
        let v: Vec<f64> = (0..n).map(|i| i as f64 + 0.5).collect();
        let before = all.before(&v);
        let mut w = v.clone();
        w[all.read..].fill(1e9);
        all.derive(&mut w, &before);
        for r in all.read..n {
            assert!(
                (w[r] - v[r]).abs() <= 1e-12 * v[r].abs(),
                "{r}: {} against {}",
                w[r],
                v[r]
            );
        }
    }
}
