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

/// Evaluates the solution without tightening at `p = 0`, at every event load and at the end
/// (above [`MAX_SAMPLES`] loads, at that many spread evenly over them by their index)
/// (by the engine kept in the solution: nothing is solved or prepared again). A load off the
/// traced path is skipped; an error of the solution at a load is returned. The loads are
/// evaluated in one walk along the path ([`ContactSolution::at_many`]).
pub fn samples(sol: &ContactSolution) -> Result<PathSamples, ContactError> {
    let mut want: Vec<f64> = vec![0.0];
    want.extend(
        sol.steps
            .iter()
            .map(|s| s.p)
            .filter(|p| p.is_finite() && *p >= 0.0),
    );
    if let Some(e) = end_load(sol) {
        want.push(e);
    }
    let mut loads: Vec<f64> = Vec::with_capacity(want.len());
    for p in want {
        if loads
            .last()
            .is_some_and(|q: &f64| (q - p).abs() <= 1e-12 * p.abs().max(1.0))
        {
            continue;
        }
        loads.push(p);
    }
    let loads = thin(loads, MAX_SAMPLES);
    let mut out = PathSamples {
        loads: Vec::new(),
        pairs: Vec::new(),
    };
    for (p, at) in loads.iter().copied().zip(sol.at_many(&loads)?) {
        if let Some((pairs, _)) = at {
            out.loads.push(p);
            out.pairs.push(pairs);
        } else if sol
            .p
            .is_some_and(|q| (q - p).abs() <= 1e-12 * p.abs().max(1.0))
        {
            out.loads.push(p);
            out.pairs.push(sol.pairs.clone());
        }
    }
    Ok(out)
}

/// At most this many loads are evaluated for the charts: a panel is 180 px wide, and each
/// evaluation removes the tightening by pivots (the cost of the report).
pub const MAX_SAMPLES: usize = 200;

