//! The pictures of a load history: the load–displacement curves of chosen pairs (a hysteresis
//! loop is drawn as one) and the states of all pairs over the history's pseudo-time.
//!
//! The curves are exact polylines: a history is piecewise linear in its pseudo-time with a
//! breakpoint at every step, so the straight line through the start (every pair unloaded:
//! `x_t = 0`, `z_t = 0`, every factor 0), every step and every stage end, in order, is the
//! curve itself.

use unilateral_contact::{EventKind, HistorySolution, PairResult, PairState, StageSolution};

use crate::font::{self, Anchor};
use crate::history::{check, factors_at, pseudo_time};
use crate::structure::state_style;
use crate::svg::{nice_range, num, ticks, Svg};
use crate::NonFiniteOutput;

/// What the curves show against the accumulated slip `z_t` (horizontal axis).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CurveKind {
    /// The tangential force `x_t`.
    TangentialForce,
    /// The factor of the named load case.
    Factor(String),
}

/// What to draw in the pictures of a history.
#[derive(Debug, Clone, Default)]
pub struct HistoryChartOptions {
    /// The pairs of the curves, by name (unknown names are skipped); `None`: the
    /// [`CURVE_PAIRS`] pairs whose slip and tangential force change most.
    pub pairs: Option<Vec<String>>,
}

/// The number of pairs the curves show when none are named.
pub const CURVE_PAIRS: usize = 6;

/// One breakpoint of the history: the stage it belongs to, whether it is the stage's end, the
/// pairs there (empty at the unloaded start: every `x_t`, `z_t` 0) and the factors there.
struct Breakpoint<'a> {
    stage: usize,
    end: bool,
    pairs: &'a [PairResult],
    factors: Vec<f64>,
}

/// The breakpoints of the history in order: the start, every step and every stage end.
fn points(h: &HistorySolution) -> Vec<Breakpoint<'_>> {
    let mut out = vec![Breakpoint {
        stage: 0,
        end: false,
        pairs: &[],
        factors: vec![0.0; h.cases.len()],
    }];
    for st in &h.stages {
        for step in &st.steps {
            out.push(Breakpoint {
                stage: st.stage,
                end: false,
                pairs: &step.pairs,
                factors: step.factors.clone(),
            });
        }
        out.push(Breakpoint {
            stage: st.stage,
            end: true,
            pairs: &st.pairs,
            factors: factors_at(st, st.s_end),
        });
    }
    out
}

fn range(v: impl Iterator<Item = f64>) -> f64 {
    let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    if hi >= lo {
        hi - lo
    } else {
        0.0
    }
}

/// The pairs of the curves: those named (in the given order, unknown names skipped), else the
/// `count` whose range of slip `z_t` plus range of tangential force `x_t` over the history,
/// each relative to the largest such range of all pairs, is largest (ties to the lower index),
/// in pair order.
pub fn curve_pairs(h: &HistorySolution, names: Option<&[String]>, count: usize) -> Vec<usize> {
    if let Some(want) = names {
        return want
            .iter()
            .filter_map(|w| h.names.iter().position(|n| n == w))
            .collect();
    }
    let m = h.names.len();
    let pts = points(h);
    let r = |i: usize, f: &dyn Fn(&PairResult) -> f64| {
        range(
            pts.iter()
                .map(|p| p.pairs.get(i).map_or(0.0, f))
                .chain([0.0]),
        )
    };
    let rz: Vec<f64> = (0..m).map(|i| r(i, &|p| p.z_t)).collect();
    let rx: Vec<f64> = (0..m).map(|i| r(i, &|p| p.x_t)).collect();
    crate::chart::most_changing(&rz, &rx, count)
}

/// The case whose factor changes most over the history (the first of equals), `None` without
/// cases.
pub fn busiest_case(h: &HistorySolution) -> Option<usize> {
    let pts = points(h);
    (0..h.cases.len())
        .map(|c| (c, range(pts.iter().map(|p| p.factors[c]))))
        .fold(None, |best: Option<(usize, f64)>, (c, r)| match best {
            Some((_, b)) if b >= r => best,
            _ => Some((c, r)),
        })
        .map(|(c, _)| c)
}

