//! The structure picture: undeformed and deformed shape, bending moments, stresses in plane
//! elements, contact pairs by state and their forces, the pairs' names where they fit, the
//! supports and the loads.

use unilateral_analysis::{Analysis, PairState};
use unilateral_fem::{
    Element, Endpoint, Load, LoadFrame, Model, NodeId, Releases, Results, SupportDof,
};

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
    // Supports and load arrows have sizes in pixels: room for them beyond the model.
    let p_drawn = sol.p.unwrap_or(1.0);
    let loads = loads_at(model, p_drawn);
    let supports = res.map(supports_of).unwrap_or_default();
    let margin_px = if !loads.nodal.is_empty() || !loads.lines.is_empty() {
        LOAD_ARROW + 12.0
    } else if !supports.is_empty() {
        24.0
    } else {
        0.0
    };
    let (draw_w, draw_h_max) = (760.0, 620.0);
    let k0 = (draw_w / (bx1 - bx0 + 0.12 * size)).min(draw_h_max / (by1 - by0 + 0.12 * size));
    let pad = 0.06 * size + margin_px / k0;
    let (bx0, bx1, by0, by1) = (bx0 - pad, bx1 + pad, by0 - pad, by1 + pad);

    let planes_exist = model
        .elements()
        .iter()
        .any(|e| matches!(e, Element::Plane { .. } | Element::Triangle { .. }));
    let k = (draw_w / (bx1 - bx0)).min(draw_h_max / (by1 - by0));
    let dw = (bx1 - bx0) * k;
    let dh = ((by1 - by0) * k).max(160.0);
    let header = 76.0;
    let bar_w = if planes_exist { 110.0 } else { 0.0 };
    let width = (dw + 40.0 + bar_w).max(640.0);
    let legend_rows = if supports.is_empty()
        && loads.nodal.is_empty()
        && loads.lines.is_empty()
        && loads.body == 0
    {
        0.0
    } else {
        18.0
    };
    let height = header + dh + 70.0 + legend_rows + if pairs.is_empty() { 0.0 } else { 12.0 };
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
    // The file's force and length units after the values they measure.
    let about = crate::json::About {
        title: None,
        units: options.units.clone(),
    };
    let (fu, lu) = match about.force_length() {
        Some((f, l)) => (format!(" {f}"), format!(" {l}")),
        None => (String::new(), String::new()),
    };
    let mut info = format!(
        "Grey: undeformed. Deformation scale × {}  (largest displacement {}{lu}).",
        num(scale),
        num(umax)
    );
    if fmax > 0.0 {
        info.push_str(&format!(" Longest arrow: contact force {}{fu}.", num(fmax)));
    }
    g.text(&info, 20.0, 42.0, 9.0, Anchor::Start, "#333333");
    if km > 0.0 {
        g.text(
            &format!(
                "Bending moment drawn on the tension side; largest |M| = {}{}.",
                num(mmax),
                match about.force_length() {
                    Some((f, l)) => format!(" {f}·{l}"),
                    None => String::new(),
                }
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
    // Marks the pairs' names must not cover: frames and bars, arrows, symbols.
    let mut marks: Vec<(f64, f64)> = Vec::new();
    let mut boxes: Vec<[f64; 4]> = Vec::new();
    for e in model.elements() {
        if let Element::Frame { nodes: n, .. } | Element::Bar { nodes: n, .. } = e {
            let (a0, b0) = (def(n[0].0), def(n[1].0));
            marks.extend(samples_along(view.p(a0[0], a0[1]), view.p(b0[0], b0[1])));
        }
    }
    // supports: the ground side is away from the elements at the node
    for &(n, kind) in &supports {
        let d = def(n);
        let c = view.p(d[0], d[1]);
        let up = match kind {
            SupportKind::Roller { dir, .. } => {
                // the roller pushes along its restrained direction, from the side away from
                // the structure
                let away = away_from_elements(model, n);
                let sg = if dir[0] * away[0] + dir[1] * away[1] > 0.0 {
                    -1.0
                } else {
                    1.0
                };
                (sg * dir[0], -sg * dir[1])
            }
            _ => {
                let away = away_from_elements(model, n);
                (-away[0], away[1])
            }
        };
        g.raw(&format!("<g class=\"support {}\">", kind.name()));
        boxes.push(support_symbol(&mut g, c, kind, up));
        g.raw("</g>");
    }
    // loads at the drawn state, one scale for all nodal forces and one for distributed loads
    let fl_max = loads
        .nodal
        .iter()
        .map(|l| l.2[0].hypot(l.2[1]))
        .fold(0.0f64, f64::max);
    let wl_max = loads
        .lines
        .iter()
        .flat_map(|l| [l.2[0].hypot(l.2[1]), l.3[0].hypot(l.3[1])])
        .fold(0.0f64, f64::max);
    let ink = |constant: bool| if constant { CONSTANT_INK } else { VARIABLE_INK };
    let group = |constant: bool| if constant { "constant" } else { "variable" };
    for &(constant, e, w0, w1) in &loads.lines {
        let Some(Element::Frame { nodes: n, .. } | Element::Bar { nodes: n, .. }) =
            model.elements().get(e)
        else {
            continue;
        };
        let (a0, b0) = (def(n[0].0), def(n[1].0));
        let (pa, pb) = (view.p(a0[0], a0[1]), view.p(b0[0], b0[1]));
        // an arrow every 25 px or so, at the middles of equal parts (none twice at a node
        // shared by two loaded elements)
        let stations = ((pb.0 - pa.0).hypot(pb.1 - pa.1) / 25.0)
            .round()
            .clamp(1.0, 6.0) as usize;
        let mut tails = Vec::new();
        for j in 0..stations {
            let t = (j as f64 + 0.5) / stations as f64;
            let w = [w0[0] + t * (w1[0] - w0[0]), w0[1] + t * (w1[1] - w0[1])];
            let wl = w[0].hypot(w[1]);
            let c = (pa.0 + t * (pb.0 - pa.0), pa.1 + t * (pb.1 - pa.1));
            if wl <= 1e-12 * wl_max || wl_max <= 0.0 {
                tails.push(c);
                continue;
            }
            let len = (LINE_LOAD_ARROW * wl / wl_max).max(MIN_ARROW);
            let u = (w[0] / wl, -w[1] / wl);
            g.raw(&format!(
                "<g class=\"load {} distributed\">",
                group(constant)
            ));
            marks.extend(load_arrow(&mut g, c, u, len, 1.0, ink(constant)));
            g.raw("</g>");
            tails.push((c.0 - (len + 1.0) * u.0, c.1 - (len + 1.0) * u.1));
        }
        g.polyline(&tails, ink(constant), 0.9, "");
    }
    // contact forces and pair symbols
    let off = 7.0; // pixels, along the normal into side B, so that the two sides of a wall separate
    let mut labels: Vec<(String, (f64, f64))> = Vec::with_capacity(pairs.len());
    for i in 0..pairs.len() {
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
            marks.extend(samples_along((tip.0 - dx, tip.1 - dy), tip));
        }
        let state = sol
            .pairs
            .get(i)
            .map(|r| r.state)
            .unwrap_or(PairState::Stick);
        symbol(&mut g, c, state, (tv[0], -tv[1]));
        marks.extend([
            c,
            (c.0 - 4.5, c.1),
            (c.0 + 4.5, c.1),
            (c.0, c.1 - 4.5),
            (c.0, c.1 + 4.5),
        ]);
        labels.push((model.pair_name(i), c));
    }
    // nodal loads over the pair symbols (a force into a paired node had its head under the
    // node's symbol)
    for &(constant, n, f, m) in &loads.nodal {
        let d = def(n);
        let c = view.p(d[0], d[1]);
        let fl = f[0].hypot(f[1]);
        if fl > 1e-12 * fl_max && fl_max > 0.0 {
            let len = (LOAD_ARROW * fl / fl_max).max(MIN_ARROW);
            g.raw(&format!("<g class=\"load {} force\">", group(constant)));
            marks.extend(load_arrow(
                &mut g,
                c,
                (f[0] / fl, -f[1] / fl),
                len,
                3.0,
                ink(constant),
            ));
            g.raw("</g>");
        }
        if m != 0.0 {
            g.raw(&format!("<g class=\"load {} moment\">", group(constant)));
            marks.extend(moment_arrow(&mut g, c, m, ink(constant)));
            g.raw("</g>");
        }
    }
    let skipped = place_labels(
        &mut g,
        &labels,
        &marks,
        &boxes,
        [4.0, header, width - bar_w - 4.0, header + dh],
    );

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
    let mut note_y = ly + 18.0;
    if legend_rows > 0.0 {
        let y = ly + 20.0;
        let mut x = 24.0;
        let kinds = [
            (SupportKind::Clamped, "fixed"),
            (SupportKind::Pinned, "pinned"),
            (
                SupportKind::Roller {
                    dir: [0.0, 1.0],
                    rotation: false,
                },
                "roller",
            ),
        ];
        for (kind, name) in kinds {
            let present = supports
                .iter()
                .any(|s| std::mem::discriminant(&s.1) == std::mem::discriminant(&kind));
            if present {
                support_symbol(&mut g, (x + 8.0, y - 12.0), kind, (0.0, -1.0));
                g.text(name, x + 18.0, y, 9.0, Anchor::Start, "#222222");
                x += 30.0 + font::width(name, 9.0);
            }
        }
        for (constant, name) in [(true, "constant load"), (false, "variable load p·F")] {
            let present = loads.nodal.iter().any(|l| l.0 == constant)
                || loads.lines.iter().any(|l| l.0 == constant);
            if present {
                g.arrow((x, y - 4.0), (x + 24.0, y - 4.0), ink(constant), 1.5, 7.0);
                g.text(name, x + 30.0, y, 9.0, Anchor::Start, "#222222");
                x += 42.0 + font::width(name, 9.0);
            }
        }
        let mut scale = Vec::new();
        if fl_max > 0.0 {
            scale.push(format!("longest load arrow {}{fu}", num(fl_max)));
        }
        if wl_max > 0.0 {
            scale.push(match about.force_length() {
                Some((f, l)) => format!("distributed up to {} {f}/{l}", num(wl_max)),
                None => format!("distributed up to {} per length", num(wl_max)),
            });
        }
        if loads.body > 0 {
            scale.push(format!("body forces on {} elements not drawn", loads.body));
        }
        let pstr = sol.p.map(num).unwrap_or_else(|| "1".into());
        let note = if scale.is_empty() {
            String::new()
        } else {
            format!("at p = {pstr}: {}", scale.join("; "))
        };
        g.text(&note, x, y, 8.0, Anchor::Start, "#555555");
        note_y = y + 18.0;
    }
    g.text(
        "slip triangles point in the direction of the slip of side B (+t or −t); symbols are moved slightly along the normal into side B",
        24.0,
        note_y,
        8.0,
        Anchor::Start,
        "#555555",
    );
    if !pairs.is_empty() {
        let text = if skipped == 0 {
            "every pair labelled with its name".to_string()
        } else {
            format!(
                "{} of {} pair names left out where they would cover something or sit as near another pair (every pair by name in the tables)",
                skipped,
                pairs.len()
            )
        };
        g.text(&text, 24.0, note_y + 12.0, 8.0, Anchor::Start, "#555555");
    }

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
        // The unit on a line of its own: the bar sits at the picture's right edge.
        if let Some((f, l)) = about.force_length() {
            g.math(name, bx - 4.0, by - 20.0, 9.0, Anchor::Start, "#222222");
            g.text(
                &format!("[{f}/({l}·{l})]"),
                bx - 4.0,
                by - 8.0,
                9.0,
                Anchor::Start,
                "#222222",
            );
        } else {
            g.math(name, bx - 4.0, by - 8.0, 9.0, Anchor::Start, "#222222");
        }
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

/// The kind of support symbol of a node, from the DOFs its supports fix.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SupportKind {
    /// `ux`, `uy` and `rz` fixed: a clamp (a hatched block).
    Clamped,
    /// `ux` and `uy` fixed: a pin (a triangle on a hatched base).
    Pinned,
    /// One translation fixed (along `dir`, world components): a roller, with a small square
    /// when the rotation is held too.
    Roller { dir: [f64; 2], rotation: bool },
    /// Only the rotation held: a small square.
    Rotation,
}

/// The supports of the model, one symbol a node, from the reactions of the results (one per
/// prescribed DOF: the model's fixed DOFs).
fn supports_of(r: &Results) -> Vec<(usize, SupportKind)> {
    let mut per: Vec<(usize, Vec<SupportDof>)> = Vec::new();
    for x in &r.reactions {
        match per.iter_mut().find(|(n, _)| *n == x.node.0) {
            Some((_, v)) => v.push(x.dof),
            None => per.push((x.node.0, vec![x.dof])),
        }
    }
    per.into_iter()
        .map(|(n, dofs)| {
            let rot = dofs.iter().any(|d| matches!(d, SupportDof::Rz));
            let trans: Vec<[f64; 2]> = dofs
                .iter()
                .filter_map(|d| match d {
                    SupportDof::Ux => Some([1.0, 0.0]),
                    SupportDof::Uy => Some([0.0, 1.0]),
                    SupportDof::Along(v) => {
                        let l = v[0].hypot(v[1]);
                        (l > 0.0).then(|| [v[0] / l, v[1] / l])
                    }
                    SupportDof::Rz => None,
                })
                .collect();
            let kind = match (trans.len(), rot) {
                (0, _) => SupportKind::Rotation,
                (1, rotation) => SupportKind::Roller {
                    dir: trans[0],
                    rotation,
                },
                (_, true) => SupportKind::Clamped,
                (_, false) => SupportKind::Pinned,
            };
            (n, kind)
        })
        .collect()
}

impl SupportKind {
    /// The name of the symbol (in the legend and as the SVG group's class).
    fn name(self) -> &'static str {
        match self {
            SupportKind::Clamped => "fixed",
            SupportKind::Pinned => "pinned",
            SupportKind::Roller { .. } => "roller",
            SupportKind::Rotation => "rotation",
        }
    }
}

