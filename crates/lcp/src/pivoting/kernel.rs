//! The inverse of the basis kernel `K = A[R, S]`, stored column-major with spare capacity so that
//! every update is a sequence of contiguous `axpy`s.

use rayon::prelude::*;

use crate::pivoting::simd::{axpy, dot, dots};

/// `G = K⁻¹`: rows follow the basic non-slack columns `S`, columns the rows `R`.
#[derive(Debug, Clone, Default)]
pub(crate) struct KernelInverse {
    k: usize,
    ld: usize,
    data: Vec<f64>,
    /// A scale of `|G|` for tolerances: `max |G|` at the last `assign_lu_inverse`, raised by the new row
    /// and column of every `border` (the other updates change entries by round-off-sized
    /// corrections relative to this scale, or shrink the matrix).
    gmax: f64,
}

/// Kernel order from which the `O(k²)` passes run on the thread pool (rayon's, one thread per
/// core of the machine).
const PARALLEL_K: usize = 384;

/// faer's parallelism for the refactorisation's LU and inverse: the caller's thread pool.
/// Both split their work by blocks of the result, never a sum, so the factors and the inverse
/// are the same bits whatever the number of threads (unlike faer's product of a matrix and one
/// column, which the rest of the workspace runs with `Par::Seq`).
fn refactor_par() -> faer::Par {
    faer::Par::rayon(0)
}

/// Columns per task of the parallel passes.
pub(crate) const PARALLEL_BLOCK: usize = 64;

/// The memory of a refactorisation, kept between refactorisations: the kernel's `k × k` copy
/// that is factorised in place and faer's scratch. A fresh allocation of each (tens of MB at
/// k = 1500) was mapped from the system and faulted in page by page at every refactorisation
/// (with the kernel inverse's growth, a tenth of the 1000-bearing beam's CPU as page faults).
/// A clone starts empty: the memory is a cache, not a value.
#[derive(Default)]
pub(crate) struct RefactorWork {
    lu: Vec<f64>,
    scratch: Scratch,
}

impl std::fmt::Debug for RefactorWork {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RefactorWork")
            .field("lu", &self.lu.len())
            .field("scratch", &self.scratch)
            .finish()
    }
}

impl Clone for RefactorWork {
    fn clone(&self) -> Self {
        Self::default()
    }
}

/// faer's scratch, kept for the next step that needs no more ([`Scratch::get`]).
#[derive(Default)]
pub(crate) struct Scratch(Option<(faer::dyn_stack::StackReq, faer::dyn_stack::MemBuffer)>);

impl Scratch {
    /// The scratch for a step that needs `need` (the kept one, grown when too small).
    fn get(&mut self, need: faer::dyn_stack::StackReq) -> &mut faer::dyn_stack::MemBuffer {
        // A buffer made for `have` serves `need` when it is as long and at least as aligned
        // (its start is aligned to `have`'s alignment; `need`'s size assumes an aligned start).
        let fits = |have: &faer::dyn_stack::StackReq| {
            need.size_bytes() <= have.size_bytes() && need.align_bytes() <= have.align_bytes()
        };
        if !self.0.as_ref().is_some_and(|(have, _)| fits(have)) {
            let req = self.0.take().map_or(need, |(have, _)| need.or(have));
            self.0 = Some((req, faer::dyn_stack::MemBuffer::new(req)));
        }
        &mut self.0.as_mut().expect("scratch just made").1
    }
}

impl std::fmt::Debug for Scratch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let bytes = self.0.as_ref().map(|(req, _)| req.size_bytes());
        f.debug_tuple("Scratch").field(&bytes).finish()
    }
}

