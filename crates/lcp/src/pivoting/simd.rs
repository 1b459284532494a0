//! The engine's hot loops compiled for the widest vector instructions of the machine it runs on,
//! chosen once at run time.
//!
//! The slack-row pass ([`add_columns`]), the kernel inverse's updates and solves ([`axpy`],
//! [`dot`]) are plain element-wise loops. Built for the baseline `x86_64` (SSE2) they handle two
//! doubles an instruction, while the dense LU the benchmarks compare with (`faer`) picks AVX2 or
//! AVX-512 at run time. Here each loop's body is written once (`#[inline(always)]`) and
//! instantiated inside functions compiled with `avx2` and with `avx512f` enabled; [`level`] picks
//! one from what the processor reports, once per process.
//!
//! **The results are the same bits at every level.** Each output element is formed by the same
//! multiplications and additions in the same order whatever the vector width: the lanes of a
//! vector are independent elements (or, in [`dot`], the eight partial sums the loop keeps in any
//! case), and Rust never fuses a multiplication and an addition into one rounding (no FMA
//! contraction without an explicit `mul_add`). The tests below compare every level the machine
//! has with the plain one, bit for bit, on data whose sums would change in their last bits under
//! any other association.

use std::sync::OnceLock;

/// The vector instructions a loop is compiled for. Only [`level`] (and, in tests, `levels`)
/// hands out a level, and only one the processor has: the `*_at` functions of this module,
/// which run the loops compiled for the level they are given, are private to it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(not(target_arch = "x86_64"), allow(dead_code))]
pub(crate) enum Level {
    /// The target's baseline (SSE2 on `x86_64`).
    Plain,
    /// AVX2: four doubles an instruction.
    Avx2,
    /// AVX-512F: eight doubles an instruction.
    Avx512,
}

/// The widest level this processor supports (detected once).
pub(crate) fn level() -> Level {
    static LEVEL: OnceLock<Level> = OnceLock::new();
    *LEVEL.get_or_init(detect)
}

fn detect() -> Level {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            return Level::Avx512;
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            return Level::Avx2;
        }
    }
    Level::Plain
}

/// Every level this processor supports, the plain one first (for tests).
#[cfg(test)]
pub(crate) fn levels() -> Vec<Level> {
    let mut v = vec![Level::Plain];
    if level() != Level::Plain {
        v.push(Level::Avx2);
    }
    if level() == Level::Avx512 {
        v.push(Level::Avx512);
    }
    v
}

/// Calls `$body($args)` compiled for `$level`: the body is `#[inline(always)]`, so it is
/// compiled into each of the wrappers generated here with their target features.
macro_rules! at_level {
    ($level:expr, fn $name:ident($($arg:ident: $ty:ty),*) -> $ret:ty = $body:path) => {{
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2")]
        unsafe fn avx2($($arg: $ty),*) -> $ret {
            $body($($arg),*)
        }
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx512f")]
        unsafe fn avx512($($arg: $ty),*) -> $ret {
            $body($($arg),*)
        }
        match $level {
            // SAFETY: the levels reach these private functions only from `level()`, which
            // returns them only where the processor reports the features (`detect`), or from
            // the tests' `levels()`, which returns only what `level()` allows.
            #[cfg(target_arch = "x86_64")]
            Level::Avx512 => unsafe { avx512($($arg),*) },
            #[cfg(target_arch = "x86_64")]
            Level::Avx2 => unsafe { avx2($($arg),*) },
            _ => $body($($arg),*),
        }
    }};
}

/// `y += a·x` over the common length.
#[inline]
pub(crate) fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    axpy_at(level(), y, a, x)
}

fn axpy_at(level: Level, y: &mut [f64], a: f64, x: &[f64]) {
    at_level!(level, fn axpy(y: &mut [f64], a: f64, x: &[f64]) -> () = axpy_body)
}

#[inline(always)]
fn axpy_body(y: &mut [f64], a: f64, x: &[f64]) {
    let n = y.len().min(x.len());
    let (y, x) = (&mut y[..n], &x[..n]);
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += a * xi;
    }
}

/// `aᵀb` over the common length, as eight partial sums (element `i` into sum `i mod 8`) added
/// in order at the end, then the left-over elements one by one.
#[inline]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    dot_at(level(), a, b)
}