const SUPPORT_INK: &str = "#37474f";

/// Draws a support symbol at the node `c` (pixels); `up` is the unit direction (screen) from
/// the ground into the structure. Returns the box it covers.
fn support_symbol(g: &mut Svg, c: (f64, f64), kind: SupportKind, up: (f64, f64)) -> [f64; 4] {
    let s = 7.0;
    // across: perpendicular to `up`
    let (ux, uy) = up;
    let (ax, ay) = (-uy, ux);
    let at = |along: f64, across: f64| {
        (
            c.0 - ux * along + ax * across,
            c.1 - uy * along + ay * across,
        )
    };
    let hatch = |g: &mut Svg, base: f64, half: f64| {
        g.line(at(base, -half), at(base, half), SUPPORT_INK, 1.2, "");
        let n = 4;
        for k in 0..=n {
            let t = -half + 2.0 * half * k as f64 / n as f64;
            g.line(at(base, t), at(base + 3.5, t - 3.0), SUPPORT_INK, 0.7, "");
        }
    };
    match kind {
        SupportKind::Clamped => {
            let pts = [at(0.0, -s), at(0.0, s), at(5.0, s), at(5.0, -s)];
            g.polygon(&pts, "#cfd8dc", SUPPORT_INK, 1.0, "");
            hatch(g, 5.0, s);
        }
        SupportKind::Pinned => {
            g.polygon(
                &[c, at(s * 1.3, -s * 0.8), at(s * 1.3, s * 0.8)],
                "#eceff1",
                SUPPORT_INK,
                1.0,
                "",
            );
            hatch(g, s * 1.3, s);
        }
        SupportKind::Roller { rotation, .. } => {
            g.polygon(
                &[c, at(s * 1.2, -s * 0.75), at(s * 1.2, s * 0.75)],
                "#eceff1",
                SUPPORT_INK,
                1.0,
                "",
            );
            for t in [-0.45 * s, 0.45 * s] {
                g.circle(at(s * 1.2 + 1.8, t), 1.6, "#ffffff", SUPPORT_INK, 0.8);
            }
            hatch(g, s * 1.2 + 3.6, s);
            if rotation {
                g.rect(c.0 - 2.5, c.1 - 2.5, 5.0, 5.0, SUPPORT_INK, "none", 0.0);
            }
        }
        SupportKind::Rotation => g.rect(c.0 - 3.0, c.1 - 3.0, 6.0, 6.0, SUPPORT_INK, "none", 0.0),
    }
    let r = 2.0 * s + 4.0;
    [c.0 - r, c.1 - r, c.0 + r, c.1 + r]
}