/// The loads thinned to at most `max` (`max ≥ 2`), evenly by their index along the path, the
/// first and the last kept.
fn thin(loads: Vec<f64>, max: usize) -> Vec<f64> {
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
pub fn chart(
    sol: &ContactSolution,
    s: &PathSamples,
    selected: &[usize],
    kind: ChartKind,
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
    let (title, a_lab, b_lab, what) = match kind {
        ChartKind::Forces => (
            "Load path: contact forces of the pairs",
            "x_n (normal force, compression +)",
            "x_t (tangential force)",
            "forces",
        ),
        ChartKind::Displacements => (
            "Load path: mutual displacements of the pairs",
            "z_n (opening +)",
            "z_t (slip)",
            "mutual displacements",
        ),
    };
    let mut caption = format!(
        "The {what} of each pair against the load p, exact at p = 0, at every event and at the end, straight in between. Each panel has its own vertical scale. Red marks: events of the pair (numbers as in the list below); grey lines: events of other pairs."
    );
    if sol.tightening > 0.0 {
        caption.push_str(&format!(
            " The values are those of the solution without tightening; the events are those of the path traced with the tightening c = {}, and the scheme without it may change at other loads.",
            num(sol.tightening)
        ));
    }
    let total = s.pairs.first().map_or(0, |p| p.len());
    let many = total > MANY_PAIRS;
    let many_events = sol.steps.len() > MANY_EVENTS;
    if many {
        caption.push_str(&format!(
            " Of the {total} pairs, {} panels are shown{}.",
            selected.len(),
            if kind == ChartKind::Forces {
                "; the map below the panels shows the state of every pair at every sampled load"
            } else {
                " (the forces chart has a map of the states of all pairs)"
            }
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
        .filter(|_| !many_events)
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
    let map_h = if many && kind == ChartKind::Forces && s.loads.len() >= 2 {
        map_height(total)
    } else {
        0.0
    };
    let height = top + panels_h + 30.0 + ev_rows as f64 * 14.0 + 20.0 + map_h;

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
    g.math(a_lab, 50.0, ly, 9.0, Anchor::Start, "#222222");
    let x2 = 50.0 + font::width_rich(a_lab, 9.0) + 30.0;
    g.line(
        (x2, ly - 3.0),
        (x2 + 24.0, ly - 3.0),
        C_TANGENT,
        2.0,
        r#" stroke-dasharray="5 3""#,
    );
    g.math(b_lab, x2 + 30.0, ly, 9.0, Anchor::Start, "#222222");
    let x3 = x2 + 30.0 + font::width_rich(b_lab, 9.0) + 30.0;
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
        g.text(
            "no load path to draw (no solution along the path)",
            20.0,
            top + 20.0,
            10.0,
            Anchor::Start,
            "#b3261e",
        );
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
        // events of all pairs: faint lines; of this pair: marks and numbers
        let mut own: Vec<(f64, usize)> = Vec::new();
        for st in &sol.steps {
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
        let state = sol
            .pairs
            .get(pi)
            .map(|r| format!("  ({})", r.state))
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
    if map_h > 0.0 {
        let my = ey + ev_rows as f64 * 14.0 + 10.0;
        state_map(&mut g, s, &names, my, width);
    }
    g.finish()
}

/// Height of the state map of `m` pairs (title, rows, axis).
fn map_height(m: usize) -> f64 {
    MAP_HEAD + (m as f64 * 2.0).clamp(60.0, 600.0) + 40.0
}

const MAP_HEAD: f64 = 40.0;

/// The states of all pairs at every sampled load, one row per pair and one column per sample,
/// drawn as one rectangle per run of a non-open state along a row (open is the background).
fn state_map(g: &mut Svg, s: &PathSamples, names: &[String], y0: f64, width: f64) {
    let m = s.pairs.first().map_or(0, |p| p.len());
    let k = s.loads.len();
    let (left, right) = (72.0, 20.0);
    let w = width - left - right;
    let h = (m as f64 * 2.0).clamp(60.0, 600.0);
    let top = y0 + MAP_HEAD;
    g.text(
        "States of all pairs over the load (one row per pair, one column per sampled load)",
        20.0,
        y0 + 12.0,
        10.0,
        Anchor::Start,
        "#111111",
    );
    let mut lx = 20.0;
    for st in [
        PairState::Open,
        PairState::Stick,
        PairState::SlipPlus,
        PairState::SlipMinus,
    ] {
        let (fill, word) = state_style(st);
        g.rect(lx, y0 + 20.0, 9.0, 9.0, fill, "#333333", 0.6);
        g.text(word, lx + 13.0, y0 + 28.0, 8.5, Anchor::Start, "#222222");
        lx += 13.0 + font::width(word, 8.5) + 18.0;
    }
    let (cw, rh) = (w / k as f64, h / m.max(1) as f64);
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
        let state_at = |j: usize| s.pairs[j].get(i).map(|r| r.state);
        let mut j = 0;
        while j < k {
            let st = state_at(j);
            let mut e = j + 1;
            while e < k && state_at(e) == st {
                e += 1;
            }
            if let Some(st) = st.filter(|&v| v != PairState::Open) {
                let x = left + j as f64 * cw;
                g.rect(
                    x,
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
    // pair names at the first and last rows, loads at a few columns
    for i in [0, m.saturating_sub(1)] {
        if let Some(nm) = names.get(i) {
            g.text(
                nm,
                left - 4.0,
                top + (i as f64 + 0.5) * rh + 3.0,
                8.0,
                Anchor::End,
                "#444444",
            );
        }
    }
    let marks = 5.min(k);
    for t in 0..marks {
        let j = if marks > 1 {
            t * (k - 1) / (marks - 1)
        } else {
            0
        };
        let x = left + (j as f64 + 0.5) * cw;
        g.line((x, top + h), (x, top + h + 4.0), "#444444", 0.6, "");
        g.text(
            &format!("p = {}", num(s.loads[j])),
            x,
            top + h + 14.0,
            8.0,
            Anchor::Middle,
            "#444444",
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
        (0..self.lcp.pairs).map(|i| (i + 1).to_string()).collect()
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
        let s = PathSamples {
            loads: vec![0.0, 1.0, 2.0, 3.0],
            pairs: (0..4)
                .map(|j| (0..3).map(|i| pair(i, 1.0, 0.0, rows[i][j])).collect())
                .collect(),
        };
        let names: Vec<String> = (0..3).map(|i| format!("s{i}")).collect();
        let mut g = Svg::new(400.0, 300.0, "map");
        state_map(&mut g, &s, &names, 0.0, 400.0);
        let svg = g.finish();
        assert_eq!(svg.matches("<rect").count(), 10, "{svg}");
    }
}
