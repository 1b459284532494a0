//! Small dense linear algebra of element matrices (at most 12 × 12, row-major `Vec<f64>`):
//! Gaussian elimination and static condensation of element DOFs (end releases, the
//! incompatible modes of QM6).

/// Solves `a x = b` in place for `nrhs` right-hand sides stored row-major in `b` (`n × nrhs`).
/// Gaussian elimination with partial pivoting; the matrices here are at most 12 × 12.
pub(crate) fn solve_small(a: &mut [f64], n: usize, b: &mut [f64], nrhs: usize) {
    for col in 0..n {
        let mut piv = col;
        for r in col + 1..n {
            if a[r * n + col].abs() > a[piv * n + col].abs() {
                piv = r;
            }
        }
        if piv != col {
            for c in 0..n {
                a.swap(col * n + c, piv * n + c);
            }
            for c in 0..nrhs {
                b.swap(col * nrhs + c, piv * nrhs + c);
            }
        }
        let d = a[col * n + col];
        for r in col + 1..n {
            let f = a[r * n + col] / d;
            if f != 0.0 {
                for c in col..n {
                    a[r * n + c] -= f * a[col * n + c];
                }
                for c in 0..nrhs {
                    b[r * nrhs + c] -= f * b[col * nrhs + c];
                }
            }
        }
    }
    for col in (0..n).rev() {
        let d = a[col * n + col];
        for c in 0..nrhs {
            let mut s = b[col * nrhs + c];
            for k in col + 1..n {
                s -= a[col * n + k] * b[k * nrhs + c];
            }
            b[col * nrhs + c] = s / d;
        }
    }
}

/// Static condensation of the DOFs `drop` out of `k` (n × n) and the load `f`:
/// `k ← k_kk − k_kd k_dd⁻¹ k_dk`, `f ← f_k − k_kd k_dd⁻¹ f_d`; dropped rows/cols become zero.
pub(crate) fn condense_dofs(k: &mut [f64], n: usize, f: Option<&mut [f64]>, drop: &[usize]) {
    if drop.is_empty() {
        return;
    }
    let nd = drop.len();
    let keep: Vec<usize> = (0..n).filter(|i| !drop.contains(i)).collect();
    // X = k_dd⁻¹ [k_dk | f_d]
    let mut kdd = vec![0.0; nd * nd];
    for (a, &i) in drop.iter().enumerate() {
        for (b, &j) in drop.iter().enumerate() {
            kdd[a * nd + b] = k[i * n + j];
        }
    }
    let nrhs = n + 1;
    let mut x = vec![0.0; nd * nrhs];
    for (a, &i) in drop.iter().enumerate() {
        for j in 0..n {
            x[a * nrhs + j] = k[i * n + j];
        }
    }
    let have_f = f.is_some();
    let mut fv = f;
    if let Some(f) = fv.as_deref() {
        for (a, &i) in drop.iter().enumerate() {
            x[a * nrhs + n] = f[i];
        }
    }
    solve_small(&mut kdd, nd, &mut x, nrhs);
    let old = k.to_vec();
    for &i in &keep {
        for &j in &keep {
            let mut s = old[i * n + j];
            for (a, &d) in drop.iter().enumerate() {
                s -= old[i * n + d] * x[a * nrhs + j];
            }
            k[i * n + j] = s;
        }
        if have_f {
            let f = fv.as_deref_mut().unwrap();
            let mut s = f[i];
            for (a, &d) in drop.iter().enumerate() {
                s -= old[i * n + d] * x[a * nrhs + n];
            }
            f[i] = s;
        }
    }
    for &d in drop {
        for j in 0..n {
            k[d * n + j] = 0.0;
            k[j * n + d] = 0.0;
        }
        if let Some(f) = fv.as_deref_mut() {
            f[d] = 0.0;
        }
    }
}