impl RefactorWork {
    /// A `k × k` matrix (column major) filled by `entry`, factorised in place by faer's LU with
    /// partial pivoting (`lu_in_place`, what `partial_piv_lu` runs on a copy before splitting
    /// it into separate `L` and `U`): the unit lower and upper factors, and the row
    /// permutation's forward and inverse indices for [`KernelInverse::assign_lu_inverse`].
    /// The factors are read by [`RefactorWork::factors`].
    pub fn lu_in_place(
        &mut self,
        k: usize,
        entry: impl Fn(usize, usize) -> f64,
    ) -> (Vec<usize>, Vec<usize>) {
        use faer::dyn_stack::MemStack;
        use faer::linalg::lu::partial_pivoting::factor;
        let par = refactor_par();
        let need = factor::lu_in_place_scratch::<usize, f64>(k, k, par, Default::default());
        self.lu.clear();
        self.lu.extend(
            (0..k)
                .flat_map(|b| (0..k).map(move |a| (a, b)))
                .map(|(a, b)| entry(a, b)),
        );
        let (mut fwd, mut bwd) = (vec![0usize; k], vec![0usize; k]);
        let scratch = self.scratch.get(need);
        factor::lu_in_place(
            faer::MatMut::from_column_major_slice_mut(&mut self.lu[..], k, k),
            &mut fwd,
            &mut bwd,
            par,
            MemStack::new(scratch),
            Default::default(),
        );
        (fwd, bwd)
    }

    /// The factors of the last [`RefactorWork::lu_in_place`] (of order `k`), and the scratch
    /// for [`KernelInverse::assign_lu_inverse`].
    pub fn factors(&mut self, k: usize) -> (faer::MatRef<'_, f64>, &mut Scratch) {
        (
            faer::MatRef::from_column_major_slice(&self.lu[..k * k], k, k),
            &mut self.scratch,
        )
    }
}

/// `a` factorised in place by faer's LU with partial pivoting ([`RefactorWork::lu_in_place`]
/// on a matrix of the caller's).
#[cfg(test)]
pub(crate) fn lu_in_place(a: &mut faer::Mat<f64>) -> (Vec<usize>, Vec<usize>) {
    let k = a.nrows();
    let mut work = RefactorWork::default();
    let (fwd, bwd) = work.lu_in_place(k, |i, j| a[(i, j)]);
    a.copy_from(work.factors(k).0);
    (fwd, bwd)
}

impl KernelInverse {
    /// A scale of the entries of `G` (see the field), `O(1)`.
    pub fn max_entry(&self) -> f64 {
        self.gmax
    }

    /// Replaces the content by the inverse of the `k × k` matrix whose LU factors with partial
    /// pivoting `lu` and `perm` hold, as faer's `lu_in_place` leaves them (`L` unit lower
    /// below the diagonal, `U` on and above it). The inverse is formed by faer's own
    /// `inverse` directly in this buffer: the same bits as `PartialPivLu::inverse`, without
    /// its separate `L`, `U` and result (two `k × k` matrices fewer at the refactorisation's
    /// peak, test `in_place_inverse_is_faers`).
    pub fn assign_lu_inverse(
        &mut self,
        lu: faer::MatRef<'_, f64>,
        perm: faer::perm::PermRef<'_, usize>,
        scratch: &mut Scratch,
    ) {
        use faer::dyn_stack::MemStack;
        use faer::linalg::lu::partial_pivoting::inverse;
        let k = lu.nrows();
        self.reserve(k);
        let par = refactor_par();
        let scratch = scratch.get(inverse::inverse_scratch::<usize, f64>(k, par));
        let out = faer::MatMut::from_column_major_slice_with_stride_mut(
            &mut self.data[..],
            k,
            k,
            self.ld,
        );
        inverse::inverse(out, lu, lu, perm, par, MemStack::new(scratch));
        let mut gmax = 0.0f64;
        for b in 0..k {
            for v in &self.data[b * self.ld..b * self.ld + k] {
                gmax = gmax.max(v.abs());
            }
        }
        self.gmax = gmax;
    }

    /// Order `k` with a buffer of room for it (the content is left as it is).
    fn reserve(&mut self, k: usize) {
        self.k = k;
        self.ld = k.max(self.ld).max(8);
        // Entries beyond `k` are never read: keep the buffer when it is large enough.
        if self.data.len() < self.ld * self.ld {
            // Freed before the larger one is taken: never both at once.
            self.data = Vec::new();
            self.data = vec![0.0; self.ld * self.ld];
        }
    }