/// Colour of the constant load's arrows.
const CONSTANT_INK: &str = "#795548";
/// Colour of the variable load's arrows.
const VARIABLE_INK: &str = "#c2185b";
/// The longest nodal load arrow, in pixels.
const LOAD_ARROW: f64 = 56.0;
/// The longest arrow of a distributed load, in pixels.
const LINE_LOAD_ARROW: f64 = 30.0;

/// The loads the picture draws: nodal forces and moments at nodes, distributed loads on
/// frames and bars (global components), each `(constant?, …)`; and the number of elements
/// with a body force (not drawn).
#[derive(Default)]
struct Loads {
    nodal: Vec<(bool, usize, [f64; 2], f64)>,
    lines: Vec<(bool, usize, [f64; 2], [f64; 2])>,
    body: usize,
}

/// The loads of the two groups at the load `p`: the constant load as it is, the variable one
/// multiplied by `p` (the loads acting in the state drawn).
fn loads_at(model: &Model, p: f64) -> Loads {
    let cases = model.cases();
    let mut out = Loads::default();
    for (case, load) in model.loads() {
        let (constant, factor) = match cases.get(case.0).map(String::as_str) {
            Some("constant") => (true, 1.0),
            Some("variable") => (false, p),
            _ => continue,
        };
        match *load {
            Load::Nodal { node, fx, fy, m } => {
                let (f, m) = ([factor * fx, factor * fy], factor * m);
                match out
                    .nodal
                    .iter_mut()
                    .find(|(c, n, ..)| *c == constant && *n == node.0)
                {
                    Some(x) => {
                        x.2 = [x.2[0] + f[0], x.2[1] + f[1]];
                        x.3 += m;
                    }
                    None => out.nodal.push((constant, node.0, f, m)),
                }
            }
            Load::Distributed {
                element,
                start,
                end,
                frame,
            } => {
                let Some(Element::Frame { nodes, .. } | Element::Bar { nodes, .. }) =
                    model.elements().get(element.0)
                else {
                    continue;
                };
                let (a, b) = (model.nodes()[nodes[0].0], model.nodes()[nodes[1].0]);
                let l = (b[0] - a[0]).hypot(b[1] - a[1]);
                let global = |w: [f64; 2]| match frame {
                    LoadFrame::Global => [factor * w[0], factor * w[1]],
                    LoadFrame::Local if l > 0.0 => {
                        let (e, n) = (
                            [(b[0] - a[0]) / l, (b[1] - a[1]) / l],
                            [-(b[1] - a[1]) / l, (b[0] - a[0]) / l],
                        );
                        [
                            factor * (w[0] * e[0] + w[1] * n[0]),
                            factor * (w[0] * e[1] + w[1] * n[1]),
                        ]
                    }
                    LoadFrame::Local => [0.0, 0.0],
                };
                out.lines
                    .push((constant, element.0, global(start), global(end)));
            }
            Load::BodyForce { .. } => out.body += 1,
            Load::Settlement { .. } | Load::Temperature { .. } => {}
        }
    }
    out
}

