//! Load-path charts: the forces and mutual displacements of the pairs against the load `p`,
//! one small panel per pair, events marked and numbered.

use unilateral_contact::{
    ContactError, ContactSolution, EventKind, LoadStep, Outcome, PairResult, PairState,
};

use crate::structure::state_style;

use crate::font::{self, Anchor};
use crate::svg::{nice_range, num, ticks, Svg};

/// The c-free solution sampled along the traced path: the start, every event load and the end.
#[derive(Debug, Clone)]
pub struct PathSamples {
    /// The loads, in the order of the path.
    pub loads: Vec<f64>,
    /// The pair results at each load.
    pub pairs: Vec<Vec<PairResult>>,
}

/// The load at which the charts end: the reported load, the limit load, or (for a ray) a
/// little beyond the last event.
pub fn end_load(sol: &ContactSolution) -> Option<f64> {
    let last = sol.steps.iter().map(|s| s.p).fold(0.0f64, f64::max);
    match &sol.outcome {
        Outcome::Ray { p_from } => {
            let beyond = if *p_from > 0.0 { 1.25 * p_from } else { 1.0 };
            let _ = last;
            Some(sol.p.map_or(beyond, |p| p.max(beyond)))
        }
        Outcome::Mechanism { p_limit, .. } => Some(*p_limit),
        _ => sol.p.or(if last > 0.0 { Some(last) } else { None }),
    }
}

/// The values the charts draw. With a tightening `c > 0` (the paper's procedure), the path
/// as traced, with `c` in it ([`ContactSolution::traced_on_segments`]), at its breakpoints
/// (above `MAX_SAMPLES` = 200, at that many spread evenly over them by their index): exact there,
/// linear in between, and never mixed with values without the tightening. Without one, the
/// same breakpoints are the solution of the problem at their loads (the start, every event),
/// and the end (on a ray, a little beyond the last event) is evaluated on the path's last
/// segment ([`ContactSolution::at_many`]). An error of the solution at a load is returned.
/// Nothing is solved or prepared again.
pub fn samples(sol: &ContactSolution) -> Result<PathSamples, ContactError> {
    let mut out = match traced_samples(sol) {
        // the product out of range where the solution is not (a friction coefficient near
        // the end of the range): the solution at the breakpoints' loads
        Err(ContactError::OutOfRange(_)) if sol.tightening == 0.0 => {
            let loads: Vec<f64> = thin(
                sol.path.breakpoints.iter().map(|b| b.p).collect(),
                MAX_SAMPLES,
            );
            let mut out = PathSamples {
                loads: Vec::new(),
                pairs: Vec::new(),
            };
            for (p, at) in loads.iter().copied().zip(sol.at_many(&loads)?) {
                if let Some((pairs, _)) = at {
                    out.loads.push(p);
                    out.pairs.push(pairs);
                }
            }
            out
        }
        other => other?,
    };
    if sol.tightening > 0.0 {
        return Ok(out);
    }
    // Without tightening the breakpoints are the solution at their loads; the charts go on
    // to the end (on a ray, a little beyond the last event), a load past the last breakpoint.
    // There the scheme of the last segment holds, the values are linear in p: the reported
    // solution is that point when it lies at the end, and the end is on the straight line
    // through the last breakpoint and the reported solution when that lies beyond it (no walk
    // along the path and no fresh solve: on a path of thousands of steps either costs as much
    // as the trace). Otherwise the curves end at the last breakpoint.
    let last = out.loads.last().copied().unwrap_or(0.0);
    let near = |a: f64, b: f64| (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0);
    if let (Some(e), Some(p), Some(last_pairs)) = (end_load(sol), sol.p, out.pairs.last()) {
        if e > last && !near(e, last) && p > last && !near(p, last) {
            let pairs = if near(p, e) {
                sol.pairs.clone()
            } else {
                let s = (e - last) / (p - last);
                let lerp = |a: f64, b: f64| a + s * (b - a);
                last_pairs
                    .iter()
                    .zip(&sol.pairs)
                    .map(|(a, b)| PairResult {
                        x_n: lerp(a.x_n, b.x_n),
                        x_t: lerp(a.x_t, b.x_t),
                        z_n: lerp(a.z_n, b.z_n),
                        z_t: lerp(a.z_t, b.z_t),
                        ..b.clone()
                    })
                    .collect()
            };
            out.loads.push(e);
            out.pairs.push(pairs);
        }
    }
    Ok(out)
}

/// The traced path at its breakpoints, consecutive breakpoints at the same load taken once
/// (the last: the scheme settled there), thinned to [`MAX_SAMPLES`].
fn traced_samples(sol: &ContactSolution) -> Result<PathSamples, ContactError> {
    let bps = &sol.path.breakpoints;
    let mut idx: Vec<usize> = Vec::with_capacity(bps.len());
    for (k, b) in bps.iter().enumerate() {
        if idx
            .last()
            .is_some_and(|&j| (bps[j].p - b.p).abs() <= 1e-12 * b.p.abs().max(1.0))
        {
            // the later breakpoint at the same load: the scheme settled there
            *idx.last_mut().unwrap_or(&mut 0) = k;
            continue;
        }
        idx.push(k);
    }
    let idx = thin(idx, MAX_SAMPLES);
    let at: Vec<(usize, f64)> = idx.iter().map(|&k| (k, 0.0)).collect();
    let mut out = PathSamples {
        loads: Vec::new(),
        pairs: Vec::new(),
    };
    for (p, pairs) in sol.traced_on_segments(&at)?.into_iter().flatten() {
        out.loads.push(p);
        out.pairs.push(pairs);
    }
    Ok(out)
}

/// The load of the last breakpoint of the traced path (where the tightened charts end).
fn last_breakpoint(sol: &ContactSolution) -> Option<f64> {
    sol.path.breakpoints.last().map(|b| b.p)
}