    pub fn clear(&mut self) {
        self.k = 0;
    }

    #[inline]
    pub fn col(&self, b: usize) -> &[f64] {
        &self.data[b * self.ld..b * self.ld + self.k]
    }

    #[inline]
    pub fn get(&self, a: usize, b: usize) -> f64 {
        self.data[b * self.ld + a]
    }

    /// `y = G v`.
    pub fn solve(&self, v: &[f64]) -> Vec<f64> {
        let k = self.k;
        let sum = |range: std::ops::Range<usize>| {
            let mut y = vec![0.0; k];
            for b in range {
                if v[b] != 0.0 {
                    axpy(&mut y, v[b], self.col(b));
                }
            }
            y
        };
        if k < PARALLEL_K {
            return sum(0..k);
        }
        // Two halves of the columns as two tasks of the thread pool, then one addition: the
        // association of the sums is fixed, so the result does not depend on the number of
        // threads. (Summing in more blocks changes the round-off, and the 1000-support beam's
        // path is sensitive to it: see docs/engine.md.)
        let half = k / 2;
        let (y, y2) = rayon::join(|| sum(0..half), || sum(half..k));
        finish_halves(y, Some(y2))
    }

    fn grow(&mut self, k: usize) {
        if k <= self.ld {
            return;
        }
        // Room for k/8 more borders: a copy (O(k²)) every k/8 pivots is O(k) a pivot, and the
        // buffer stays within 1.27 k² (doubling could hold up to 4 k², at k = 1300 and n = 3000
        // more than the 3000 × 3000 M itself).
        let ld = (self.ld + self.ld / 8 + 8).max(k);
        let mut data = vec![0.0; ld * ld];
        for b in 0..self.k {
            data[b * ld..b * ld + self.k].copy_from_slice(self.col(b));
        }
        self.ld = ld;
        self.data = data;
    }

    /// Borders `K` with a column `u` and a row `v` (corner `δ`), given `ũ = G u`, the row `v`
    /// itself and `σ = δ − vᵀ ũ`. `ṽᵀ = vᵀ G` is formed column by column in the same pass that
    /// updates the column, so `G` is read once.
    #[cfg(test)]
    pub fn border(&mut self, ut: &[f64], v: &[f64], sigma: f64) {
        self.border_solving(ut, v, sigma, &[]);
    }

    /// [`KernelInverse::border`], and `G u` for each `u` of `rhs` (`k + 1` long, in the order
    /// of the bordered rows) for the bordered `G`, formed in the same pass
    /// ([`KernelInverse::update_solving`]): the same bits as [`KernelInverse::solve`] after it.
    pub fn border_solving(
        &mut self,
        ut: &[f64],
        v: &[f64],
        sigma: f64,
        rhs: &[&[f64]],
    ) -> Vec<Vec<f64>> {
        let k = self.k;
        self.grow(k + 1);
        let ld = self.ld;
        let f: Vec<f64> = ut.iter().map(|u| u / sigma).collect();
        // The old columns, four at a time (their dot products side by side); the largest entry
        // of the new row comes back.
        let update = |_: usize, cols: &mut [f64]| {
            let vb = group_dots(v, cols, ld, k);
            let mut top = 0.0f64;
            for (col, &vb) in cols.chunks_mut(ld).zip(&vb) {
                let col = &mut col[..k + 1];
                axpy(&mut col[..k], vb, &f);
                col[k] = -vb / sigma;
                top = top.max(col[k].abs());
            }
            top
        };
        let fused = !rhs.is_empty() && solving_in_pass();
        let (new_row, partial) = if fused {
            self.update_solving(4, k, k + 1, rhs, update)
        } else {
            (self.update_columns(4, update), Vec::new())
        };
        let col = &mut self.data[k * ld..k * ld + k + 1];
        for (c, fa) in col.iter_mut().zip(&f) {
            *c = -fa;
        }
        col[k] = 1.0 / sigma;
        let new_col = col.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        self.gmax = self.gmax.max(new_col).max(new_row);
        self.k = k + 1;
        if !fused {
            return rhs.iter().map(|u| self.solve(u)).collect();
        }
        // The new column is the last of each sum (of its second half).
        let last = &self.data[k * ld..k * ld + k + 1];
        rhs.iter()
            .zip(partial)
            .map(|(u, (mut y, mut rest))| {
                let y2 = rest.as_mut().unwrap_or(&mut y);
                if u[k] != 0.0 {
                    axpy(y2, u[k], last);
                }
                finish_halves(y, rest)
            })
            .collect()
    }