/// An arrow of `len` pixels along the unit screen direction `u` with its tip `gap` pixels
/// before the point `c`; returns the points it covers (for the labels' placement).
fn load_arrow(
    g: &mut Svg,
    c: (f64, f64),
    u: (f64, f64),
    len: f64,
    gap: f64,
    ink: &str,
) -> Vec<(f64, f64)> {
    let tip = (c.0 - gap * u.0, c.1 - gap * u.1);
    let tail = (tip.0 - len * u.0, tip.1 - len * u.1);
    g.arrow(tail, tip, ink, 1.5, 7.0);
    samples_along(tail, tip)
}

/// Points every 5 px along a segment.
fn samples_along(a: (f64, f64), b: (f64, f64)) -> Vec<(f64, f64)> {
    let l = (b.0 - a.0).hypot(b.1 - a.1);
    let n = (l / 5.0).ceil().max(1.0) as usize;
    (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1))
        })
        .collect()
}

/// A moment at `c` as a ¾ circle with a head, counter-clockwise for `m > 0`.
fn moment_arrow(g: &mut Svg, c: (f64, f64), m: f64, ink: &str) -> Vec<(f64, f64)> {
    let r = 12.0;
    let (a0, a1) = if m > 0.0 {
        (-60.0f64, 210.0f64)
    } else {
        (240.0, -30.0)
    };
    let pts: Vec<(f64, f64)> = (0..=18)
        .map(|k| {
            let a = (a0 + (a1 - a0) * k as f64 / 18.0).to_radians();
            (c.0 + r * a.cos(), c.1 - r * a.sin())
        })
        .collect();
    g.polyline(&pts[..17], ink, 1.4, "");
    g.arrow(pts[15], pts[18], ink, 1.4, 6.0);
    pts
}