fn dot_at(level: Level, a: &[f64], b: &[f64]) -> f64 {
    at_level!(level, fn dot(a: &[f64], b: &[f64]) -> f64 = dot_body)
}

#[inline(always)]
fn dot_body(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 8];
    let mut ca = a.chunks_exact(8);
    let mut cb = b.chunks_exact(8);
    for (x, y) in (&mut ca).zip(&mut cb) {
        for l in 0..8 {
            acc[l] += x[l] * y[l];
        }
    }
    let mut s: f64 = acc.iter().sum();
    for (x, y) in ca.remainder().iter().zip(cb.remainder()) {
        s += x * y;
    }
    s
}

/// [`dot`] of `a` with up to four vectors at once, each sum formed exactly as [`dot`] forms it.
/// One dot product is a chain of dependent additions (each of its eight partial sums waits for
/// the last); four side by side keep the adder busy and read `a` once.
pub(crate) fn dots(a: &[f64], b: &[&[f64]]) -> [f64; 4] {
    dots_at(level(), a, b)
}

fn dots_at(level: Level, a: &[f64], b: &[&[f64]]) -> [f64; 4] {
    at_level!(level, fn dots(a: &[f64], b: &[&[f64]]) -> [f64; 4] = dots_body)
}

#[inline(always)]
fn dots_body(a: &[f64], b: &[&[f64]]) -> [f64; 4] {
    let mut out = [0.0f64; 4];
    if b.len() != 4 || b.iter().any(|v| v.len() != a.len()) {
        for (o, v) in out.iter_mut().zip(b) {
            *o = dot_body(a, v);
        }
        return out;
    }
    let n = a.len();
    let full = n - n % 8;
    let mut acc = [[0.0f64; 8]; 4];
    let (b0, b1, b2, b3) = (&b[0][..n], &b[1][..n], &b[2][..n], &b[3][..n]);
    let mut i = 0;
    while i < full {
        let x = &a[i..i + 8];
        let (y0, y1, y2, y3) = (&b0[i..i + 8], &b1[i..i + 8], &b2[i..i + 8], &b3[i..i + 8]);
        for l in 0..8 {
            acc[0][l] += x[l] * y0[l];
            acc[1][l] += x[l] * y1[l];
            acc[2][l] += x[l] * y2[l];
            acc[3][l] += x[l] * y3[l];
        }
        i += 8;
    }
    for (q, o) in out.iter_mut().enumerate() {
        let mut s: f64 = acc[q].iter().sum();
        for j in full..n {
            s += a[j] * b[q][j];
        }
        *o = s;
    }
    out
}

/// `out += Σ y_s c_s` over the columns `c` (each at least as long as `out`) with weights `y`,
/// in their order, four columns to a partial sum: `out_i += (y_a c_ai + y_b c_bi + y_c c_ci +
/// y_d c_di)` for each four in turn, then the left-over columns one by one. Two fours are taken
/// per pass over `out` (eight columns read side by side, half the passes over `out`); the sums
/// are formed exactly as one four at a time would form them.
pub(crate) fn add_columns(columns: &[&[f64]], y: &[f64], out: &mut [f64]) {
    add_columns_at(level(), columns, y, out)
}

fn add_columns_at(level: Level, columns: &[&[f64]], y: &[f64], out: &mut [f64]) {
    at_level!(level, fn add(columns: &[&[f64]], y: &[f64], out: &mut [f64]) -> () = add_columns_body)
}

