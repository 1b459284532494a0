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
