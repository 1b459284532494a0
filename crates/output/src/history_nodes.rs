//! The load–displacement curves of chosen nodes over a load history of a structural model: the
//! factor of one load case against the node's displacement `ux` and `uy`, through the unloaded
//! start, every change of the working scheme and every stage end, in order (the evolution is
//! linear between them, so the polyline is the exact curve). A cyclic history that dissipates
//! shows as a loop.

use unilateral_analysis::HistoryAnalysis;

use crate::font::Anchor;
use crate::history::pseudo_time;
use crate::svg::{nice_range, num, ticks, Svg};
use crate::NonFiniteOutput;

/// One point of a node's curve: the pseudo-time, the case factor, and `(ux, uy)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodePoint {
    /// `stage − 1 + s`.
    pub t: f64,
    /// The factor of the charted case.
    pub factor: f64,
    /// The node's displacement `(ux, uy)`.
    pub u: [f64; 2],
}

/// The curves of the nodes `nodes` (0-based indices) against the factor of case `case`: one
/// list of points per node, recovered at every breakpoint of the history
/// ([`HistoryAnalysis::results_at`]).
pub fn node_curves(
    a: &HistoryAnalysis,
    nodes: &[usize],
    case: usize,
) -> Result<Vec<Vec<NodePoint>>, String> {
    let mut out = vec![
        vec![NodePoint {
            t: 0.0,
            factor: 0.0,
            u: [0.0; 2]
        }];
        nodes.len()
    ];
    // A failed stage's states are where the engine went before it stopped, not the
    // structure's: the curves end with the last stage that has states.
    for st in a
        .history
        .stages
        .iter()
        .take_while(|st| st.status.has_states())
    {
        // The steps inside the stage, then its end (a step at the end of a stage that stops
        // early — a mechanism — may carry its `s` a rounding above `s_end`).
        let mut marks: Vec<f64> = st
            .steps
            .iter()
            .map(|p| p.s)
            .filter(|&s| s > 0.0 && s < st.s_end)
            .collect();
        marks.push(st.s_end);
        marks.dedup();
        for s in marks {
            let (_, r) = a.results_at(st.stage, s).map_err(|e| e.to_string())?;
            let factor =
                st.factors_start[case] + s * (st.factors_end[case] - st.factors_start[case]);
            for (curve, &n) in out.iter_mut().zip(nodes) {
                let d = r.displacements.get(n).ok_or("node out of range")?;
                curve.push(NodePoint {
                    t: pseudo_time(st.stage, s),
                    factor,
                    u: [d[0], d[1]],
                });
            }
        }
    }
    Ok(out)
}

/// The picture of [`node_curves`]: one panel per node, the case factor against `ux` (blue) and
/// `uy` (orange), the start marked.
pub fn node_curves_svg(
    names: &[String],
    case: &str,
    curves: &[Vec<NodePoint>],
) -> Result<String, NonFiniteOutput> {
    for (name, c) in names.iter().zip(curves) {
        for (k, p) in c.iter().enumerate() {
            for (what, v) in [("factor", p.factor), ("ux", p.u[0]), ("uy", p.u[1])] {
                crate::finite::finite(v, || format!("node {name} point {}: {what}", k + 1))?;
            }
        }
    }
    let cols = curves.len().clamp(1, 3);
    let rows = curves.len().div_ceil(cols).max(1);
    let (pw, ph) = (380.0, 300.0);
    let (w, h) = (cols as f64 * pw + 40.0, rows as f64 * ph + 90.0);
    let mut svg = Svg::new(
        w,
        h,
        &format!("Load history: factor of {case} against node displacements"),
    );
    svg.text(
        &format!("Load history: the factor of {case} against node displacements"),
        20.0,
        30.0,
        16.0,
        Anchor::Start,
        "#222",
    );
    svg.text(
        "every breakpoint in order (the exact path); blue: ux, orange: uy; ring: the unloaded start",
        20.0,
        52.0,
        11.0,
        Anchor::Start,
        "#444",
    );
    for (k, (name, c)) in names.iter().zip(curves).enumerate() {
        let (x0, y0) = (
            20.0 + (k % cols) as f64 * pw + 60.0,
            80.0 + (k / cols) as f64 * ph,
        );
        let (iw, ih) = (pw - 90.0, ph - 80.0);
        let (ulo, uhi) = c.iter().fold((0.0f64, 0.0f64), |(lo, hi), p| {
            (lo.min(p.u[0]).min(p.u[1]), hi.max(p.u[0]).max(p.u[1]))
        });
        let (flo, fhi) = c.iter().fold((0.0f64, 0.0f64), |(lo, hi), p| {
            (lo.min(p.factor), hi.max(p.factor))
        });
        let (ulo, uhi) = nice_range(ulo, if uhi > ulo { uhi } else { ulo + 1.0 });
        let (flo, fhi) = nice_range(flo, if fhi > flo { fhi } else { flo + 1.0 });
        let px = |u: f64| x0 + (u - ulo) / (uhi - ulo) * iw;
        let py = |f: f64| y0 + ih - (f - flo) / (fhi - flo) * ih;
        svg.rect(x0, y0, iw, ih, "none", "#bbb", 1.0);
        for t in ticks(ulo, uhi, 5) {
            svg.line((px(t), y0 + ih), (px(t), y0 + ih + 4.0), "#666", 1.0, "");
            svg.text(&num(t), px(t), y0 + ih + 16.0, 9.0, Anchor::Middle, "#444");
        }
        for t in ticks(flo, fhi, 5) {
            svg.line((x0 - 4.0, py(t)), (x0, py(t)), "#666", 1.0, "");
            svg.text(&num(t), x0 - 6.0, py(t) + 3.0, 9.0, Anchor::End, "#444");
        }
        svg.text(
            &format!("node {name}"),
            x0,
            y0 - 8.0,
            12.0,
            Anchor::Start,
            "#222",
        );
        svg.text(
            "displacement",
            x0 + iw / 2.0,
            y0 + ih + 32.0,
            10.0,
            Anchor::Middle,
            "#444",
        );
        svg.text_full(
            case,
            x0 - 42.0,
            y0 + ih / 2.0,
            10.0,
            Anchor::Middle,
            90.0,
            "#444",
            false,
        );
        for (comp, color) in [(0usize, "#1f77b4"), (1, "#ff7f0e")] {
            let pts: Vec<(f64, f64)> = c.iter().map(|p| (px(p.u[comp]), py(p.factor))).collect();
            svg.polyline(&pts, color, 1.6, "");
            for &q in &pts {
                svg.circle(q, 1.8, color, "none", 0.0);
            }
        }
        if let Some(p) = c.first() {
            svg.circle((px(p.u[0]), py(p.factor)), 4.0, "none", "#222", 1.2);
        }
    }
    Ok(svg.finish())
}
