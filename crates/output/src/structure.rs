//! The structure picture: undeformed and deformed shape, bending moments, stresses in plane
//! elements, contact pairs by state and their forces.

use unilateral_analysis::{Analysis, PairState};
use unilateral_fem::{Element, Endpoint, Model, NodeId, Releases};

use crate::font::{self, Anchor};
use crate::svg::{self, num, Svg};
use crate::{ReportOptions, StressComponent};

/// Colour and name of a pair state (for symbols and legends).
pub fn state_style(s: PairState) -> (&'static str, &'static str) {
    match s {
        PairState::Open => ("#ffffff", "open"),
        PairState::Stick => ("#1f5fa8", "stick"),
        PairState::SlipPlus => ("#f29e0c", "slip+"),
        PairState::SlipMinus => ("#d62728", "slip−"),
    }
}

/// A "nice" number `1, 2, 5 × 10^k` not larger than `v`.
pub fn nice_floor(v: f64) -> f64 {
    if v.is_nan() || v <= 0.0 || !v.is_finite() {
        return 1.0;
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    let k = if m >= 5.0 {
        5.0
    } else if m >= 2.0 {
        2.0
    } else {
        1.0
    };
    k * 10f64.powf(e)
}

/// The corner nodes of a plane element (quadrilateral or triangle), in their order; none for
/// a line element.
fn plane_nodes(e: &Element) -> &[NodeId] {
    match e {
        Element::Plane { nodes, .. } => nodes,
        Element::Triangle { nodes, .. } => nodes,
        Element::Frame { .. } | Element::Bar { .. } => &[],
    }
}

fn stress_value(s: &[f64; 4], c: StressComponent) -> f64 {
    match c {
        StressComponent::Sxx => s[0],
        StressComponent::Syy => s[1],
        StressComponent::VonMises => unilateral_fem::von_mises(*s),
    }
}

struct View {
    xmin: f64,
    ymax: f64,
    k: f64,
    ox: f64,
    oy: f64,
}

impl View {
    fn p(&self, x: f64, y: f64) -> (f64, f64) {
        (
            self.ox + (x - self.xmin) * self.k,
            self.oy + (self.ymax - y) * self.k,
        )
    }
}

/// The shortest arrow drawn for a non-zero contact force, in pixels (with its 8 px head).
const MIN_ARROW: f64 = 14.0;

/// The SVG picture of the structure at the reported load.
pub fn structure_svg(model: &Model, a: &Analysis, options: &ReportOptions) -> String {
    let nodes = model.nodes();
    let res = a.results.as_ref();
    let zero = [0.0; 3];
    let disp = |i: usize| -> [f64; 3] {
        res.and_then(|r| r.displacements.get(i).copied())
            .unwrap_or(zero)
    };

    // model size and deformation scale
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for p in nodes {
        x0 = x0.min(p[0]);
        x1 = x1.max(p[0]);
        y0 = y0.min(p[1]);
        y1 = y1.max(p[1]);
    }
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let size = (x1 - x0).max(y1 - y0).max(1e-12);
    let umax = (0..nodes.len())
        .map(|i| disp(i)[0].hypot(disp(i)[1]))
        .fold(0.0f64, f64::max);
    let scale = if umax > 0.0 {
        nice_floor(0.08 * size / umax)
    } else {
        1.0
    };
    let def = |i: usize| -> [f64; 2] {
        let d = disp(i);
        [nodes[i][0] + scale * d[0], nodes[i][1] + scale * d[1]]
    };

    // contact forces
    let pairs = model.pairs();
    let sol = &a.solution;
    let normals = &a.condensed.normals;
    let tangents = &a.condensed.tangents;
    let force = |i: usize| -> [f64; 2] {
        match (sol.pairs.get(i), normals.get(i), tangents.get(i)) {
            (Some(r), Some(nv), Some(tv)) => {
                [r.x_n * nv[0] + r.x_t * tv[0], r.x_n * nv[1] + r.x_t * tv[1]]
            }
            _ => [0.0, 0.0],
        }
    };
    let fmax = (0..pairs.len())
        .map(|i| force(i)[0].hypot(force(i)[1]))
        .fold(0.0f64, f64::max);
    let arrow_world = 0.12 * size;
    let kf = if fmax > 0.0 { arrow_world / fmax } else { 0.0 };
    let pair_at = |i: usize| -> [f64; 2] {
        let b = def(pairs[i].b.0);
        match pairs[i].a {
            Endpoint::Node(an) => {
                // The A point: the node, or its place on the segment of a node-to-segment pair.
                let q = match pairs[i].segment {
                    Some((a2, xi)) => {
                        let (q1, q2) = (def(an.0), def(a2.0));
                        [
                            (1.0 - xi) * q1[0] + xi * q2[0],
                            (1.0 - xi) * q1[1] + xi * q2[1],
                        ]
                    }
                    None => def(an.0),
                };
                [(b[0] + q[0]) / 2.0, (b[1] + q[1]) / 2.0]
            }
            Endpoint::Ground => b,
        }
    };

    // moments
    let lines: Vec<_> = res.map(|r| r.lines.clone()).unwrap_or_default();
    let is_frame = |e: usize| matches!(model.elements().get(e), Some(Element::Frame { .. }));
    let mmax = lines
        .iter()
        .filter(|l| is_frame(l.element.0))
        .flat_map(|l| l.diagram.iter().map(|d| d.m.abs()))
        .fold(0.0f64, f64::max);
    let km = if options.moments && mmax > 0.0 {
        0.1 * size / mmax
    } else {
        0.0
    };

    // extent of everything drawn
    let (mut bx0, mut bx1, mut by0, mut by1) = (x0, x1, y0, y1);
    let mut grow = |p: [f64; 2]| {
        bx0 = bx0.min(p[0]);
        bx1 = bx1.max(p[0]);
        by0 = by0.min(p[1]);
        by1 = by1.max(p[1]);
    };
    for i in 0..nodes.len() {
        grow(def(i));
    }
    for i in 0..pairs.len() {
        let p = pair_at(i);
        let f = force(i);
        grow([p[0] - kf * f[0], p[1] - kf * f[1]]);
    }
    if km > 0.0 {
        grow([x0, y0 - 0.1 * size]);
        grow([x1, y1 + 0.1 * size]);
    }
    let pad = 0.06 * size;
    let (bx0, bx1, by0, by1) = (bx0 - pad, bx1 + pad, by0 - pad, by1 + pad);

    let planes_exist = model
        .elements()
        .iter()
        .any(|e| matches!(e, Element::Plane { .. } | Element::Triangle { .. }));
    let draw_w = 760.0;
    let draw_h_max = 620.0;
    let k = (draw_w / (bx1 - bx0)).min(draw_h_max / (by1 - by0));
    let dw = (bx1 - bx0) * k;
    let dh = ((by1 - by0) * k).max(160.0);
    let header = 76.0;
    let bar_w = if planes_exist { 110.0 } else { 0.0 };
    let width = (dw + 40.0 + bar_w).max(640.0);
    let height = header + dh + 70.0;
    let view = View {
        xmin: bx0,
        ymax: by1 + (dh / k - (by1 - by0)) / 2.0,
        k,
        ox: 20.0 + (width - bar_w - 40.0 - dw) / 2.0,
        oy: header,
    };
    let title = "Structure at the reported load";
    let mut g = Svg::new(width, height, title);
    let pstr = sol.p.map(num).unwrap_or_else(|| "none".into());
    g.text(
        &format!("Deformed structure, contact states and contact forces at p = {pstr}"),
        20.0,
        24.0,
        13.0,
        Anchor::Start,
        "#111111",
    );
    let mut info = format!(
        "Grey: undeformed. Deformation scale × {}  (largest displacement {}).",
        num(scale),
        num(umax)
    );
    if fmax > 0.0 {
        info.push_str(&format!(" Longest arrow: contact force {}.", num(fmax)));
    }
    g.text(&info, 20.0, 42.0, 9.0, Anchor::Start, "#333333");
    if km > 0.0 {
        g.text(
            &format!(
                "Bending moment drawn on the tension side; largest |M| = {}.",
                num(mmax)
            ),
            20.0,
            56.0,
            9.0,
            Anchor::Start,
            "#333333",
        );
    }
    if res.is_none() {
        g.text(
            "no solution at the reported load: only the undeformed model is drawn",
            20.0,
            56.0,
            9.0,
            Anchor::Start,
            "#b3261e",
        );
    }

    // plane stresses
    let comp = options.stress;
    let mut cell: Vec<(usize, f64)> = Vec::new();
    if let Some(r) = res {
        for pl in &r.planes {
            let v = pl.stress.iter().map(|s| stress_value(s, comp)).sum::<f64>() / 4.0;
            cell.push((pl.element.0, v));
        }
    }
    let (smin, smax) = cell
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &(_, v)| {
            (a.min(v), b.max(v))
        });
    let (clo, chi) = match comp {
        StressComponent::VonMises => (0.0, smax.max(1e-300)),
        _ => {
            let m = smin.abs().max(smax.abs()).max(1e-300);
            (-m, m)
        }
    };
    let color = |v: f64| {
        let t = (v - clo) / (chi - clo);
        match comp {
            StressComponent::VonMises => svg::sequential(t),
            _ => svg::diverging(t),
        }
    };

    // undeformed, light grey
    for e in model.elements() {
        match e {
            Element::Frame { nodes: n, .. } | Element::Bar { nodes: n, .. } => {
                let (a0, b0) = (nodes[n[0].0], nodes[n[1].0]);
                g.line(
                    view.p(a0[0], a0[1]),
                    view.p(b0[0], b0[1]),
                    "#c8c8c8",
                    2.0,
                    r#" stroke-linecap="round""#,
                );
            }
            Element::Plane { .. } | Element::Triangle { .. } => {
                let pts: Vec<_> = plane_nodes(e)
                    .iter()
                    .map(|i| view.p(nodes[i.0][0], nodes[i.0][1]))
                    .collect();
                g.polygon(&pts, "none", "#d0d0d0", 0.6, "");
            }
        }
    }
    // deformed plane elements coloured by stress
    let cell_of = |ei: usize| cell.iter().find(|c| c.0 == ei).map(|c| c.1);
    for (ei, e) in model.elements().iter().enumerate() {
        if matches!(e, Element::Plane { .. } | Element::Triangle { .. }) {
            let pts: Vec<_> = plane_nodes(e)
                .iter()
                .map(|i| {
                    let d = def(i.0);
                    view.p(d[0], d[1])
                })
                .collect();
            let fill = cell_of(ei).map(color).unwrap_or_else(|| "#eeeeee".into());
            g.polygon(&pts, &fill, "#555555", 0.35, "");
        }
    }
    // moment diagrams on the undeformed axes
    if km > 0.0 {
        for l in &lines {
            let Some(Element::Frame { nodes: n, .. }) = model.elements().get(l.element.0) else {
                continue;
            };
            let (p0, p1) = (nodes[n[0].0], nodes[n[1].0]);
            let len = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
            if len <= 0.0 {
                continue;
            }
            let e = [(p1[0] - p0[0]) / len, (p1[1] - p0[1]) / len];
            let yl = [-e[1], e[0]];
            let mut pts = Vec::new();
            for d in &l.diagram {
                let b = [p0[0] + e[0] * d.s, p0[1] + e[1] * d.s];
                pts.push(view.p(b[0] - yl[0] * d.m * km, b[1] - yl[1] * d.m * km));
            }
            let mut poly = pts.clone();
            poly.push(view.p(p1[0], p1[1]));
            poly.push(view.p(p0[0], p0[1]));
            g.polygon(&poly, "#7b3fa0", "none", 0.0, r#" fill-opacity="0.18""#);
            g.polyline(&pts, "#7b3fa0", 1.0, "");
            if let Some(d) = l
                .diagram
                .iter()
                .max_by(|a, b| a.m.abs().total_cmp(&b.m.abs()))
            {
                if d.m.abs() >= 0.999 * mmax {
                    let b = [p0[0] + e[0] * d.s, p0[1] + e[1] * d.s];
                    let q = view.p(b[0] - yl[0] * d.m * km, b[1] - yl[1] * d.m * km);
                    let o = view.p(b[0], b[1]);
                    let (dx, dy) = (q.0 - o.0, q.1 - o.1);
                    let l = dx.hypot(dy).max(1e-9);
                    let (tx, ty) = (q.0 + 14.0 * dx / l, q.1 + 14.0 * dy / l + 3.5);
                    g.text(
                        &format!("M = {}", num(d.m)),
                        tx,
                        ty,
                        8.5,
                        Anchor::Middle,
                        "#5b2a7a",
                    );
                }
            }
        }
    }
    // deformed frames and bars
    for e in model.elements() {
        match e {
            Element::Frame {
                nodes: n, releases, ..
            } => {
                let pts = frame_curve(
                    nodes,
                    n[0].0,
                    n[1].0,
                    disp(n[0].0),
                    disp(n[1].0),
                    scale,
                    releases,
                );
                let px: Vec<_> = pts.iter().map(|p| view.p(p[0], p[1])).collect();
                g.polyline(&px, "#1a1a1a", 2.4, r#" stroke-linecap="round""#);
            }
            Element::Bar { nodes: n, .. } => {
                let (a0, b0) = (def(n[0].0), def(n[1].0));
                g.line(
                    view.p(a0[0], a0[1]),
                    view.p(b0[0], b0[1]),
                    "#1a1a1a",
                    1.4,
                    "",
                );
            }
            Element::Plane { .. } | Element::Triangle { .. } => {}
        }
    }
    // contact forces and pair symbols
    let off = 7.0; // pixels, along the normal into side B, so that the two sides of a wall separate
    for (i, spec) in pairs.iter().enumerate() {
        let _ = spec;
        let p = pair_at(i);
        let nv = normals.get(i).copied().unwrap_or([0.0, 1.0]);
        let tv = tangents.get(i).copied().unwrap_or([1.0, 0.0]);
        let c = view.p(p[0], p[1]);
        let c = (c.0 + off * nv[0], c.1 - off * nv[1]);
        let f = force(i);
        if kf > 0.0 && f[0].hypot(f[1]) > 1e-9 * fmax {
            let (dx, dy) = (kf * k * f[0], -kf * k * f[1]);
            // A force far smaller than the largest still shows as an arrow: never shorter
            // than MIN_ARROW pixels (the legend says so).
            let l0 = dx.hypot(dy);
            let (dx, dy) = if l0 < MIN_ARROW {
                (dx * MIN_ARROW / l0, dy * MIN_ARROW / l0)
            } else {
                (dx, dy)
            };
            let l = dx.hypot(dy);
            let tip = (c.0 - 7.0 * dx / l, c.1 - 7.0 * dy / l); // stop at the symbol's edge
            g.arrow((tip.0 - dx, tip.1 - dy), tip, "#2e7d32", 1.6, 8.0);
        }
        let state = sol
            .pairs
            .get(i)
            .map(|r| r.state)
            .unwrap_or(PairState::Stick);
        symbol(&mut g, c, state, (tv[0], -tv[1]));
    }

    // legend
    let ly = header + dh + 26.0;
    let mut x = 24.0;
    for s in [
        PairState::Open,
        PairState::Stick,
        PairState::SlipPlus,
        PairState::SlipMinus,
    ] {
        symbol(&mut g, (x, ly - 4.0), s, (1.0, 0.0));
        let lab = state_style(s).1;
        g.text(lab, x + 10.0, ly, 9.0, Anchor::Start, "#222222");
        x += 22.0 + font::width(lab, 9.0);
    }
    g.arrow((x, ly - 4.0), (x + 26.0, ly - 4.0), "#2e7d32", 1.6, 8.0);
    g.text(
        &format!("contact force on side B (drawn at least {MIN_ARROW} px long)"),
        x + 32.0,
        ly,
        9.0,
        Anchor::Start,
        "#222222",
    );
    g.text(
        "slip triangles point in the direction of the slip of side B (+t or −t); symbols are moved slightly along the normal into side B",
        24.0,
        ly + 18.0,
        8.0,
        Anchor::Start,
        "#555555",
    );

    // colour bar
    if planes_exist && !cell.is_empty() {
        let bx = width - bar_w + 10.0;
        let (by, bh) = (header + 20.0, (dh - 40.0).clamp(120.0, 400.0));
        let steps = 48;
        for j in 0..steps {
            let t0 = j as f64 / steps as f64;
            let v = clo + (t0 + 0.5 / steps as f64) * (chi - clo);
            g.rect(
                bx,
                by + bh * (1.0 - t0 - 1.0 / steps as f64),
                16.0,
                bh / steps as f64 + 0.4,
                &color(v),
                "none",
                0.0,
            );
        }
        g.rect(bx, by, 16.0, bh, "none", "#444444", 0.7);
        for t in svg::ticks(clo, chi, 5) {
            let y = by + bh * (1.0 - (t - clo) / (chi - clo));
            g.line((bx + 16.0, y), (bx + 20.0, y), "#444444", 0.7, "");
            g.text(&num(t), bx + 23.0, y + 3.5, 8.0, Anchor::Start, "#333333");
        }
        let name = match comp {
            StressComponent::VonMises => "σ_{vM} (von Mises)",
            StressComponent::Sxx => "σ_{xx}",
            StressComponent::Syy => "σ_{yy}",
        };
        g.math(name, bx - 4.0, by - 8.0, 9.0, Anchor::Start, "#222222");
        g.text(
            "element mean",
            bx - 4.0,
            by + bh + 16.0,
            8.0,
            Anchor::Start,
            "#555555",
        );
    }
    g.finish()
}

fn symbol(g: &mut Svg, c: (f64, f64), s: PairState, t: (f64, f64)) {
    let (fill, _) = state_style(s);
    let r = 4.5;
    match s {
        PairState::Open => g.circle(c, r, fill, "#333333", 1.2),
        PairState::Stick => g.rect(c.0 - r, c.1 - r, 2.0 * r, 2.0 * r, fill, "#111111", 0.8),
        PairState::SlipPlus | PairState::SlipMinus => {
            let sg = if s == PairState::SlipPlus { 1.0 } else { -1.0 };
            let (dx, dy) = (sg * t.0, sg * t.1);
            let rr = r * 1.35;
            let pts = [
                (c.0 + dx * rr, c.1 + dy * rr),
                (
                    c.0 - dx * rr * 0.7 - dy * rr * 0.8,
                    c.1 - dy * rr * 0.7 + dx * rr * 0.8,
                ),
                (
                    c.0 - dx * rr * 0.7 + dy * rr * 0.8,
                    c.1 - dy * rr * 0.7 - dx * rr * 0.8,
                ),
            ];
            g.polygon(&pts, fill, "#111111", 0.8, "");
        }
    }
}

/// Points of a deformed frame element (cubic Hermite transverse, linear axial).
fn frame_curve(
    nodes: &[[f64; 2]],
    i: usize,
    j: usize,
    di: [f64; 3],
    dj: [f64; 3],
    scale: f64,
    rel: &Releases,
) -> Vec<[f64; 2]> {
    let (p0, p1) = (nodes[i], nodes[j]);
    let len = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
    if len <= 0.0 {
        return vec![p0, p1];
    }
    let e = [(p1[0] - p0[0]) / len, (p1[1] - p0[1]) / len];
    let nrm = [-e[1], e[0]];
    let (u1, v1) = (di[0] * e[0] + di[1] * e[1], di[0] * nrm[0] + di[1] * nrm[1]);
    let (u2, v2) = (dj[0] * e[0] + dj[1] * e[1], dj[0] * nrm[0] + dj[1] * nrm[1]);
    let chord = (v2 - v1) / len;
    let t1 = if rel.start { chord } else { di[2] };
    let t2 = if rel.end { chord } else { dj[2] };
    let n = 16;
    (0..=n)
        .map(|k| {
            let x = k as f64 / n as f64;
            let (x2, x3) = (x * x, x * x * x);
            let v = (1.0 - 3.0 * x2 + 2.0 * x3) * v1
                + (x - 2.0 * x2 + x3) * len * t1
                + (3.0 * x2 - 2.0 * x3) * v2
                + (x3 - x2) * len * t2;
            let u = (1.0 - x) * u1 + x * u2;
            let s = x * len;
            [
                p0[0] + e[0] * (s + scale * u) + nrm[0] * scale * v,
                p0[1] + e[1] * (s + scale * u) + nrm[1] * scale * v,
            ]
        })
        .collect()
}