/// A colour per stage: a categorical palette for up to 10 stages, else a colour map.
fn stage_colour(stage: usize, stages: usize) -> String {
    const PALETTE: [&str; 10] = [
        "#1f5fa8", "#d9731a", "#2a9d3a", "#b3261e", "#7b4fb0", "#8c564b", "#d4479e", "#5f5f5f",
        "#a8a21f", "#17a2b8",
    ];
    if stages <= PALETTE.len() {
        PALETTE[(stage.max(1) - 1) % PALETTE.len()].to_string()
    } else {
        let t = (stage.max(1) - 1) as f64 / (stages - 1).max(1) as f64;
        crate::svg::sequential(0.9 * t)
    }
}

/// The load–displacement curves of chosen pairs over the history as an SVG document: per pair
/// one panel of `x_t` (or a case's factor) against the accumulated slip `z_t`, a polyline
/// through every breakpoint in order, coloured by stage, with a dot at every step and a
/// numbered ring at every stage end.
pub fn history_curves_svg(
    h: &HistorySolution,
    options: &HistoryChartOptions,
    kind: &CurveKind,
) -> Result<String, NonFiniteOutput> {
    check(h)?;
    let selected = curve_pairs(h, options.pairs.as_deref(), CURVE_PAIRS);
    let case = match kind {
        CurveKind::TangentialForce => None,
        CurveKind::Factor(name) => h.cases.iter().position(|c| c == name),
    };
    let (title, y_label) = match (kind, case) {
        (CurveKind::TangentialForce, _) => (
            "Load history: tangential force against accumulated slip".to_string(),
            "x_t (tangential force)".to_string(),
        ),
        (CurveKind::Factor(name), _) => (
            format!("Load history: factor of the case {name} against accumulated slip"),
            format!("factor of {name}"),
        ),
    };
    let n_stages = h.stages.len();
    let m = selected.len().max(1);
    let cols = m.clamp(1, 3);
    let rows = m.div_ceil(cols);
    let (pw, ph) = (250.0, 190.0);
    let (gap_x, gap_y) = (80.0, 70.0);
    let left = 80.0;
    let width = (left + cols as f64 * (pw + gap_x))
        .max(560.0)
        .max(font::width(&title, 13.0) + 40.0);
    let caption = format!(
        "Every breakpoint of the history in order, joined by straight lines (the exact path), \
         starting unloaded at the origin. Colour: the stage; dot: a change of the working \
         scheme; numbered ring: the end of that stage. A closed loop is a hysteresis loop: the \
         energy dissipated by friction over a cycle.{}",
        match (kind, case) {
            (CurveKind::Factor(name), None) => format!(" There is no case named {name}."),
            _ => String::new(),
        }
    );
    let cap = crate::chart::wrap(&caption, 9.0, width - 40.0);
    let legend_rows = if n_stages <= 10 {
        n_stages.div_ceil(4)
    } else {
        1
    };
    let top = 40.0 + cap.len() as f64 * 14.0 + 16.0 + legend_rows as f64 * 14.0 + 20.0;
    let height = top + rows as f64 * (ph + gap_y) + 10.0;
    let mut g = Svg::new(width, height, &title);
    g.heading(&title, &cap);
    // stage legend
    let ly = 46.0 + cap.len() as f64 * 14.0 + 10.0;
    if n_stages <= 10 {
        let colw = (width - 40.0) / 4.0;
        for st in &h.stages {
            let k = st.stage - 1;
            let (x, y) = (20.0 + (k % 4) as f64 * colw, ly + (k / 4) as f64 * 14.0);
            g.line(
                (x, y - 3.0),
                (x + 18.0, y - 3.0),
                &stage_colour(st.stage, n_stages),
                2.5,
                "",
            );
            let label = format!("{} {}", st.stage, st.name);
            let label = clip(&label, 8.5, colw - 30.0);
            g.text(&label, x + 24.0, y, 8.5, Anchor::Start, "#222222");
        }
    } else if n_stages > 0 {
        g.text(
            &format!("stages 1 to {n_stages}: colour from dark (first) to light (last)"),
            20.0,
            ly,
            8.5,
            Anchor::Start,
            "#222222",
        );
    }
    if selected.is_empty()
        || h.stages.is_empty()
        || (case.is_none() && kind != &CurveKind::TangentialForce)
    {
        g.text(
            "nothing to draw (no pair chosen, no stage run or no such case)",
            20.0,
            top + 20.0,
            10.0,
            Anchor::Start,
            "#b3261e",
        );
        return Ok(g.finish());
    }
    let pts = points(h);
    for (k, &pi) in selected.iter().enumerate() {
        let (r, c) = (k / cols, k % cols);
        let ox = left + c as f64 * (pw + gap_x);
        let oy = top + r as f64 * (ph + gap_y);
        let xy: Vec<(f64, f64)> = pts
            .iter()
            .map(|p| {
                let at = p.pairs.get(pi);
                let y = match case {
                    Some(c) => p.factors[c],
                    None => at.map_or(0.0, |r| r.x_t),
                };
                (at.map_or(0.0, |r| r.z_t), y)
            })
            .collect();
        let (zlo, zhi) = xy
            .iter()
            .fold((0.0f64, 0.0f64), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let (ylo, yhi) = xy
            .iter()
            .fold((0.0f64, 0.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
        let (x0, x1) = nice_range(zlo, zhi);
        let (y0, y1) = nice_range(ylo, yhi);
        let sx = |v: f64| ox + (v - x0) / (x1 - x0) * pw;
        let sy = |v: f64| oy + ph - (v - y0) / (y1 - y0) * ph;
        g.rect(ox, oy, pw, ph, "#ffffff", "#999999", 0.6);
        for t in ticks(x0, x1, 4) {
            let x = sx(t);
            g.line((x, oy), (x, oy + ph), "#eeeeee", 0.5, "");
            g.line((x, oy + ph), (x, oy + ph + 4.0), "#444444", 0.6, "");
            g.text(&num(t), x, oy + ph + 14.0, 8.0, Anchor::Middle, "#444444");
        }
        for t in ticks(y0, y1, 4) {
            let y = sy(t);
            g.line((ox, y), (ox + pw, y), "#eeeeee", 0.5, "");
            g.line((ox - 4.0, y), (ox, y), "#444444", 0.6, "");
            g.text(&num(t), ox - 6.0, y + 3.0, 8.0, Anchor::End, "#444444");
        }
        // the axes through zero
        if x0 < 0.0 && x1 > 0.0 {
            g.line((sx(0.0), oy), (sx(0.0), oy + ph), "#bbbbbb", 0.7, "");
        }
        if y0 < 0.0 && y1 > 0.0 {
            g.line((ox, sy(0.0)), (ox + pw, sy(0.0)), "#bbbbbb", 0.7, "");
        }
        let name = h.names.get(pi).map_or("?", String::as_str);
        g.text(
            &format!("pair {name}"),
            ox,
            oy - 8.0,
            10.0,
            Anchor::Start,
            "#111111",
        );
        g.math(
            "z_t (accumulated slip)",
            ox + pw / 2.0,
            oy + ph + 28.0,
            8.5,
            Anchor::Middle,
            "#222222",
        );
        g.text_full(
            &y_label,
            ox - 44.0,
            oy + ph / 2.0,
            8.5,
            Anchor::Middle,
            90.0,
            "#222222",
            true,
        );
        // the curve, stage by stage (each stage's polyline starts where the previous ended)
        let mut from = 0;
        for st in &h.stages {
            let to = pts
                .iter()
                .enumerate()
                .position(|(j, p)| j > from && p.end && p.stage == st.stage)
                .unwrap_or(pts.len() - 1);
            let line: Vec<(f64, f64)> =
                xy[from..=to].iter().map(|&(a, b)| (sx(a), sy(b))).collect();
            let colour = stage_colour(st.stage, n_stages);
            g.polyline(&line, &colour, 1.8, "");
            for (j, &(a, b)) in xy.iter().enumerate().take(to).skip(from + 1) {
                let _ = j;
                g.circle((sx(a), sy(b)), 2.2, &colour, "none", 0.0);
            }
            from = to;
        }
        // stage ends: a ring each, and one label per place listing the stages ending there
        let mut places: Vec<((f64, f64), Vec<usize>)> = Vec::new();
        for (p, &(a, b)) in pts.iter().zip(&xy) {
            if !p.end {
                continue;
            }
            let c = (sx(a), sy(b));
            g.circle(c, 3.6, "#ffffff", &stage_colour(p.stage, n_stages), 1.4);
            match places
                .iter_mut()
                .find(|q| (q.0 .0 - c.0).hypot(q.0 .1 - c.1) < 9.0)
            {
                Some(q) => q.1.push(p.stage),
                None => places.push((c, vec![p.stage])),
            }
        }
        for (c, stages) in &places {
            let label = stage_list(stages);
            let right = c.0 < ox + 0.6 * pw;
            let below = c.1 < oy + 14.0;
            let (x, anchor) = if right {
                (c.0 + 6.0, Anchor::Start)
            } else {
                (c.0 - 6.0, Anchor::End)
            };
            let y = if below { c.1 + 13.0 } else { c.1 - 5.0 };
            g.text(&label, x, y, 8.0, anchor, "#111111");
        }
    }
    Ok(g.finish())
}

/// The stages ending at one place: `2`, `1, 3`, `1, 3, 5`, or `1, 3 … 19 (10 stages)`.
fn stage_list(stages: &[usize]) -> String {
    let list = |v: &[usize]| {
        v.iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    match stages {
        [] => String::new(),
        v if v.len() <= 3 => list(v),
        v => format!(
            "{} … {} ({} stages)",
            list(&v[..2]),
            v[v.len() - 1],
            v.len()
        ),
    }
}

/// `s` cut to fit `w` pixels at `size`, with an ellipsis.
fn clip(s: &str, size: f64, w: f64) -> String {
    if font::width(s, size) <= w {
        return s.to_string();
    }
    let mut out: String = String::new();
    for ch in s.chars() {
        let next = format!("{out}{ch}…");
        if font::width(&next, size) > w {
            break;
        }
        out.push(ch);
    }
    format!("{out}…")
}

/// A run of one state of one pair over the pseudo-time `[t0, t1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateRun {
    /// Start (pseudo-time `stage − 1 + s`).
    pub t0: f64,
    /// End.
    pub t1: f64,
    /// The state on the run.
    pub state: PairState,
}

/// The state a pair had before an event that left it in `after` (the step records the state
/// of the segment that starts there): open before it closes; sticking before it starts to
/// slip; slipping in the direction of its tangential force at the limit (`x_t < 0`: `slip+`)
/// before it sticks; before it opens, the state it had before (`prev`) if closed, else stick.
fn before(kind: EventKind, at: &PairResult, prev: Option<PairState>) -> PairState {
    match kind {
        EventKind::Closes => PairState::Open,
        EventKind::StartsSlippingPlus | EventKind::StartsSlippingMinus => PairState::Stick,
        EventKind::Sticks => {
            if at.x_t < 0.0 {
                PairState::SlipPlus
            } else {
                PairState::SlipMinus
            }
        }
        EventKind::Opens => prev
            .filter(|s| *s != PairState::Open)
            .unwrap_or(PairState::Stick),
    }
}

fn stage_runs(st: &StageSolution, prev: &[PairState], pair: usize, runs: &mut Vec<StateRun>) {
    let t0 = pseudo_time(st.stage, 0.0);
    let t_end = pseudo_time(st.stage, st.s_end);
    let end_state = st.pairs.get(pair).map_or(PairState::Open, |p| p.state);
    let mut push = |a: f64, b: f64, s: PairState| {
        if b <= a {
            return; // a breakpoint, not a run (several changes at one s)
        }
        if let Some(last) = runs.last_mut() {
            if last.state == s && last.t1 >= a {
                last.t1 = last.t1.max(b);
                return;
            }
        }
        runs.push(StateRun {
            t0: a,
            t1: b,
            state: s,
        });
    };
    let Some(first) = st.steps.first() else {
        push(t0, t_end, end_state);
        return;
    };
    let at_first = first.pairs.get(pair);
    let first_state = at_first.map_or(end_state, |p| p.state);
    let initial = match (first.events.iter().find(|e| e.pair == pair), at_first) {
        (Some(e), Some(p)) => before(e.kind, p, prev.get(pair).copied()),
        _ => first_state,
    };
    push(t0, pseudo_time(st.stage, first.s), initial);
    for (j, step) in st.steps.iter().enumerate() {
        let a = pseudo_time(st.stage, step.s);
        let b = st
            .steps
            .get(j + 1)
            .map_or(t_end, |n| pseudo_time(st.stage, n.s));
        let s = step.pairs.get(pair).map_or(end_state, |p| p.state);
        push(a, b.max(a), s);
    }
}

/// The state of every pair over the pseudo-time of the history, as runs per pair. Between
/// breakpoints the state is that of the step that starts the segment; before the first step of
/// a stage it is the first step's state for a pair without an event there, else the state
/// the event left ([`StateRun`]); a stage without steps keeps the state of its end.
pub fn state_runs(h: &HistorySolution) -> Vec<Vec<StateRun>> {
    let m = h.names.len();
    let mut out = vec![Vec::new(); m];
    let mut prev: Vec<PairState> = vec![PairState::Open; m];
    let mut first = true;
    for st in &h.stages {
        for (i, runs) in out.iter_mut().enumerate() {
            stage_runs(st, if first { &[] } else { &prev }, i, runs);
        }
        prev = st.pairs.iter().map(|p| p.state).collect();
        first = false;
    }
    out
}

/// The states of all pairs over the history's pseudo-time (`stage − 1 + s` on the horizontal
/// axis, stage boundaries marked and numbered) as an SVG document: one row per pair, coloured
/// by state.
pub fn history_states_svg(h: &HistorySolution) -> Result<String, NonFiniteOutput> {
    check(h)?;
    let m = h.names.len();
    let n = h.stages.len();
    let title = "Load history: the states of all pairs over the pseudo-time";
    let label_rows = m <= 40;
    let name_w = if label_rows {
        h.names
            .iter()
            .map(|s| font::width(s, 8.0))
            .fold(30.0f64, f64::max)
            .min(140.0)
    } else {
        30.0
    };
    let left = 30.0 + name_w;
    let width = (left + 780.0).max(700.0);
    let w = width - left - 30.0;
    let row_h = if label_rows {
        12.0
    } else {
        (600.0 / m as f64).clamp(1.0, 6.0)
    };
    let grid_h = (m as f64 * row_h).max(12.0);
    let caption = format!(
        "One row per pair ({m} pairs), one column per pseudo-time t = stage − 1 + s; each stage \
         runs from t = K − 1 to t = K (numbered at the top). White: open."
    );
    let cap = crate::chart::wrap(&caption, 9.0, width - 40.0);
    let top = 40.0 + cap.len() as f64 * 14.0 + 30.0 + 24.0;
    let height = top + grid_h + 50.0;
    let mut g = Svg::new(width, height, title);
    g.text(title, 20.0, 26.0, 13.0, Anchor::Start, "#111111");
    for (i, l) in cap.iter().enumerate() {
        g.text(
            l,
            20.0,
            46.0 + 14.0 * i as f64,
            9.0,
            Anchor::Start,
            "#444444",
        );
    }
    let ly = 46.0 + cap.len() as f64 * 14.0 + 10.0;
    let mut lx = 20.0;
    for st in [
        PairState::Open,
        PairState::Stick,
        PairState::SlipPlus,
        PairState::SlipMinus,
    ] {
        let (fill, word) = state_style(st);
        g.rect(lx, ly - 8.0, 9.0, 9.0, fill, "#333333", 0.6);
        g.text(word, lx + 13.0, ly, 8.5, Anchor::Start, "#222222");
        lx += 13.0 + font::width(word, 8.5) + 18.0;
    }
    let t_max = n.max(1) as f64;
    let sx = |t: f64| left + t / t_max * w;
    g.rect(
        left,
        top,
        w,
        grid_h,
        state_style(PairState::Open).0,
        "#999999",
        0.6,
    );
    // Crisp edges: adjacent runs and rows meet without anti-aliased seams.
    g.raw(r#"<g shape-rendering="crispEdges">"#);
    for (i, runs) in state_runs(h).iter().enumerate() {
        let y = top + i as f64 * row_h;
        for r in runs {
            if r.state == PairState::Open || r.t1 <= r.t0 {
                continue;
            }
            g.rect(
                sx(r.t0),
                y,
                sx(r.t1) - sx(r.t0),
                row_h,
                state_style(r.state).0,
                "none",
                0.0,
            );
        }
        if label_rows {
            g.text(
                &clip(&h.names[i], 8.0, name_w),
                left - 4.0,
                y + row_h - 3.0,
                8.0,
                Anchor::End,
                "#444444",
            );
        }
    }
    g.raw("</g>");
    if !label_rows && m > 0 {
        g.text(
            &h.names[0],
            left - 4.0,
            top + 7.0,
            8.0,
            Anchor::End,
            "#444444",
        );
        g.text(
            &h.names[m - 1],
            left - 4.0,
            top + grid_h,
            8.0,
            Anchor::End,
            "#444444",
        );
    }
    // stage boundaries and numbers; the end of a stage not completed
    let every = n.div_ceil(20).max(1);
    for st in &h.stages {
        let (a, b) = (sx(st.stage as f64 - 1.0), sx(st.stage as f64));
        // Every stage boundary as a tick; through the map only for every `every`-th (all of
        // them up to 20 stages), so that many stages do not hide the states.
        let through = st.stage % every == 0;
        let (y0, y1) = if through {
            (top - 4.0, top + grid_h + 4.0)
        } else {
            (top - 4.0, top)
        };
        g.line((b, y0), (b, y1), "#333333", 0.8, "");
        if !through {
            g.line(
                (b, top + grid_h),
                (b, top + grid_h + 4.0),
                "#333333",
                0.8,
                "",
            );
        }
        if st.stage == 1 {
            g.line((a, top - 4.0), (a, top + grid_h + 4.0), "#333333", 0.8, "");
        }
        if st.stage % every == 0 || st.stage == 1 {
            let full = format!("{} {}", st.stage, st.name);
            let label = if font::width(&full, 8.5) <= b - a - 6.0 {
                full
            } else {
                st.stage.to_string()
            };
            g.text(
                &label,
                (a + b) / 2.0,
                top - 7.0,
                8.5,
                Anchor::Middle,
                "#111111",
            );
        }
        if st.s_end < 1.0 {
            let x = sx(pseudo_time(st.stage, st.s_end));
            g.line(
                (x, top),
                (x, top + grid_h),
                "#b3261e",
                1.6,
                r#" stroke-dasharray="4 2""#,
            );
            g.text(
                st.status.as_str(),
                x + 3.0,
                top + grid_h + 26.0,
                8.5,
                Anchor::Start,
                "#b3261e",
            );
        }
    }
    for t in ticks(0.0, t_max, 10.min(n.max(1))) {
        let x = sx(t);
        g.text(
            &num(t),
            x,
            top + grid_h + 14.0,
            8.0,
            Anchor::Middle,
            "#444444",
        );
    }
    g.text(
        "pseudo-time t (stage − 1 + s)",
        left + w / 2.0,
        top + grid_h + 38.0,
        9.0,
        Anchor::Middle,
        "#222222",
    );
    Ok(g.finish())
}