    /// Removes row `a` and column `b` of `K` (a pivot on `G[a, b]`); the last row and column
    /// move into the freed places.
    pub fn remove(&mut self, a: usize, b: usize) {
        let k = self.k;
        let piv = self.get(a, b);
        let mut f: Vec<f64> = self.col(b).iter().map(|g| g / piv).collect();
        f[a] = 0.0;
        self.update_columns(1, |_, col| {
            let ga = col[a];
            if ga != 0.0 {
                axpy(&mut col[..k], -ga, &f);
            }
            0.0
        });
        let ld = self.ld;
        if b != k - 1 {
            self.data
                .copy_within((k - 1) * ld..(k - 1) * ld + k, b * ld);
        }
        if a != k - 1 {
            for c in 0..k - 1 {
                self.data[c * ld + a] = self.data[c * ld + k - 1];
            }
        }
        self.k = k - 1;
    }

    /// Replaces column `a` of `K` (row `a` of `G`) given `ũ = G u` for the new column.
    #[cfg(test)]
    pub fn replace_column(&mut self, a: usize, ut: &[f64]) {
        self.replace_column_solving(a, ut, &[]);
    }

    /// [`KernelInverse::replace_column`], and `G u` for each `u` of `rhs` for the new `G`,
    /// formed in the same pass: the same bits as [`KernelInverse::solve`] after it.
    pub fn replace_column_solving(
        &mut self,
        a: usize,
        ut: &[f64],
        rhs: &[&[f64]],
    ) -> Vec<Vec<f64>> {
        let piv = ut[a];
        let k = self.k;
        let update = |_: usize, col: &mut [f64]| {
            let ra = col[a] / piv;
            if ra != 0.0 {
                axpy(&mut col[..k], -ra, ut);
                col[a] = ra;
            }
            0.0
        };
        self.update_then_solve(1, rhs, update)
    }

    /// Replaces row `b` of `K` by `v`, given `w = G e_b` (a copy); `ṽᵀ = vᵀ G` is formed column by
    /// column in the pass that updates it.
    #[cfg(test)]
    pub fn replace_row(&mut self, b: usize, w: &[f64], v: &[f64]) {
        self.replace_row_solving(b, w, v, &[]);
    }

    /// [`KernelInverse::replace_row`], and `G u` for each `u` of `rhs` (in the order of the
    /// rows after the replacement) for the new `G`, formed in the same pass: the same bits as
    /// [`KernelInverse::solve`] after it.
    pub fn replace_row_solving(
        &mut self,
        b: usize,
        w: &[f64],
        v: &[f64],
        rhs: &[&[f64]],
    ) -> Vec<Vec<f64>> {
        let vw = dot(v, w);
        let (k, ld) = (self.k, self.ld);
        // Four columns at a time: their dot products side by side.
        let update = |c0: usize, cols: &mut [f64]| {
            let vc = group_dots(v, cols, ld, k);
            for (j, (col, vc)) in cols.chunks_mut(ld).zip(vc).enumerate() {
                let corr = (vc - if c0 + j == b { 1.0 } else { 0.0 }) / vw;
                if corr != 0.0 {
                    axpy(&mut col[..k], -corr, w);
                }
            }
            0.0
        };
        self.update_then_solve(4, rhs, update)
    }

