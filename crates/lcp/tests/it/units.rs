//! The engine's answer may not depend on the units of the data: every tolerance is relative to
//! the quantity it meets (`M`, `q0` and `d` each on its own scale).

use faer::Mat;
use unilateral_lcp::{follow_path, Follow, ParametricLcp, PathOptions, PathStatus, Settings};

/// The contact LCP (`x = [x_n; x_t+; x_t-]`) of a two-node slider: `Rnn = 0`, `Rtt = k·[[1, −1],
/// [−1, 1]]`, friction `f = 1/2`, pressed by `W` per node, pulled at node 2 by `(W/12)·p`.
/// Hand analysis: pair 2 slips at `p = f·W/H = 6`, pair 1 at `p = 2·f·W/H = 12`, then a mechanism
/// at `p_lim = 12`. Built directly in the engine's terms, with no normalisation in front.
fn slider(k: f64, w: f64) -> ParametricLcp {
    let f = 0.5;
    let rtt = [[k, -k], [-k, k]];
    let mut m = Mat::<f64>::zeros(6, 6);
    for i in 0..2 {
        for j in 0..2 {
            let t = rtt[i][j] / 2.0;
            m[(2 + i, 2 + j)] = t;
            m[(2 + i, 4 + j)] = -t;
            m[(4 + i, 2 + j)] = -t;
            m[(4 + i, 4 + j)] = t;
        }
    }
    let h = w / 12.0;
    ParametricLcp {
        m,
        q0: vec![w, w, f * w, f * w, f * w, f * w],
        d: vec![0.0, 0.0, 0.0, h, 0.0, -h],
    }
}

#[test]
fn the_slider_in_raw_units() {
    let settings = Settings {
        lexicographic_order: Some(vec![2, 3, 4, 5, 0, 1]),
        ..Settings::default()
    };
    let options = PathOptions {
        target: 20.0,
        follow: Follow::ToEnd,
        tightening: None,
    };
    for k in [2e-3, 2e9, 2e150] {
        for w in [1e-150, 3e-20, 0.01, 1.0, 1e20, 1e30, 1e150] {
            let path = follow_path(&slider(k, w), &options, &settings).unwrap();
            let ps: Vec<f64> = path.steps.iter().map(|s| s.p).collect();
            assert_eq!(
                path.status,
                PathStatus::Mechanism,
                "k = {k}, W = {w}: {ps:?}"
            );
            assert_eq!(ps.len(), 2, "k = {k}, W = {w}: {ps:?}");
            assert!(
                (ps[0] - 6.0).abs() <= 1e-12 * 6.0,
                "k = {k}, W = {w}: {ps:?}"
            );
            assert!(
                (ps[1] - 12.0).abs() <= 1e-12 * 12.0,
                "k = {k}, W = {w}: {ps:?}"
            );
            let p_lim = path.p_limit.unwrap();
            assert!((p_lim - 12.0).abs() <= 1e-12 * 12.0, "k = {k}, W = {w}");
            let sol = path.solution.expect("a verified solution at p_lim");
            assert!(sol.residual.max() <= 1e-9);
            assert!(sol.x.iter().chain(&sol.z).all(|v| v.is_finite()));
        }
    }
}

mod random {
    use super::*;
    use proptest::prelude::*;
    use unilateral_lcp::Tightening;

