//! Generated contact zones for benchmarks and tests.

use faer::Mat;

use crate::ContactZone;

/// A small deterministic pseudo-random generator (no external dependency, reproducible).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64)
    }
}

/// Solves the symmetric tridiagonal system `(a diag, b off-diagonal) x = r` in place (Thomas).
fn tridiagonal_solve(diag: &[f64], off: &[f64], r: &mut [f64]) {
    let n = diag.len();
    let mut c = vec![0.0; n];
    let mut d = diag[0];
    r[0] /= d;
    for i in 1..n {
        c[i - 1] = off[i - 1] / d;
        d = diag[i] - off[i - 1] * c[i - 1];
        r[i] = (r[i] - off[i - 1] * r[i - 1]) / d;
    }
    for i in (0..n - 1).rev() {
        r[i] -= c[i] * r[i + 1];
    }
}

/// A continuous beam on `m` unilateral frictional supports (spans 1, `EI = 1`, `EA = 100`,
/// friction 0.3), pressed by a constant uniform weight and loaded by a variable set of
/// up/down point loads at mid-span and sideways nodal forces (deterministic from `seed`), so
/// that a good share of the pairs open, close or slip as `p` grows.
///
/// The contact zone is exact for this beam: `Rnn` is the beam's bending stiffness condensed to
/// the support deflections (rotations eliminated), `Rtt` its axial stiffness, and the load vectors
/// are the support reactions of the bonded beam (compression positive).
#[allow(clippy::needless_range_loop)] // index loops mirror the assembly formulas
pub fn beam_on_supports(m: usize, seed: u64) -> ContactZone {
    assert!(m >= 2, "a beam needs two supports");
    let (l, ei, ea) = (1.0f64, 1.0f64, 100.0f64);
    let k = ei / (l * l * l);
    // Bending stiffness blocks over (v, θ) of the nodes; element e joins nodes e and e+1.
    let mut kvv = vec![[0.0f64; 3]; m]; // (sub, diag, super) per row
    let mut kvt = vec![[0.0f64; 3]; m];
    let mut ktt_diag = vec![0.0f64; m];
    let mut ktt_off = vec![0.0f64; m - 1];
    for e in 0..m - 1 {
        let (a, b) = (e, e + 1);
        kvv[a][1] += 12.0 * k;
        kvv[b][1] += 12.0 * k;
        kvv[a][2] -= 12.0 * k;
        kvv[b][0] -= 12.0 * k;
        kvt[a][1] += 6.0 * k * l;
        kvt[a][2] += 6.0 * k * l;
        kvt[b][0] -= 6.0 * k * l;
        kvt[b][1] -= 6.0 * k * l;
        ktt_diag[a] += 4.0 * k * l * l;
        ktt_diag[b] += 4.0 * k * l * l;
        ktt_off[e] += 2.0 * k * l * l;
    }
    // K_θv = K_vθᵀ: column j of K_θv has entries at rows j-1, j, j+1.
    let kvt_at = |i: usize, j: usize| -> f64 {
        if j + 1 == i {
            kvt[i][0]
        } else if i == j {
            kvt[i][1]
        } else if i + 1 == j {
            kvt[i][2]
        } else {
            0.0
        }
    };
    let mut rnn = Mat::<f64>::zeros(m, m);
    let mut x = vec![0.0; m];
    for j in 0..m {
        for (i, xi) in x.iter_mut().enumerate() {
            *xi = kvt_at(j, i); // (K_θv)[i][j] = (K_vθ)[j][i]
        }
        tridiagonal_solve(&ktt_diag, &ktt_off, &mut x);
        for i in 0..m {
            let lo = i.saturating_sub(1);
            let hi = (i + 1).min(m - 1);
            let mut s = 0.0;
            for (t, xt) in x.iter().enumerate().take(hi + 1).skip(lo) {
                s += kvt_at(i, t) * xt;
            }
            let kv = if j + 1 == i {
                kvv[i][0]
            } else if i == j {
                kvv[i][1]
            } else if i + 1 == j {
                kvv[i][2]
            } else {
                0.0
            };
            rnn[(i, j)] = kv - s;
        }
    }
    // Symmetrise the round-off.
    for j in 0..m {
        for i in 0..j {
            let v = 0.5 * (rnn[(i, j)] + rnn[(j, i)]);
            rnn[(i, j)] = v;
            rnn[(j, i)] = v;
        }
    }
    let ka = ea / l;
    let rtt = Mat::<f64>::from_fn(m, m, |i, j| {
        if i == j {
            if i == 0 || i == m - 1 {
                ka
            } else {
                2.0 * ka
            }
        } else if i + 1 == j || j + 1 == i {
            -ka
        } else {
            0.0
        }
    });
    // Reactions of the bonded beam (v = u = 0) to element loads given as equivalent nodal loads.
    let reactions = |fv: &[f64], ft: &[f64]| -> Vec<f64> {
        let mut theta = ft.to_vec();
        tridiagonal_solve(&ktt_diag, &ktt_off, &mut theta);
        (0..m)
            .map(|i| {
                let lo = i.saturating_sub(1);
                let hi = (i + 1).min(m - 1);
                let s: f64 = (lo..=hi).map(|t| kvt_at(i, t) * theta[t]).sum();
                s - fv[i]
            })
            .collect()
    };
    // Constant: uniform weight w = 1 downward.
    let w = 1.0;
    let mut fv = vec![0.0; m];
    let mut ft = vec![0.0; m];
    for e in 0..m - 1 {
        fv[e] -= w * l / 2.0;
        fv[e + 1] -= w * l / 2.0;
        ft[e] -= w * l * l / 12.0;
        ft[e + 1] += w * l * l / 12.0;
    }
    let rc_n = reactions(&fv, &ft);
    // Variable: mid-span point loads, mostly down, some up; sideways nodal forces.
    let mut rng = Lcg(seed.wrapping_mul(2654435761).wrapping_add(12345));
    let mut fv = vec![0.0; m];
    let mut ft = vec![0.0; m];
    for e in 0..m - 1 {
        let pdown = 3.0 * (rng.next() * 2.5 - 1.0); // in [-3, 4.5]: negative lifts
        fv[e] -= pdown / 2.0;
        fv[e + 1] -= pdown / 2.0;
        ft[e] -= pdown * l / 8.0;
        ft[e + 1] += pdown * l / 8.0;
    }
    let rv_n = reactions(&fv, &ft);
    let mut rv_t: Vec<f64> = (0..m).map(|_| rng.next() - 0.5).collect();
    let mean = rv_t.iter().sum::<f64>() / m as f64;
    rv_t.iter_mut().for_each(|v| *v -= mean);
    let mut zone = ContactZone::new(rnn, rtt);
    zone.friction = vec![0.3; m];
    zone.constant.normal = rc_n;
    zone.variable.normal = rv_n;
    zone.variable.tangential = rv_t;
    zone
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three supports with spans 1: the condensed stiffness is `3EI/(2L³)·[1,−2,1]ᵀ[1,−2,1]`
    /// (a two-span beam has one redundant support), the paper's Example 1 matrix scaled by 8.
    #[test]
    fn three_supports_match_the_closed_form() {
        let z = beam_on_supports(3, 1);
        let v = [1.0, -2.0, 1.0];
        for i in 0..3 {
            for j in 0..3 {
                assert!((z.rnn[(i, j)] - 1.5 * v[i] * v[j]).abs() < 1e-12);
            }
        }
        // Uniform weight on two spans: reactions 3/8, 10/8, 3/8 (w·L = 1).
        let r = [0.375, 1.25, 0.375];
        for (got, want) in z.constant.normal.iter().zip(r) {
            assert!((got - want).abs() < 1e-12);
        }
    }
}