    /// An update of every column that keeps the order `k` ([`KernelInverse::update_columns`]),
    /// then `G u` for each `u` of `rhs`: formed in the update's pass where
    /// [`solving_in_pass`] allows, else solved after it (the same bits either way).
    fn update_then_solve(
        &mut self,
        group: usize,
        rhs: &[&[f64]],
        update: impl Fn(usize, &mut [f64]) -> f64 + Sync + Send,
    ) -> Vec<Vec<f64>> {
        let k = self.k;
        if !rhs.is_empty() && solving_in_pass() {
            let (_, partial) = self.update_solving(group, k, k, rhs, update);
            partial
                .into_iter()
                .map(|(y, rest)| finish_halves(y, rest))
                .collect()
        } else {
            self.update_columns(group, update);
            rhs.iter().map(|u| self.solve(u)).collect()
        }
    }

    /// [`KernelInverse::update_columns`] over the first `updated` columns, and in the same pass
    /// for each `u` of `rhs` the partial sums of `y = Σ_b u_b G[..len, b]` over them, each
    /// column added once updated (while it is in the cache) in the order and the halves
    /// [`KernelInverse::solve`] sums a `len × len` inverse in: the first half's sum, and the
    /// second's when there are two. A column `updated..len` (a bordering's new one) is the
    /// caller's to add.
    #[allow(clippy::type_complexity)]
    fn update_solving(
        &mut self,
        group: usize,
        updated: usize,
        len: usize,
        rhs: &[&[f64]],
        f: impl Fn(usize, &mut [f64]) -> f64 + Sync + Send,
    ) -> (f64, Vec<(Vec<f64>, Option<Vec<f64>>)>) {
        let ld = self.ld;
        let part = |c0: usize, data: &mut [f64]| -> (f64, Vec<Vec<f64>>) {
            let mut ys = vec![vec![0.0; len]; rhs.len()];
            let mut top = 0.0f64;
            for (i, cols) in data.chunks_mut(group * ld).enumerate() {
                let c = c0 + i * group;
                top = top.max(f(c, cols));
                for (j, col) in cols.chunks(ld).enumerate() {
                    for (y, u) in ys.iter_mut().zip(rhs) {
                        let ub = u[c + j];
                        if ub != 0.0 {
                            axpy(y, ub, &col[..len]);
                        }
                    }
                }
            }
            (top, ys)
        };
        let data = &mut self.data[..updated * ld];
        if len < PARALLEL_K {
            let (top, ys) = part(0, data);
            return (top, ys.into_iter().map(|y| (y, None)).collect());
        }
        let half = len / 2;
        let (first, second) = data.split_at_mut(half * ld);
        let ((t1, y1), (t2, y2)) = rayon::join(|| part(0, first), || part(half, second));
        let ys = y1.into_iter().zip(y2).map(|(a, b)| (a, Some(b))).collect();
        (t1.max(t2), ys)
    }

    /// Applies `f(c, columns)` to the columns of `G` in runs of `group` (`c` the first column of
    /// the run; each column `ld` long, its first `k` entries the matrix's; the last run may be
    /// shorter), on the machine's thread pool when `G` is large, and returns the largest value
    /// `f` returned. Each column's result depends on that column alone, so it is the same
    /// whatever the threads.
    fn update_columns(
        &mut self,
        group: usize,
        f: impl Fn(usize, &mut [f64]) -> f64 + Sync + Send,
    ) -> f64 {
        let (k, ld) = (self.k, self.ld);
        let data = &mut self.data[..k * ld];
        if k < PARALLEL_K {
            data.chunks_mut(group * ld)
                .enumerate()
                .map(|(i, cols)| f(i * group, cols))
                .fold(0.0f64, f64::max)
        } else {
            data.par_chunks_mut(group * ld)
                .with_min_len((PARALLEL_BLOCK / group).max(1))
                .enumerate()
                .map(|(i, cols)| f(i * group, cols))
                .reduce(|| 0.0f64, f64::max)
        }
    }
}