#[inline(always)]
fn add_columns_body(columns: &[&[f64]], y: &[f64], out: &mut [f64]) {
    debug_assert_eq!(columns.len(), y.len());
    let len = out.len();
    let mut eights = columns.chunks_exact(8);
    let mut ys = y.chunks_exact(8);
    for (ch, w) in (&mut eights).zip(&mut ys) {
        let [c0, c1, c2, c3, c4, c5, c6, c7]: [&[f64]; 8] = std::array::from_fn(|j| &ch[j][..len]);
        for (i, t) in out.iter_mut().enumerate() {
            let first = *t + (w[0] * c0[i] + w[1] * c1[i] + w[2] * c2[i] + w[3] * c3[i]);
            *t = first + (w[4] * c4[i] + w[5] * c5[i] + w[6] * c6[i] + w[7] * c7[i]);
        }
    }
    let (rest, wrest) = (eights.remainder(), ys.remainder());
    let mut fours = rest.chunks_exact(4);
    let mut wfours = wrest.chunks_exact(4);
    for (ch, w) in (&mut fours).zip(&mut wfours) {
        let (c0, c1, c2, c3) = (&ch[0][..len], &ch[1][..len], &ch[2][..len], &ch[3][..len]);
        for ((((t, a0), a1), a2), a3) in out.iter_mut().zip(c0).zip(c1).zip(c2).zip(c3) {
            *t += w[0] * a0 + w[1] * a1 + w[2] * a2 + w[3] * a3;
        }
    }
    for (c, &w) in fours.remainder().iter().zip(wfours.remainder()) {
        axpy_body(out, w, c);
    }
}

/// `r += s·e` and `t += size·|e|` with `e = 0 + c` (`plus`) or `e = 0 − c`: the terms of a
/// column of the tableau, read from its stored column of `M`, as a residual and the size of
/// its terms gather them (`Pivoter::direction_residual`).
pub(crate) fn residual_terms(
    r: &mut [f64],
    t: &mut [f64],
    c: &[f64],
    s: f64,
    size: f64,
    plus: bool,
) {
    residual_terms_at(level(), r, t, c, s, size, plus)
}

fn residual_terms_at(
    level: Level,
    r: &mut [f64],
    t: &mut [f64],
    c: &[f64],
    s: f64,
    size: f64,
    plus: bool,
) {
    at_level!(level, fn terms(r: &mut [f64], t: &mut [f64], c: &[f64], s: f64, size: f64, plus: bool) -> () = residual_terms_body)
}

#[inline(always)]
fn residual_terms_body(r: &mut [f64], t: &mut [f64], c: &[f64], s: f64, size: f64, plus: bool) {
    let n = r.len().min(t.len()).min(c.len());
    let (r, t, c) = (&mut r[..n], &mut t[..n], &c[..n]);
    if plus {
        for ((ri, ti), &v) in r.iter_mut().zip(t.iter_mut()).zip(c) {
            let e = 0.0 + v;
            *ri += s * e;
            *ti += size * e.abs();
        }
    } else {
        for ((ri, ti), &v) in r.iter_mut().zip(t.iter_mut()).zip(c) {
            let e = 0.0 - v;
            *ri += s * e;
            *ti += size * e.abs();
        }
    }
}

/// [`add_columns`] for two right-hand sides over the same columns: `out1 += Σ y1_s c_s` and
/// `out2 += Σ y2_s c_s`, each formed exactly as [`add_columns`] forms it alone (the same
/// groups of four and eight, in the same order), with each column read once for both.
pub(crate) fn add_columns2(
    columns: &[&[f64]],
    y1: &[f64],
    y2: &[f64],
    out1: &mut [f64],
    out2: &mut [f64],
) {
    add_columns2_at(level(), columns, y1, y2, out1, out2)
}

fn add_columns2_at(
    level: Level,
    columns: &[&[f64]],
    y1: &[f64],
    y2: &[f64],
    out1: &mut [f64],
    out2: &mut [f64],
) {
    at_level!(level, fn add2(columns: &[&[f64]], y1: &[f64], y2: &[f64], out1: &mut [f64], out2: &mut [f64]) -> () = add_columns2_body)
}