/// Items by their cell of a grid over the picture.
type Grid<T> = std::collections::HashMap<(i64, i64), Vec<T>>;

/// Places the labels greedily in pair order: each name next to its symbol (right, left, above
/// or below), skipped where it would overlap another label, a symbol, an arrow or a support,
/// or leave the drawing, or where another symbol would be about as near to it as its own
/// (the name would not say which pair it names). Returns how many were left out.
fn place_labels(
    g: &mut Svg,
    labels: &[(String, (f64, f64))],
    marks: &[(f64, f64)],
    boxes: &[[f64; 4]],
    area: [f64; 4],
) -> usize {
    let size = 8.0;
    let mut placed: Vec<[f64; 4]> = Vec::new();
    // marks on a grid of 24 px cells, so that a label is tested against the marks near it only
    let cell = 24.0;
    let key = |p: (f64, f64)| ((p.0 / cell).floor() as i64, (p.1 / cell).floor() as i64);
    let mut grid: Grid<(f64, f64)> = Default::default();
    for &p in marks {
        grid.entry(key(p)).or_default().push(p);
    }
    // the symbols, so that a name is drawn only where its own symbol is the nearest one
    let mut symbols: Grid<(usize, (f64, f64))> = Default::default();
    for (i, (_, c)) in labels.iter().enumerate() {
        symbols.entry(key(*c)).or_default().push((i, *c));
    }
    let distance = |p: (f64, f64), b: &[f64; 4]| {
        let dx = (b[0] - p.0).max(p.0 - b[2]).max(0.0);
        let dy = (b[1] - p.1).max(p.1 - b[3]).max(0.0);
        dx.hypot(dy)
    };
    // two names at least 3 px apart
    let overlaps = |a: &[f64; 4], b: &[f64; 4]| {
        a[0] < b[2] + 3.0 && b[0] < a[2] + 3.0 && a[1] < b[3] + 3.0 && b[1] < a[3] + 3.0
    };
    let mut skipped = 0;
    for (own, (name, c)) in labels.iter().enumerate() {
        let w = font::width(name, size);
        let candidates = [
            (
                c.0 + 8.0,
                c.1 + 3.0,
                Anchor::Start,
                [c.0 + 7.0, c.1 - 5.0, c.0 + 9.0 + w, c.1 + 5.0],
            ),
            (
                c.0 - 8.0,
                c.1 + 3.0,
                Anchor::End,
                [c.0 - 9.0 - w, c.1 - 5.0, c.0 - 7.0, c.1 + 5.0],
            ),
            (
                c.0,
                c.1 - 9.0,
                Anchor::Middle,
                [
                    c.0 - w / 2.0 - 1.0,
                    c.1 - 17.0,
                    c.0 + w / 2.0 + 1.0,
                    c.1 - 7.0,
                ],
            ),
            (
                c.0,
                c.1 + 16.0,
                Anchor::Middle,
                [
                    c.0 - w / 2.0 - 1.0,
                    c.1 + 7.0,
                    c.0 + w / 2.0 + 1.0,
                    c.1 + 18.0,
                ],
            ),
        ];
        let free = |b: &[f64; 4]| {
            if b[0] < area[0] || b[1] < area[1] || b[2] > area[2] || b[3] > area[3] {
                return false;
            }
            if placed.iter().chain(boxes).any(|o| overlaps(o, b)) {
                return false;
            }
            // another symbol nearer than its own, or as near within half a pixel
            let d = distance(*c, b) + 0.5;
            let (k0, k1) = (key((b[0] - d, b[1] - d)), key((b[2] + d, b[3] + d)));
            for i in k0.0..=k1.0 {
                for j in k0.1..=k1.1 {
                    let nearer = symbols
                        .get(&(i, j))
                        .is_some_and(|ps| ps.iter().any(|&(k, q)| k != own && distance(q, b) < d));
                    if nearer {
                        return false;
                    }
                }
            }
            // A mark is a point: 1.5 px of room around the label (a symbol's own marks lie
            // 2.5 px outside its candidate boxes).
            let m = 1.5;
            let (k0, k1) = (key((b[0] - m, b[1] - m)), key((b[2] + m, b[3] + m)));
            for i in k0.0..=k1.0 {
                for j in k0.1..=k1.1 {
                    let hit = grid.get(&(i, j)).is_some_and(|ps| {
                        ps.iter().any(|p| {
                            p.0 > b[0] - m && p.0 < b[2] + m && p.1 > b[1] - m && p.1 < b[3] + m
                        })
                    });
                    if hit {
                        return false;
                    }
                }
            }
            true
        };
        match candidates.iter().find(|c| free(&c.3)) {
            Some(&(x, y, anchor, b)) => {
                // a light box behind the name, so that it reads on a coloured mesh
                g.raw(&format!(
                    r##"<rect class="label" x="{}" y="{}" width="{}" height="{}" rx="2" fill="#ffffff" fill-opacity="0.8"/>"##,
                    svg::n(b[0]),
                    svg::n(b[1]),
                    svg::n(b[2] - b[0]),
                    svg::n(b[3] - b[1])
                ));
                g.text(name, x, y, size, anchor, "#263238");
                placed.push(b);
            }
            None => skipped += 1,
        }
    }
    skipped
}

/// The unit direction (world) pointing away from the elements at node `n`: the opposite of
/// the mean direction towards their other nodes (down when the node has no element or the
/// directions cancel).
fn away_from_elements(model: &Model, n: usize) -> [f64; 2] {
    let nodes = model.nodes();
    let mut d = [0.0f64, 0.0f64];
    for e in model.elements() {
        let ns: &[NodeId] = match e {
            Element::Frame { nodes, .. } | Element::Bar { nodes, .. } => nodes,
            Element::Plane { nodes, .. } => nodes,
            Element::Triangle { nodes, .. } => nodes,
        };
        if ns.iter().any(|x| x.0 == n) {
            for x in ns.iter().filter(|x| x.0 != n) {
                let (q, p) = (nodes[x.0], nodes[n]);
                let l = (q[0] - p[0]).hypot(q[1] - p[1]);
                if l > 0.0 {
                    d[0] += (q[0] - p[0]) / l;
                    d[1] += (q[1] - p[1]) / l;
                }
            }
        }
    }
    let l = d[0].hypot(d[1]);
    if l > 1e-9 {
        [-d[0] / l, -d[1] / l]
    } else {
        [0.0, -1.0]
    }
}