/// Whether an update forms the next kernel solve in its own pass. The pass then runs as the
/// solve's two fixed halves, two tasks: on a pool of more threads the update is left to split
/// finer, and the solve runs after it (the same bits either way).
fn solving_in_pass() -> bool {
    rayon::current_num_threads() <= 2
}

/// The kernel solve's sum from its halves: the first, plus the second when there are two.
fn finish_halves(mut y: Vec<f64>, second: Option<Vec<f64>>) -> Vec<f64> {
    if let Some(y2) = second {
        axpy(&mut y, 1.0, &y2);
    }
    y
}

/// [`dots`] of `v` with the (up to four) columns of a run `cols` of columns `ld` long, over
/// their first `k` entries.
fn group_dots(v: &[f64], cols: &[f64], ld: usize, k: usize) -> [f64; 4] {
    let mut parts: [&[f64]; 4] = [&[]; 4];
    let mut count = 0;
    for (p, c) in parts.iter_mut().zip(cols.chunks(ld)) {
        *p = &c[..k];
        count += 1;
    }
    dots(v, &parts[..count])
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::linalg::solvers::DenseSolveCore;
    use faer::Mat;

    /// A well-conditioned test matrix of order `k` with entries of mixed signs and sizes.
    fn matrix(k: usize, seed: usize) -> Mat<f64> {
        Mat::<f64>::from_fn(k, k, |i, j| {
            ((i * 31 + j * 17 + seed) as f64).sin() * (1.0 + ((i + 3 * j) % 5) as f64)
                + if i == j { 4.0 * k as f64 } else { 0.0 }
        })
    }

    fn inverse_of(a: &Mat<f64>) -> KernelInverse {
        let mut g = KernelInverse::default();
        let mut lu = a.clone();
        let (fwd, bwd) = lu_in_place(&mut lu);
        g.assign_lu_inverse(
            lu.as_ref(),
            faer::perm::PermRef::new_checked(&fwd, &bwd, a.nrows()),
            &mut Scratch::default(),
        );
        g
    }

    fn same_bits(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// The kernel solves formed in the pass of an update (bordering, replacing a row or a
    /// column; one or two right-hand sides) are the solves run after the update, bit for bit,
    /// and the updated inverse is the same: below and above the order from which the passes
    /// are split in two, on pools of one, two and three threads (three: the update splits finer
    /// and the solves run after it), with some zero entries in the right-hand side (skipped by
    /// the solve).
    #[test]
    fn a_solve_in_the_update_pass_is_the_solve_after_it() {
        for k in [5usize, 40, PARALLEL_K - 1, PARALLEL_K, 2 * PARALLEL_K + 3] {
            let a = matrix(k, k);
            let g0 = inverse_of(&a);
            let rhs = |len: usize| -> Vec<f64> {
                (0..len)
                    .map(|i| {
                        if i % 7 == 3 {
                            0.0
                        } else {
                            ((i * 13 + k) as f64).cos()
                        }
                    })
                    .collect()
            };
            // Bordering: a new column u (through ũ = G u) and row v, corner δ.
            let u: Vec<f64> = (0..k).map(|i| ((i + 2 * k) as f64 * 0.37).sin()).collect();
            let v: Vec<f64> = (0..k).map(|i| ((i * 5 + k) as f64 * 0.11).cos()).collect();
            let ut = g0.solve(&u);
            let sigma = 3.0 * k as f64 - dot(&v, &ut);
            let next = rhs(k + 1);
            // Replacing row b by v, with w = G e_b.
            let b = k / 3;
            let w = g0.col(b).to_vec();
            let next_rr = rhs(k);
            let mut want_b = g0.clone();
            want_b.border(&ut, &v, sigma);
            let want_by = want_b.solve(&next);
            let mut want_r = g0.clone();
            want_r.replace_row(b, &w, &v);
            let want_ry = want_r.solve(&next_rr);
            // Replacing column a_col of K by u: ũ = G u.
            let a_col = (2 * k) / 3;
            let ut_c = g0.solve(&u);
            let mut want_c = g0.clone();
            want_c.replace_column(a_col, &ut_c);
            let want_cy = want_c.solve(&next_rr);
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("a pool");
                // Two right-hand sides at once, as a pivot asks (the next column's, the
                // values'): each as alone.
                let other: Vec<f64> = next.iter().map(|x| 1.0 - 2.0 * x).collect();
                let mut gb = g0.clone();
                let yb = pool.install(|| gb.border_solving(&ut, &v, sigma, &[&next, &other]));
                let mut gr = g0.clone();
                let yr = pool.install(|| gr.replace_row_solving(b, &w, &v, &[&next_rr]));
                let mut gc = g0.clone();
                let yc = pool.install(|| gc.replace_column_solving(a_col, &ut_c, &[&next_rr]));
                assert!(same_bits(&yb[0], &want_by), "border k = {k}, {threads}");
                assert!(same_bits(&yb[1], &want_b.solve(&other)), "border k = {k}");
                assert!(same_bits(&yr[0], &want_ry), "row k = {k}, {threads}");
                assert!(same_bits(&yc[0], &want_cy), "column k = {k}, {threads}");
                for c in 0..k {
                    assert!(same_bits(gc.col(c), want_c.col(c)), "column G, k = {k}");
                }
                for c in 0..=k {
                    assert!(same_bits(gb.col(c), want_b.col(c)), "border G, k = {k}");
                }
                for c in 0..k {
                    assert!(same_bits(gr.col(c), want_r.col(c)), "row G, k = {k}");
                }
                assert_eq!(gb.max_entry().to_bits(), want_b.max_entry().to_bits());
            }
            // And the bordered inverse is the inverse of the bordered matrix.
            let mut big = Mat::<f64>::zeros(k + 1, k + 1);
            for i in 0..k {
                for j in 0..k {
                    big[(i, j)] = a[(i, j)];
                }
                big[(i, k)] = u[i];
                big[(k, i)] = v[i];
            }
            big[(k, k)] = 3.0 * k as f64;
            let y = want_b.solve(&next);
            for i in 0..=k {
                let r: f64 = (0..=k).map(|j| big[(i, j)] * y[j]).sum::<f64>() - next[i];
                assert!(
                    r.abs() < 1e-9,
                    "k = {k}: row {i} of the bordered system off by {r}"
                );
            }
        }
    }

    // Reference: faer's `PartialPivLu::inverse` (the refactorisation before: the matrix copied,
    // factorised, split into `L` and `U`, inverted into a new matrix), bit for bit, for orders
    // on both sides of faer's blocking thresholds, and into a buffer left larger
    // by an earlier, larger order (a leading dimension above `k`).
    #[test]
    fn in_place_inverse_is_faers() {
        let mut g = KernelInverse::default();
        // one workspace for every order, as a basis keeps it: its memory, left from a larger
        // or smaller order, never shows in the factors
        let mut work = RefactorWork::default();
        for k in [1usize, 2, 7, 33, 130, 300, 520, 64, 5] {
            let a = Mat::<f64>::from_fn(k, k, |i, j| {
                ((i * 31 + j * 17 + k) as f64).sin() + if i == j { 0.5 } else { 0.0 }
            });
            let want = a.partial_piv_lu().inverse();
            // factorised by what `Basis::refactor` runs
            let (fwd, bwd) = work.lu_in_place(k, |i, j| a[(i, j)]);
            let (lu, scratch) = work.factors(k);
            let perm = faer::perm::PermRef::new_checked(&fwd, &bwd, k);
            g.assign_lu_inverse(lu, perm, scratch);
            assert_eq!(g.k, k);
            let mut gmax = 0.0f64;
            for j in 0..k {
                for i in 0..k {
                    let (w, v) = (want[(i, j)], g.col(j)[i]);
                    assert_eq!(w.to_bits(), v.to_bits(), "k = {k}, ({i}, {j}): {w} vs {v}");
                    gmax = gmax.max(w.abs());
                }
            }
            assert_eq!(g.max_entry(), gmax, "k = {k}");
        }
    }
}