#[inline(always)]
fn add_columns2_body(
    columns: &[&[f64]],
    y1: &[f64],
    y2: &[f64],
    out1: &mut [f64],
    out2: &mut [f64],
) {
    debug_assert_eq!(columns.len(), y1.len());
    debug_assert_eq!(columns.len(), y2.len());
    let len = out1.len().min(out2.len());
    let (out1, out2) = (&mut out1[..len], &mut out2[..len]);
    let mut eights = columns.chunks_exact(8);
    let mut ys = y1.chunks_exact(8).zip(y2.chunks_exact(8));
    for (ch, (w, v)) in (&mut eights).zip(&mut ys) {
        let [c0, c1, c2, c3, c4, c5, c6, c7]: [&[f64]; 8] = std::array::from_fn(|j| &ch[j][..len]);
        for i in 0..len {
            let first = out1[i] + (w[0] * c0[i] + w[1] * c1[i] + w[2] * c2[i] + w[3] * c3[i]);
            out1[i] = first + (w[4] * c4[i] + w[5] * c5[i] + w[6] * c6[i] + w[7] * c7[i]);
            let first = out2[i] + (v[0] * c0[i] + v[1] * c1[i] + v[2] * c2[i] + v[3] * c3[i]);
            out2[i] = first + (v[4] * c4[i] + v[5] * c5[i] + v[6] * c6[i] + v[7] * c7[i]);
        }
    }
    let rest = eights.remainder();
    let done = columns.len() - rest.len();
    let (w1, w2) = (&y1[done..], &y2[done..]);
    let mut fours = rest.chunks_exact(4);
    let mut wfours = w1.chunks_exact(4).zip(w2.chunks_exact(4));
    for (ch, (w, v)) in (&mut fours).zip(&mut wfours) {
        let (c0, c1, c2, c3) = (&ch[0][..len], &ch[1][..len], &ch[2][..len], &ch[3][..len]);
        for i in 0..len {
            out1[i] += w[0] * c0[i] + w[1] * c1[i] + w[2] * c2[i] + w[3] * c3[i];
            out2[i] += v[0] * c0[i] + v[1] * c1[i] + v[2] * c2[i] + v[3] * c3[i];
        }
    }
    let singles = fours.remainder();
    let at = w1.len() - singles.len();
    for ((c, &a), &b) in singles.iter().zip(&w1[at..]).zip(&w2[at..]) {
        axpy_body(out1, a, c);
        axpy_body(out2, b, c);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The residual's terms are the plain loop's bits at every level, signed zeros included.
    #[test]
    fn residual_terms_are_the_plain_loops_at_every_level() {
        let mut c = data(1003, 7);
        c[3] = 0.0;
        c[4] = -0.0;
        for plus in [false, true] {
            let (r0, t0) = (data(1003, 8), data(1003, 9));
            let (mut r1, mut t1) = (r0.clone(), t0.clone());
            for ((ri, ti), &v) in r1.iter_mut().zip(t1.iter_mut()).zip(&c) {
                let e = if plus { 0.0 + v } else { 0.0 - v };
                *ri += -0.37 * e;
                *ti += 2.5 * e.abs();
            }
            for level in levels() {
                let (mut r2, mut t2) = (r0.clone(), t0.clone());
                residual_terms_at(level, &mut r2, &mut t2, &c, -0.37, 2.5, plus);
                assert!(same(&r1, &r2) && same(&t1, &t2), "{level:?}, {plus}");
            }
        }
    }

    /// Two right-hand sides in one pass give each the bits of its own pass, at every level,
    /// for column counts that exercise the eights, a four and single columns.
    #[test]
    fn two_sums_in_one_pass_are_each_alone() {
        for level in levels() {
            for (cols, len) in [
                (0usize, 5usize),
                (3, 17),
                (4, 9),
                (8, 33),
                (23, 1003),
                (64, 64),
            ] {
                let columns: Vec<Vec<f64>> = (0..cols).map(|j| data(len, 10 + j as u64)).collect();
                let refs: Vec<&[f64]> = columns.iter().map(|c| &c[..]).collect();
                let y1 = data(cols, 3);
                let y2 = data(cols, 4);
                let (start1, start2) = (data(len, 5), data(len, 6));
                let (mut a1, mut a2) = (start1.clone(), start2.clone());
                add_columns_at(level, &refs, &y1, &mut a1);
                add_columns_at(level, &refs, &y2, &mut a2);
                let (mut b1, mut b2) = (start1.clone(), start2.clone());
                add_columns2_at(level, &refs, &y1, &y2, &mut b1, &mut b2);
                assert!(
                    same(&a1, &b1) && same(&a2, &b2),
                    "{level:?}, {cols} × {len}"
                );
            }
        }
    }

    /// Entries of both signs over six orders of magnitude: any other association of the sums
    /// than the loops' would change their last bits.
    fn data(len: usize, seed: u64) -> Vec<f64> {
        (0..len as u64)
            .map(|i| {
                let k = (i ^ seed).wrapping_mul(0x9e37_79b9_7f4a_7c15) >> 40;
                (k as f64 / (1u64 << 24) as f64 - 0.5) * (1.0 + (i % 7) as f64 * 1e5)
            })
            .collect()
    }

    fn same(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    #[test]
    fn every_level_gives_the_plain_loops_bits() {
        let levels = levels();
        // On an x86_64 machine of this decade at least AVX2 is there: the test must compare
        // something (it is still the plain level alone on another architecture).
        #[cfg(target_arch = "x86_64")]
        assert!(levels.len() > 1 || !std::arch::is_x86_feature_detected!("avx2"));
        // Lengths around the vector widths and the eight-sum blocks, and a long one.
        for len in [0, 1, 3, 7, 8, 9, 15, 16, 17, 31, 64, 1003] {
            let a = data(len, 1);
            let b = data(len, 2);
            let y0 = data(len, 3);
            let plain_dot = dot_at(Level::Plain, &a, &b);
            let mut plain_axpy = y0.clone();
            axpy_at(Level::Plain, &mut plain_axpy, -0.37, &a);
            // 8·2 + 4 + 3 columns: both eight-column passes, one four and three singles.
            let cols: Vec<Vec<f64>> = (0..23).map(|j| data(len + j, 10 + j as u64)).collect();
            let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
            let w = data(23, 99);
            let mut plain_add = y0.clone();
            add_columns_at(Level::Plain, &refs, &w, &mut plain_add);
            for &l in &levels {
                assert_eq!(
                    dot_at(l, &a, &b).to_bits(),
                    plain_dot.to_bits(),
                    "dot, {l:?}, length {len}"
                );
                let c = data(len, 5);
                let d = data(len, 6);
                let e = data(len, 7);
                let four = dots_at(l, &a, &[&b, &c, &d, &e]);
                for (got, v) in four.iter().zip([&b, &c, &d, &e]) {
                    let want = dot_at(Level::Plain, &a, v);
                    assert_eq!(got.to_bits(), want.to_bits(), "dots, {l:?}, length {len}");
                }
                // Vectors of other lengths: each over its common length with `a`, as `dot`.
                let short = &b[..len / 2];
                let mixed = dots_at(l, &a, &[&b, short, &d, &e]);
                for (got, v) in mixed.iter().zip([&b[..], short, &d, &e]) {
                    let want = dot_at(Level::Plain, &a, v);
                    assert_eq!(got.to_bits(), want.to_bits(), "dots mixed, {l:?}, {len}");
                }
                let three = dots_at(l, &a, &[&b, &c, &d]);
                assert_eq!(three[2].to_bits(), dot_at(Level::Plain, &a, &d).to_bits());
                assert_eq!(three[3], 0.0);
                let mut v = y0.clone();
                axpy_at(l, &mut v, -0.37, &a);
                assert!(same(&v, &plain_axpy), "axpy, {l:?}, length {len}");
                let mut v = y0.clone();
                add_columns_at(l, &refs, &w, &mut v);
                assert!(same(&v, &plain_add), "add_columns, {l:?}, length {len}");
            }
        }
    }

    /// The plain pass is the sum it says it is: four columns to a partial sum, in order, then
    /// the left-over columns one by one (a reference written without the eight-column blocking).
    #[test]
    fn the_pass_forms_fours_in_order() {
        let len = 37;
        let cols: Vec<Vec<f64>> = (0..15).map(|j| data(len, 40 + j as u64)).collect();
        let refs: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
        let w = data(15, 7);
        let start = data(len, 8);
        let mut reference = start.clone();
        for (i, t) in reference.iter_mut().enumerate() {
            let v = |j: usize| w[j] * cols[j][i];
            for f in 0..3 {
                *t += v(4 * f) + v(4 * f + 1) + v(4 * f + 2) + v(4 * f + 3);
            }
            for j in 12..15 {
                *t += v(j);
            }
        }
        for l in levels() {
            let mut out = start.clone();
            add_columns_at(l, &refs, &w, &mut out);
            assert!(same(&out, &reference), "{l:?}");
        }
    }
}