    /// The contact LCP of a random zone: `R = B Bᵀ + I/4` (positive definite), friction per
    /// pair, constant and variable loads; `M`, `q0`, `d` as in the formulation (§3).
    fn contact(
        m: usize,
        b: &[i32],
        f: &[f64],
        loads: &[i32],
    ) -> (ParametricLcp, Vec<f64>, Vec<usize>) {
        let k = 2 * m;
        let bm = |i: usize, j: usize| b[i * 6 + j] as f64 / 4.0;
        let r = Mat::<f64>::from_fn(k, k, |i, j| {
            (0..k).map(|l| bm(i, l) * bm(j, l)).sum::<f64>() + if i == j { 0.25 } else { 0.0 }
        });
        let n = 3 * m;
        let mut mm = Mat::<f64>::zeros(n, n);
        for i in 0..m {
            for j in 0..m {
                let (nn, nt, tn, tt) = (r[(i, j)], r[(i, m + j)], r[(m + i, j)], r[(m + i, m + j)]);
                mm[(i, j)] = nn;
                mm[(i, m + j)] = nt / 2.0;
                mm[(i, 2 * m + j)] = -nt / 2.0;
                mm[(m + i, j)] = f[i] * nn + tn;
                mm[(m + i, m + j)] = (f[i] * nt + tt) / 2.0;
                mm[(m + i, 2 * m + j)] = -(f[i] * nt + tt) / 2.0;
                mm[(2 * m + i, j)] = f[i] * nn - tn;
                mm[(2 * m + i, m + j)] = (f[i] * nt - tt) / 2.0;
                mm[(2 * m + i, 2 * m + j)] = -(f[i] * nt - tt) / 2.0;
            }
        }
        let l = |i: usize| loads[i] as f64 / 4.0;
        let stack = |off: usize| {
            let mut v: Vec<f64> = (0..m).map(|i| l(off + i)).collect();
            v.extend((0..m).map(|i| f[i] * l(off + i) + l(off + 3 + i)));
            v.extend((0..m).map(|i| f[i] * l(off + i) - l(off + 3 + i)));
            v
        };
        let mut dir = vec![1.0; n];
        for i in 0..m {
            dir[m + i] = f[i].max(1.0);
            dir[2 * m + i] = f[i].max(1.0);
        }
        let order = (m..n).chain(0..m).collect();
        (
            ParametricLcp {
                m: mm,
                q0: stack(0),
                d: stack(6),
            },
            dir,
            order,
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

        /// Reference: dimensional analysis — `M → a·M`, `q0, d, c → b·(q0, d, c)` maps solutions
        /// `(x, z)` at `p` to `(b·x, (b/a)·z)` at the same `p`: the same pivots at the same loads.
        #[test]
        fn the_path_does_not_depend_on_the_units(
            m in 1usize..=3,
            b in prop::collection::vec(-2i32..=2, 36),
            f in prop::collection::vec(0.0f64..2.0, 3),
            loads in prop::collection::vec(-8i32..=8, 12),
            c in prop::sample::select(vec![0.0, 0.1, 1.0]),
            ea in -12.0f64..12.0,
            eb in -12.0f64..12.0,
        ) {
            let (a, bf) = (10f64.powf(ea), 10f64.powf(eb));
            let (p1, dir, order) = contact(m, &b, &f, &loads);
            let p2 = ParametricLcp {
                m: Mat::from_fn(3 * m, 3 * m, |i, j| p1.m[(i, j)] * a),
                q0: p1.q0.iter().map(|v| v * bf).collect(),
                d: p1.d.iter().map(|v| v * bf).collect(),
            };
            let settings = Settings { lexicographic_order: Some(order), ..Settings::default() };
            let opts = |amount: f64| PathOptions {
                target: 2.0,
                follow: Follow::ToEnd,
                tightening: (amount > 0.0).then(|| Tightening { amount, direction: dir.clone() }),
            };
            let r1 = follow_path(&p1, &opts(c), &settings).unwrap();
            let r2 = follow_path(&p2, &opts(c * bf), &settings).unwrap();
            prop_assert_eq!(r1.status, r2.status);
            prop_assert_eq!(r1.steps.len(), r2.steps.len());
            for (s, t) in r1.steps.iter().zip(&r2.steps) {
                prop_assert_eq!((s.entering, s.leaving), (t.entering, t.leaving));
                // p is dimensionless; its scale is the target p* = O(1).
                prop_assert!((s.p - t.p).abs() <= 1e-9 * s.p.abs().max(1.0), "{} vs {}", s.p, t.p);
            }
            prop_assert_eq!(r1.solution.is_some(), r2.solution.is_some());
            if let (Some(s1), Some(s2)) = (&r1.solution, &r2.solution) {
                let xs = s1.x.iter().chain(&p1.q0).chain(&p1.d).fold(0.0f64, |u, v| u.max(v.abs()));
                let zs = s1.z.iter().fold(xs / 4.0, |u, v| u.max(v.abs()));
                for (u, v) in s1.x.iter().zip(&s2.x) {
                    prop_assert!((u * bf - v).abs() <= 1e-9 * xs * bf, "x: {} vs {}", u, v);
                }
                for (u, v) in s1.z.iter().zip(&s2.z) {
                    prop_assert!((u * bf / a - v).abs() <= 1e-9 * zs * bf / a, "z: {} vs {}", u, v);
                }
            }
        }
    }
}