/// At most this many loads are evaluated for the charts: a panel is 180 px wide.
pub const MAX_SAMPLES: usize = 200;

/// The loads thinned to at most `max` (`max ≥ 2`), evenly by their index along the path, the
/// first and the last kept.
fn thin<T: Copy>(loads: Vec<T>, max: usize) -> Vec<T> {
    let k = loads.len();
    if k <= max || max < 2 {
        return loads;
    }
    (0..max).map(|i| loads[i * (k - 1) / (max - 1)]).collect()
}

/// A short label of a step: `3: left.4 opens`.
pub fn step_label(step: &LoadStep) -> String {
    let what = if step.events.is_empty() {
        format!("{} leaves, {} enters", step.leaving, step.entering)
    } else {
        step.events
            .iter()
            .map(|e| format!("{} {}", e.name, event_word(e.kind)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!("{}: {what}", step.index)
}

/// One word for an event.
pub fn event_word(k: EventKind) -> &'static str {
    match k {
        EventKind::Opens => "opens",
        EventKind::Closes => "closes",
        EventKind::StartsSlippingPlus => "slips+",
        EventKind::StartsSlippingMinus => "slips−",
        EventKind::Sticks => "sticks",
    }
}

/// Which quantity a chart shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ChartKind {
    /// `x_n` and `x_t`.
    Forces,
    /// `z_n` and `z_t`.
    Displacements,
}

const C_NORMAL: &str = "#1f5fa8";

/// Above this many pairs the charts show the pairs that change most (see [`ranked`]) and a map
/// of the states of all pairs; up to it, every pair has its panel.
pub const MANY_PAIRS: usize = 24;

/// Above this many events the panels leave out the faint lines of other pairs' events and the
/// chart leaves out the list of events (the report's table of events has them all).
pub const MANY_EVENTS: usize = 60;
const C_TANGENT: &str = "#d9731a";
const C_EVENT: &str = "#b3261e";

/// Wraps a text into lines no wider than `w` pixels.
pub fn wrap(s: &str, size: f64, w: f64) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for word in s.split_whitespace() {
        let cand = if cur.is_empty() {
            word.to_string()
        } else {
            format!("{cur} {word}")
        };
        if font::width(&cand, size) > w && !cur.is_empty() {
            lines.push(std::mem::take(&mut cur));
            cur = word.to_string();
        } else {
            cur = cand;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// The SVG of one chart (small multiples, one panel per selected pair).
///
/// `units` is the file's `units` text (`"N, m"`): its force and length units label the
/// panels' quantities (`x_n [N]`), as the tables' columns are labelled.
pub fn chart(
    sol: &ContactSolution,
    s: &PathSamples,
    selected: &[usize],
    kind: ChartKind,
    units: Option<&str>,
) -> String {
    let names: Vec<String> = sol.lcp_names();
    let m = selected.len().max(1);
    let cols = ((m as f64 * 1.5).sqrt().ceil() as usize).clamp(1, 6).min(m);
    let rows = m.div_ceil(cols);
    let (pw, ph) = (180.0, 110.0);
    let (gap_x, gap_y) = (58.0, 40.0);
    let left = 72.0;
    let width = left + cols as f64 * (pw + gap_x) + 20.0;

    // header text
    let about = crate::json::About {
        title: None,
        units: units.map(str::to_string),
    };
    let unit = |force: bool| match about.force_length() {
        Some((f, l)) => format!(" [{}]", if force { f } else { l }),
        None => String::new(),
    };
    let (title, a_lab, b_lab, what) = match kind {
        ChartKind::Forces => (
            "Load path: contact forces of the pairs",
            format!("x_n{} (normal force, compression +)", unit(true)),
            format!("x_t{} (tangential force)", unit(true)),
            "forces",
        ),
        ChartKind::Displacements => (
            "Load path: mutual displacements of the pairs",
            format!("z_n{} (opening +)", unit(false)),
            format!("z_t{} (slip)", unit(false)),
            "mutual displacements",
        ),
    };
    let tightened = sol.tightening > 0.0;
    let mut caption = if tightened {
        format!(
            "The paper's procedure: the {what} of each pair on the path traced with the tightening c = {c}, against the load p; values, states and events all depend on c (the solution without the tightening is the report's table of pairs). Exact at every breakpoint of the traced path up to the last one (p = {last}), straight in between.",
            c = num(sol.tightening),
            last = last_breakpoint(sol).map_or_else(|| "0".into(), num),
        )
    } else {
        format!(
            "The {what} of each pair against the load p, exact at p = 0, at every event and at the end, straight in between."
        )
    };
    caption.push_str(
        " Each panel has its own vertical scale. Red marks: events of the pair (numbers as in the list below), and red ticks under every p axis: the loads of all events; grey lines: events of other pairs.",
    );
    let total = s.pairs.first().map_or(0, |p| p.len());
    let many = total > MANY_PAIRS;
    let many_events = sol.steps.len() > MANY_EVENTS;
    if many {
        caption.push_str(&format!(
            " Of the {total} pairs, the {} that change most are shown; the working-scheme map shows every pair.",
            selected.len(),
        ));
    }
    if many_events {
        caption.push_str(&format!(
            " The {} events are listed in the report's table of events{}.",
            sol.steps.len(),
            if s.loads.len() < sol.steps.len() {
                format!(
                    "; the curves are exact at {} loads spread evenly over them",
                    s.loads.len()
                )
            } else {
                String::new()
            }
        ));
    }
    let cap_lines = wrap(&caption, 9.0, width - 40.0);
    let top = 40.0 + cap_lines.len() as f64 * 14.0 + 44.0;

    // event list
    let labels: Vec<(f64, String)> = sol
        .steps
        .iter()
        .filter(|st| !many_events && !st.settling)
        .map(|st| (st.p, format!("{}   p = {}", step_label(st), num(st.p))))
        .collect();
    let ev_size = 8.5;
    let ev_colw = labels
        .iter()
        .map(|l| font::width(&l.1, ev_size))
        .fold(120.0f64, f64::max)
        + 24.0;
    let ev_cols = (((width - 40.0) / ev_colw).floor() as usize).max(1);
    let ev_rows = labels.len().div_ceil(ev_cols);
    let panels_h = rows as f64 * (ph + gap_y);
    let height = top + panels_h + 30.0 + ev_rows as f64 * 14.0 + 20.0;

    let title = if tightened {
        format!(
            "{title} (traced with the tightening c = {})",
            num(sol.tightening)
        )
    } else {
        title.to_string()
    };
    let title = title.as_str();
    let mut g = Svg::new(width, height, title);
    g.text(title, 20.0, 26.0, 13.0, Anchor::Start, "#111111");
    for (i, l) in cap_lines.iter().enumerate() {
        g.text(
            l,
            20.0,
            46.0 + 14.0 * i as f64,
            9.0,
            Anchor::Start,
            "#444444",
        );
    }
    // legend
    let ly = top - 30.0;
    g.line((20.0, ly - 3.0), (44.0, ly - 3.0), C_NORMAL, 2.0, "");
    g.math(&a_lab, 50.0, ly, 9.0, Anchor::Start, "#222222");
    let x2 = 50.0 + font::width_rich(&a_lab, 9.0) + 30.0;
    g.line(
        (x2, ly - 3.0),
        (x2 + 24.0, ly - 3.0),
        C_TANGENT,
        2.0,
        r#" stroke-dasharray="5 3""#,
    );
    g.math(&b_lab, x2 + 30.0, ly, 9.0, Anchor::Start, "#222222");
    let x3 = x2 + 30.0 + font::width_rich(&b_lab, 9.0) + 30.0;
    g.polygon(&tri(x3 + 6.0, ly - 3.0, 4.5), C_EVENT, "none", 0.0, "");
    g.text(
        "event of the pair",
        x3 + 16.0,
        ly,
        9.0,
        Anchor::Start,
        "#222222",
    );

    if s.loads.len() < 2 || selected.is_empty() {
        // A path traced with the tightening records its values at its events only: one
        // stopped at its target before the first has nothing but its start to draw, while its
        // solution is reported.
        let why = if tightened && sol.p.is_some() && sol.steps.is_empty() {
            "no curve to draw: the traced path (with c) keeps one working scheme up to its \
             target; the solution there is reported in the tables"
        } else {
            "no load path to draw (no solution along the path)"
        };
        for (i, line) in wrap(why, 10.0, width - 40.0).iter().enumerate() {
            g.text(
                line,
                20.0,
                top + 20.0 + 14.0 * i as f64,
                10.0,
                Anchor::Start,
                "#b3261e",
            );
        }
        return g.finish();
    }

    let val = |r: &PairResult| match kind {
        ChartKind::Forces => (r.x_n, r.x_t),
        ChartKind::Displacements => (r.z_n, r.z_t),
    };
    let pmax = s.loads.iter().cloned().fold(0.0f64, f64::max);
    let pmin = s.loads.iter().cloned().fold(0.0f64, f64::min);
    let global_max = s
        .pairs
        .iter()
        .flatten()
        .map(|r| {
            let (a, b) = val(r);
            a.abs().max(b.abs())
        })
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let (p0, p1) = nice_range(pmin, pmax);
    let xt = ticks(p0, p1, 4);

    // The state in each panel's title: of the reported solution; of a tightened run, that of
    // the traced path at its end (as the working-scheme map's last column).
    let end_states: Vec<PairState> = if tightened {
        let mut st: Vec<PairState> = s
            .pairs
            .last()
            .map(|p| p.iter().map(|r| r.state).collect())
            .unwrap_or_default();
        if let (Some(last), Some(var), Some(&(_, true, _, _))) =
            (s.pairs.last(), sol.path.last_entering, segments(sol).last())
        {
            growing(&mut st, last, var, sol.pairs());
        }
        st
    } else {
        sol.pairs.iter().map(|r| r.state).collect()
    };
    for (k, &pi) in selected.iter().enumerate() {
        let (r, c) = (k / cols, k % cols);
        let ox = left + c as f64 * (pw + gap_x);
        let oy = top + r as f64 * (ph + gap_y);
        // each panel its own vertical scale, so that small forces show their kinks too
        let (mut lo, mut hi) = (0.0f64, 0.0f64);
        for pr in &s.pairs {
            if let Some(x) = pr.get(pi) {
                let (a, b) = val(x);
                for v in [a, b] {
                    if v.is_finite() {
                        lo = lo.min(v);
                        hi = hi.max(v);
                    }
                }
            }
        }
        let tiny = 1e-12 * global_max;
        if hi - lo <= tiny {
            (lo, hi) = (0.0, 0.0);
        }
        let (lo, hi) = nice_range(lo, hi);
        let yt = ticks(lo, hi, 4);
        let fx = |p: f64| ox + (p - p0) / (p1 - p0) * pw;
        let fy = |v: f64| oy + ph - (v - lo) / (hi - lo) * ph;
        g.rect(ox, oy, pw, ph, "#fbfbfb", "#999999", 0.8);
        for &t in &yt {
            g.line((ox, fy(t)), (ox + pw, fy(t)), "#e4e4e4", 0.6, "");
            g.text(&num(t), ox - 4.0, fy(t) + 3.5, 8.0, Anchor::End, "#444444");
        }
        for &t in &xt {
            g.line((fx(t), oy), (fx(t), oy + ph), "#e4e4e4", 0.6, "");
            if r == rows - 1 || k + cols >= m {
                g.text(
                    &num(t),
                    fx(t),
                    oy + ph + 13.0,
                    8.0,
                    Anchor::Middle,
                    "#444444",
                );
            }
        }
        if lo < 0.0 && hi > 0.0 {
            g.line((ox, fy(0.0)), (ox + pw, fy(0.0)), "#777777", 0.8, "");
        }
        // the loads of all events as ticks under the p axis (one path per panel)
        let mut ticks_d = String::new();
        let mut last_tick = f64::NEG_INFINITY;
        for st in sol
            .steps
            .iter()
            .filter(|st| !st.settling && !st.events.is_empty())
        {
            if st.p >= p0 && st.p <= p1 {
                let x = fx(st.p);
                if (x - last_tick).abs() >= 0.5 {
                    ticks_d.push_str(&format!(
                        "M{} {}v5",
                        crate::svg::n(x),
                        crate::svg::n(oy + ph)
                    ));
                    last_tick = x;
                }
            }
        }
        if !ticks_d.is_empty() {
            g.raw(&format!(
                r#"<path d="{ticks_d}" stroke="{C_EVENT}" stroke-width="0.9" fill="none"/>"#
            ));
        }
        // events of all pairs: faint lines; of this pair: marks and numbers (the pivots that
        // settle the start at p = 0 are no events, as the ticks and the summary say)
        let mut own: Vec<(f64, usize)> = Vec::new();
        for st in sol.steps.iter().filter(|st| !st.settling) {
            if !(st.p >= p0 && st.p <= p1) {
                continue;
            }
            if st.events.iter().any(|e| e.pair == pi) {
                own.push((st.p, st.index));
            } else if !many_events {
                g.line((fx(st.p), oy), (fx(st.p), oy + ph), "#d0d0d0", 0.5, "");
            }
        }
        // the curves
        let a: Vec<(f64, f64)> = s
            .loads
            .iter()
            .zip(&s.pairs)
            .filter_map(|(&p, pr)| pr.get(pi).map(|x| (fx(p), fy(val(x).0))))
            .collect();
        let b: Vec<(f64, f64)> = s
            .loads
            .iter()
            .zip(&s.pairs)
            .filter_map(|(&p, pr)| pr.get(pi).map(|x| (fx(p), fy(val(x).1))))
            .collect();
        g.polyline(&b, C_TANGENT, 1.6, r#" stroke-dasharray="5 3""#);
        g.polyline(&a, C_NORMAL, 1.8, "");
        let mut last_x = f64::NEG_INFINITY;
        let mut row = 0;
        for (p, idx) in own {
            let x = fx(p);
            g.line(
                (x, oy),
                (x, oy + ph),
                C_EVENT,
                0.7,
                r#" stroke-dasharray="2 2""#,
            );
            g.polygon(&tri(x, oy + ph - 4.0, 4.0), C_EVENT, "none", 0.0, "");
            let lab = idx.to_string();
            let w = font::width(&lab, 7.0);
            row = if x - last_x < w + 3.0 {
                (row + 1) % 3
            } else {
                0
            };
            if row == 0 {
                last_x = x;
            }
            g.text(
                &lab,
                x + 2.0,
                oy + 10.0 + 9.0 * row as f64,
                7.0,
                Anchor::Start,
                C_EVENT,
            );
        }
        // panel title: pair name and final state
        let name = names.get(pi).cloned().unwrap_or_else(|| pi.to_string());
        let state = end_states
            .get(pi)
            .map(|st| format!("  ({st})"))
            .unwrap_or_default();
        g.text(
            &format!("{name}{state}"),
            ox,
            oy - 6.0,
            9.0,
            Anchor::Start,
            "#111111",
        );
    }
    // axis titles
    let yb = top + panels_h - gap_y + 28.0;
    g.text(
        "load p",
        left + (cols as f64 * (pw + gap_x)) / 2.0,
        yb,
        9.5,
        Anchor::Middle,
        "#222222",
    );
    let ylab = match kind {
        ChartKind::Forces => "force",
        ChartKind::Displacements => "displacement",
    };
    g.text_full(
        ylab,
        16.0,
        top + panels_h / 2.0,
        9.5,
        Anchor::Middle,
        90.0,
        "#222222",
        false,
    );

    // list of events
    let ey = yb + 26.0;
    if labels.is_empty() && !many_events {
        g.text(
            "no events: the working scheme does not change",
            20.0,
            ey,
            ev_size,
            Anchor::Start,
            "#444444",
        );
    }
    for (i, (_, l)) in labels.iter().enumerate() {
        let (r, c) = (i % ev_rows.max(1), i / ev_rows.max(1));
        g.text(
            l,
            20.0 + c as f64 * ev_colw,
            ey + r as f64 * 14.0,
            ev_size,
            Anchor::Start,
            "#333333",
        );
    }
    g.finish()
}

/// One column of the working-scheme map: a segment of the traced path between two
/// breakpoints (or the last one, beyond the last breakpoint), with the state of every pair in
/// it.
#[derive(Debug, Clone, PartialEq)]
pub struct SchemeColumn {
    /// The segment: it starts at breakpoint `segment` of [`LoadPath::breakpoints`](unilateral_lcp::LoadPath::breakpoints).
    pub segment: usize,
    /// The load at its start.
    pub p_from: f64,
    /// The load at its end.
    pub p_to: f64,
    /// The state of every pair inside the segment.
    pub states: Vec<PairState>,
}

/// At most this many segments are drawn as columns of the working-scheme map (spread evenly
/// over the path when it has more): about two pixels each on its 1000 px.
pub const MAP_COLUMNS: usize = 480;

/// The columns of the working-scheme map: every segment of the traced path along which the
/// load moves (segments that only settle the scheme at one load are not columns), and the
/// segment after the last breakpoint when the path goes on beyond it (a ray, or the target on
/// it). A pair's state in a segment is read at the segment's middle (inside it the basis does
/// not change, so neither does the state); beyond the last breakpoint it is the state there
/// with the variable that enters on the last segment taken as growing (the pair it belongs to
/// opens, closes, slips or sticks). With a tightening the states are those of the traced path,
/// which depend on `c`.
pub fn scheme_columns(sol: &ContactSolution) -> Result<Vec<SchemeColumn>, ContactError> {
    let segs = thin(segments(sol), MAP_COLUMNS);
    let at: Vec<(usize, f64)> = segs
        .iter()
        .map(|&(k, fin, _, _)| (k, if fin { 0.0 } else { 0.5 }))
        .collect();
    let m = sol.pairs();
    let mut out = Vec::with_capacity(segs.len());
    // Only the states are read: the pairs unnamed.
    for (&(k, fin, p_from, p_to), v) in segs.iter().zip(sol.traced_on_segments_unnamed(&at)?) {
        let Some((_, pairs)) = v else { continue };
        let mut states: Vec<PairState> = pairs.iter().map(|r| r.state).collect();
        // Beyond the last breakpoint the scheme no longer changes: without the tightening,
        // where the reported load lies there, the reported solution's states are the column's
        // (at the breakpoint itself every force may be zero — a homogeneous problem at p = 0 —
        // and every pair would read open).
        let reported_inside = fin
            && sol.tightening == 0.0
            && sol.p.is_some_and(|p| p > p_from)
            && sol.pairs.len() == m;
        if reported_inside {
            states = sol.pairs.iter().map(|r| r.state).collect();
        } else if fin {
            if let Some(var) = sol.path.last_entering {
                growing(&mut states, &pairs, var, m);
            }
        }
        out.push(SchemeColumn {
            segment: k,
            p_from,
            p_to,
            states,
        });
    }
    Ok(out)
}

/// The segments of the path that are columns of the map: `(breakpoint, beyond the last one,
/// p_from, p_to)`.
fn segments(sol: &ContactSolution) -> Vec<(usize, bool, f64, f64)> {
    let bps = &sol.path.breakpoints;
    let Some(last) = bps.last() else {
        return Vec::new();
    };
    let scale = bps.iter().fold(1.0f64, |a, b| a.max(b.p.abs()));
    let tol = 1e-12 * scale;
    let mut segs: Vec<(usize, bool, f64, f64)> = bps
        .windows(2)
        .enumerate()
        .filter(|(_, w)| (w[1].p - w[0].p).abs() > tol)
        .map(|(k, w)| (k, false, w[0].p, w[1].p))
        .collect();
    let end = end_load(sol).unwrap_or(last.p);
    if end > last.p + tol || segs.is_empty() {
        segs.push((bps.len() - 1, true, last.p, end.max(last.p)));
    }
    // The pivots that settle the start move the load by round-off only: the first column
    // starts at the start's load (p = 0), not at the round-off load they end at.
    if let Some(first) = segs.first_mut() {
        if (first.2 - bps[0].p).abs() <= tol {
            first.2 = bps[0].p;
        }
    }
    segs
}

/// The states just after a breakpoint, where `var` (zero at the breakpoint) starts to grow.
fn growing(states: &mut [PairState], pairs: &[PairResult], var: unilateral_lcp::Var, m: usize) {
    use unilateral_lcp::Var;
    let (i, is_z) = match var {
        Var::X(i) => (i, false),
        Var::Z(i) => (i, true),
        Var::Driver => return,
    };
    if m == 0 || i >= 3 * m {
        return;
    }
    let (pair, part) = (i % m, i / m);
    let slip = |r: &PairResult| {
        if r.z_t > 0.0 {
            PairState::SlipPlus
        } else if r.z_t < 0.0 {
            PairState::SlipMinus
        } else {
            PairState::Stick
        }
    };
    let st = &mut states[pair];
    *st = match (part, is_z) {
        (0, true) => PairState::Open,
        (0, false) if *st == PairState::Open => slip(&pairs[pair]),
        (1, true) if *st != PairState::Open => PairState::SlipPlus,
        (2, true) if *st != PairState::Open => PairState::SlipMinus,
        (_, false) if part > 0 && *st != PairState::Open => PairState::Stick,
        _ => *st,
    };
}

/// The column of the reported load and the fraction of the way through it.
fn reported_column(sol: &ContactSolution, cols: &[SchemeColumn]) -> Option<(usize, f64)> {
    let p = sol.p?;
    let frac = |c: &SchemeColumn| {
        if c.p_to != c.p_from {
            ((p - c.p_from) / (c.p_to - c.p_from)).clamp(0.0, 1.0)
        } else {
            1.0
        }
    };
    let inside = |c: &SchemeColumn| {
        let (lo, hi) = if c.p_from <= c.p_to {
            (c.p_from, c.p_to)
        } else {
            (c.p_to, c.p_from)
        };
        let t = 1e-12 * hi.abs().max(1.0);
        p >= lo - t && p <= hi + t
    };
    let by_segment = sol
        .path
        .target_segment
        .and_then(|ts| cols.iter().position(|c| c.segment == ts && inside(c)));
    if let Some(j) = by_segment.or_else(|| cols.iter().position(inside)) {
        return Some((j, frac(&cols[j])));
    }
    // a thinned map: the reported load lies between two drawn columns
    let j = cols.iter().position(|c| c.p_from.max(c.p_to) >= p)?;
    Some((j, 0.0))
}

const MAP_W: f64 = 1000.0;

/// Height of the map's legend row and the label of the reported load above the rows.
const MAP_LEGEND: f64 = 34.0;

/// The working-scheme map as an SVG document: every pair (rows) against the load path
/// (columns, one per segment between breakpoints: [`scheme_columns`]), coloured by its state
/// as the structure picture colours its pairs, the reported load marked.
pub fn scheme_map_svg(sol: &ContactSolution, cols: &[SchemeColumn]) -> String {
    let names = sol.lcp_names();
    let tightened = sol.tightening > 0.0;
    let title = if tightened {
        format!(
            "Working scheme along the load path traced with the tightening c = {}",
            num(sol.tightening)
        )
    } else {
        "Working scheme along the load path".to_string()
    };
    let segments = segments(sol).len();
    let mut caption = String::from(
        "The state of every pair (rows) in every segment of the load path between two breakpoints (columns). Every segment has the same width whatever its range of loads, so that events close together stay apart: the loads under the map are those at the ends of the segments, not to scale.",
    );
    if tightened {
        caption.push_str(&format!(
            " The paper's procedure: the states are those of the path traced with the tightening c = {}, and they and the loads of their changes depend on c.",
            num(sol.tightening)
        ));
    }
    if cols.len() < segments {
        caption.push_str(&format!(
            " Of the {segments} segments, {} spread evenly over the path are drawn.",
            cols.len()
        ));
    }
    let cap = wrap(&caption, 9.0, MAP_W - 40.0);
    let m = names.len();
    let rh = (600.0 / m.max(1) as f64).clamp(0.6, 18.0);
    let h = rh * m.max(1) as f64;
    let head = 40.0 + cap.len() as f64 * 14.0 + 6.0;
    let height = head + MAP_LEGEND + h + 50.0;
    let mut g = Svg::new(MAP_W, height, &title);
    g.heading(&title, &cap);
    if cols.is_empty() {
        g.text(
            "no load path to draw (no solution along the path)",
            20.0,
            head + 20.0,
            10.0,
            Anchor::Start,
            "#b3261e",
        );
        return g.finish();
    }
    let marker = reported_column(sol, cols);
    state_map(&mut g, cols, &names, head, MAP_W, marker, sol.p);
    g.finish()
}

/// Draws the map of `cols` (legend at `y0`, then the rows) into `g`: one rectangle per run of
/// equal non-open state along a row (open is the background).
#[allow(clippy::too_many_arguments)]
fn state_map(
    g: &mut Svg,
    cols: &[SchemeColumn],
    names: &[String],
    y0: f64,
    width: f64,
    marker: Option<(usize, f64)>,
    p_reported: Option<f64>,
) {
    let m = cols.first().map_or(0, |c| c.states.len());
    let k = cols.len();
    let label_size = 8.0;
    let left = names
        .iter()
        .map(|n| font::width(n, label_size))
        .fold(30.0f64, f64::max)
        .min(160.0)
        + 12.0;
    let right = 20.0;
    let w = width - left - right;
    let rh = (600.0 / m.max(1) as f64).clamp(0.6, 18.0);
    let h = rh * m.max(1) as f64;
    let top = y0 + MAP_LEGEND;
    let mut lx = left;
    for st in [
        PairState::Open,
        PairState::Stick,
        PairState::SlipPlus,
        PairState::SlipMinus,
    ] {
        let (fill, word) = state_style(st);
        g.rect(lx, y0 + 2.0, 9.0, 9.0, fill, "#333333", 0.6);
        g.text(word, lx + 13.0, y0 + 10.0, 8.5, Anchor::Start, "#222222");
        lx += 13.0 + font::width(word, 8.5) + 18.0;
    }
    let cw = w / k.max(1) as f64;
    g.rect(
        left,
        top,
        w,
        h,
        state_style(PairState::Open).0,
        "#999999",
        0.6,
    );
    for i in 0..m {
        let state_at = |j: usize| cols[j].states.get(i).copied();
        let mut j = 0;
        while j < k {
            let st = state_at(j);
            let mut e = j + 1;
            while e < k && state_at(e) == st {
                e += 1;
            }
            if let Some(st) = st.filter(|&v| v != PairState::Open) {
                g.rect(
                    left + j as f64 * cw,
                    top + i as f64 * rh,
                    (e - j) as f64 * cw,
                    rh,
                    state_style(st).0,
                    "none",
                    0.0,
                );
            }
            j = e;
        }
    }
    // row labels: every `every`-th pair, where they fit
    let every = ((label_size + 3.0) / rh).ceil().max(1.0) as usize;
    for i in (0..m).step_by(every) {
        if let Some(nm) = names.get(i) {
            g.text(
                nm,
                left - 4.0,
                top + (i as f64 + 0.5) * rh + label_size / 2.0,
                label_size,
                Anchor::End,
                "#444444",
            );
        }
    }
    // the loads at the ends of the segments: a readable subset
    let bounds: Vec<(f64, f64)> = std::iter::once((left, cols[0].p_from))
        .chain(
            cols.iter()
                .enumerate()
                .map(|(j, c)| (left + (j + 1) as f64 * cw, c.p_to)),
        )
        .collect();
    let mut last_right = f64::NEG_INFINITY;
    let mut ticks_d = String::new();
    for (x, p) in &bounds {
        ticks_d.push_str(&format!(
            "M{} {}v3",
            crate::svg::n(*x),
            crate::svg::n(top + h)
        ));
        let lab = num(*p);
        let lw = font::width(&lab, 8.0);
        if x - lw / 2.0 > last_right + 8.0 && x + lw / 2.0 <= width {
            g.line((*x, top + h), (*x, top + h + 6.0), "#444444", 0.7, "");
            g.text(&lab, *x, top + h + 16.0, 8.0, Anchor::Middle, "#444444");
            last_right = x + lw / 2.0;
        }
    }
    g.raw(&format!(
        r##"<path d="{ticks_d}" stroke="#888888" stroke-width="0.5" fill="none"/>"##
    ));
    g.text(
        "load p at the ends of the segments (not to scale)",
        left + w / 2.0,
        top + h + 32.0,
        9.0,
        Anchor::Middle,
        "#222222",
    );
    if let (Some((j, f)), Some(p)) = (marker, p_reported) {
        let x = left + (j as f64 + f) * cw;
        g.line((x, top - 4.0), (x, top + h + 2.0), "#111111", 1.4, "");
        g.text(
            &format!("reported p = {}", num(p)),
            x.clamp(left + 40.0, width - 60.0),
            top - 5.0,
            8.0,
            Anchor::Middle,
            "#111111",
        );
    }
}

fn tri(x: f64, y: f64, s: f64) -> [(f64, f64); 3] {
    [(x, y - s), (x - s, y + s * 0.8), (x + s, y + s * 0.8)]
}

/// The names of the pairs of a solution (from its results, else numbered).
trait Names {
    fn lcp_names(&self) -> Vec<String>;
}

impl Names for ContactSolution {
    fn lcp_names(&self) -> Vec<String> {
        if !self.pairs.is_empty() {
            return self.pairs.iter().map(|r| r.name.clone()).collect();
        }
        (0..self.pairs()).map(|i| (i + 1).to_string()).collect()
    }
}

/// The indices of the pairs to show: those named (in the given order; unknown names are
/// skipped), else all up to [`MANY_PAIRS`], else the [`MANY_PAIRS`] that change most
/// ([`ranked`]), in pair order.
pub fn select(sol: &ContactSolution, s: &PathSamples, names: Option<&[String]>) -> Vec<usize> {
    let all: Vec<String> = s
        .pairs
        .first()
        .map(|p| p.iter().map(|r| r.name.clone()).collect())
        .unwrap_or_else(|| sol.lcp_names());
    match names {
        None if all.len() > MANY_PAIRS => ranked(s, MANY_PAIRS),
        None => (0..all.len()).collect(),
        Some(want) => want
            .iter()
            .filter_map(|w| all.iter().position(|n| n == w))
            .collect(),
    }
}

/// The `count` pairs that change most along the sampled path, in pair order. A pair's score is
/// the range of its normal force `x_n` over the samples divided by the largest such range of
/// all pairs, plus the same for its opening `z_n`: forces and displacements weigh alike whatever
/// their units, and a pair that closes, carries load and opens again ranks above one that sits
/// still. Ties go to the lower index.
pub fn ranked(s: &PathSamples, count: usize) -> Vec<usize> {
    let m = s.pairs.first().map_or(0, |p| p.len());
    let range = |i: usize, f: &dyn Fn(&PairResult) -> f64| {
        let (lo, hi) = s
            .pairs
            .iter()
            .filter_map(|pr| pr.get(i).map(f))
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
        if hi >= lo {
            hi - lo
        } else {
            0.0
        }
    };
    let rx: Vec<f64> = (0..m).map(|i| range(i, &|r| r.x_n)).collect();
    let rz: Vec<f64> = (0..m).map(|i| range(i, &|r| r.z_n)).collect();
    most_changing(&rx, &rz, count)
}

/// The `count` indices (in ascending order) with the largest `a_i/max a + b_i/max b`: the pairs
/// whose two charted quantities change most, each relative to its largest change (ties to the
/// lower index).
pub(crate) fn most_changing(a: &[f64], b: &[f64], count: usize) -> Vec<usize> {
    let top = |v: &[f64]| v.iter().copied().fold(0.0f64, f64::max);
    let (ta, tb) = (top(a), top(b));
    let part = |r: f64, t: f64| if t > 0.0 { r / t } else { 0.0 };
    let score: Vec<f64> = (0..a.len())
        .map(|i| part(a[i], ta) + part(b[i], tb))
        .collect();
    let mut order: Vec<usize> = (0..a.len()).collect();
    order.sort_by(|&x, &y| score[y].total_cmp(&score[x]).then(x.cmp(&y)));
    order.truncate(count);
    order.sort_unstable();
    order
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair(i: usize, x_n: f64, z_n: f64, state: PairState) -> PairResult {
        PairResult {
            name: format!("s{i}"),
            x_n,
            x_t: 0.0,
            z_n,
            z_t: 0.0,
            state,
        }
    }

    // Reference: by hand. Pair 1's force spans 0..10 (score 1), pair 3's opening spans
    // 0..0.002 (score 1, in other units), pair 2 spans half of both (score 1), pair 0 a tenth
    // of the force range (0.1) and pair 4 nothing: the three top pairs are 1, 2, 3, returned
    // in pair order; a tie (pairs 0 and 5 both 0.1) goes to the lower index.
    #[test]
    fn ranking_by_normalised_ranges() {
        let at = |v: [(f64, f64); 6]| -> Vec<PairResult> {
            v.iter()
                .enumerate()
                .map(|(i, &(x, z))| pair(i, x, z, PairState::Stick))
                .collect()
        };
        let s = PathSamples {
            loads: vec![0.0, 1.0],
            pairs: vec![
                at([
                    (1.0, 0.0),
                    (0.0, 0.0),
                    (5.0, 0.0),
                    (3.0, 0.0),
                    (2.0, 0.0),
                    (0.0, 0.0),
                ]),
                at([
                    (2.0, 0.0),
                    (10.0, 0.0),
                    (10.0, 0.001),
                    (3.0, 0.002),
                    (2.0, 0.0),
                    (1.0, 0.0),
                ]),
            ],
        };
        assert_eq!(ranked(&s, 3), vec![1, 2, 3]);
        assert_eq!(ranked(&s, 4), vec![0, 1, 2, 3]);
        assert_eq!(ranked(&s, 10), vec![0, 1, 2, 3, 4, 5]);
    }

    // Reference: counted by hand. Pair 0: stick, stick, open, slip+ → 2 runs drawn; pair 1:
    // open throughout → none; pair 2: slip−, slip−, slip−, stick → 2. One background rect,
    // four legend swatches, and the picture's own white background: 1 + 4 + 4 + 1 = 10 rects.
    #[test]
    fn state_map_draws_one_rect_per_run() {
        use PairState::*;
        let rows = [
            [Stick, Stick, Open, SlipPlus],
            [Open, Open, Open, Open],
            [SlipMinus, SlipMinus, SlipMinus, Stick],
        ];
        let cols: Vec<SchemeColumn> = (0..4)
            .map(|j| SchemeColumn {
                segment: j,
                p_from: j as f64,
                p_to: j as f64 + 1.0,
                states: (0..3).map(|i| rows[i][j]).collect(),
            })
            .collect();
        let names: Vec<String> = (0..3).map(|i| format!("s{i}")).collect();
        let mut g = Svg::new(400.0, 300.0, "map");
        state_map(&mut g, &cols, &names, 0.0, 400.0, Some((1, 0.5)), Some(1.5));
        let svg = g.finish();
        assert_eq!(svg.matches("<rect").count(), 10, "{svg}");
    }

    fn solve_example3() -> ContactSolution {
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/example3-sheet-pile.toml");
        let unilateral_io::Problem::Structural(pb) = unilateral_io::read_problem(&file).unwrap()
        else {
            panic!("a structural model");
        };
        unilateral_analysis::analyze(&pb.model, &pb.settings)
            .unwrap()
            .solution
    }

    /// The map of a homogeneous problem traced without tightening (the paper's Example 1 zone,
    /// c = 0): its scheme is settled at p = 0 and holds for every p > 0 — pair 1 lifts, pairs 2
    /// and 3 press and stick (formulation §5, the paper's answer). Its one column shows that
    /// scheme, not the all-zero forces at p = 0 (where every pair read open and the map was
    /// blank).
    #[test]
    fn a_homogeneous_path_maps_its_scheme_for_p_above_zero() {
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/example1-contact-zone.toml");
        let unilateral_io::Problem::ContactZone(pb) = unilateral_io::read_problem(&file).unwrap()
        else {
            panic!("a contact zone");
        };
        let settings = unilateral_contact::SolveSettings {
            tightening: 0.0,
            ..pb.settings.clone()
        };
        let sol = unilateral_contact::solve(&pb.zone, &settings).unwrap();
        let cols = scheme_columns(&sol).unwrap();
        assert_eq!(cols.len(), 1, "{cols:?}");
        assert_eq!(
            cols[0].states,
            [PairState::Open, PairState::Stick, PairState::Stick]
        );
    }

    /// The working-scheme map starts at p = 0: the cylinder settles its start by pivots at
    /// loads of round-off (8.5e-13), after which the map's first column began (its axis read
    /// "8.466e-13"). Reference: the path's own start, p = 0.
    #[test]
    fn the_scheme_map_starts_at_the_start() {
        let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/cylinder-on-foundation.toml");
        let unilateral_io::Problem::Structural(pb) = unilateral_io::read_problem(&file).unwrap()
        else {
            panic!("a structural model");
        };
        let sol = unilateral_analysis::analyze(&pb.model, &pb.settings)
            .unwrap()
            .solution;
        assert!(sol.steps.iter().any(|s| s.settling && s.p > 0.0));
        // its pivots at loads of round-off settle the start, those after a wander to 7e-9
        // and back too (the summary says "settled by 4 pivots")
        assert_eq!(sol.steps.iter().filter(|s| s.settling).count(), 4);
        assert_eq!(sol.path.breakpoints[0].p, 0.0);
        let cols = scheme_columns(&sol).unwrap();
        assert_eq!(cols[0].p_from, 0.0, "{:?}", cols[0].p_from);
    }

    /// The working-scheme map of Example 3 (c = 1000): one column per segment of the traced path
    /// along which the load moves, and from one column to the next exactly the pairs named by the
    /// events of the steps in between change state (opens → open, closes → pressed, slips ± →
    /// slip ±, sticks → stick). Reference: the path's events, read from its leaving variables
    /// (`ContactSolution::steps`), not from any value. The last column (the ray beyond the last
    /// breakpoint) has the last event applied. The reported load p = 1 is marked.
    #[test]
    fn scheme_map_changes_exactly_at_the_events() {
        use unilateral_contact::EventKind;
        let sol = solve_example3();
        let cols = scheme_columns(&sol).unwrap();
        let moving = sol
            .path
            .breakpoints
            .windows(2)
            .filter(|w| w[1].p != w[0].p)
            .count();
        // the ray beyond the last breakpoint is one more column
        assert_eq!(cols.len(), moving + 1);
        for w in cols.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            // the steps from the end of column a to the start of column b
            let events: Vec<_> = sol.steps[a.segment..b.segment]
                .iter()
                .flat_map(|st| st.events.iter())
                .filter(|e| !e.while_open)
                .collect();
            for (i, (sa, sb)) in a.states.iter().zip(&b.states).enumerate() {
                let named: Vec<_> = events.iter().filter(|e| e.pair == i).collect();
                match named.last() {
                    None => assert_eq!(
                        sa, sb,
                        "pair {i} between segments {} and {}",
                        a.segment, b.segment
                    ),
                    Some(e) => {
                        let want = match e.kind {
                            EventKind::Opens => vec![PairState::Open],
                            EventKind::Closes => {
                                vec![PairState::Stick, PairState::SlipPlus, PairState::SlipMinus]
                            }
                            EventKind::StartsSlippingPlus => vec![PairState::SlipPlus],
                            EventKind::StartsSlippingMinus => vec![PairState::SlipMinus],
                            EventKind::Sticks => vec![PairState::Stick],
                        };
                        assert!(want.contains(sb), "pair {i} after {e}: {sb}");
                    }
                }
            }
        }
        let svg = scheme_map_svg(&sol, &cols);
        assert!(
            svg.contains("<title>reported p = 1</title>"),
            "reported load marked"
        );
        assert!(svg.contains("tightening c = 1000"));
    }
}
