//! A tiny hand-written SVG writer: shapes, text, number formatting, nice ticks and colour maps.
//!
//! Text is written in one of two ways ([`TextMode`]), chosen once for every picture drawn
//! through [`Svg`]: as strokes of the built-in font ([`font`]), so that a
//! standalone `.svg` renders the same on a machine without any font (PNG conversion), or as
//! real SVG `<text>`, which a browser shows in any script and which can be searched and
//! copied (the pictures inside `report.html`). The mode is taken when a picture is started:
//! [`with_text_mode`] draws a picture in another mode without any change to its drawing code.

use std::cell::Cell;
use std::fmt::Write as _;

use crate::font::{self, Anchor};

/// A coordinate with at most two decimals (`-0` written as `0`).
pub fn n(v: f64) -> String {
    let mut s = String::with_capacity(12);
    push_n(&mut s, v);
    s
}

/// [`n`] appended to `s` (no allocation of its own).
pub fn push_n(s: &mut String, v: f64) {
    let c = (v * 100.0).round();
    if c == 0.0 || !c.is_finite() || c.abs() >= 9.0e15 {
        // zero, and (never drawn) the non-finite and the huge: the general formatting
        let r = c / 100.0;
        if r == 0.0 {
            s.push('0');
            return;
        }
        let t = format!("{r:.2}");
        s.push_str(t.trim_end_matches('0').trim_end_matches('.'));
        return;
    }
    // Hundredths as an integer: the same digits as `{:.2}` of the rounded value, without
    // the exact float formatting (the drawing's hot spot).
    let h = c as i64;
    let (int, frac) = (h.unsigned_abs() / 100, h.unsigned_abs() % 100);
    if h < 0 {
        s.push('-');
    }
    s.push_str(itoa::Buffer::new().format(int));
    if frac != 0 {
        // `.d` or `.dd`, the digits of `frac` without a trailing zero
        s.push('.');
        s.push(char::from(b'0' + (frac / 10) as u8));
        if frac % 10 != 0 {
            s.push(char::from(b'0' + (frac % 10) as u8));
        }
    }
}

/// XML escaping for attribute values and text content.
pub fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&apos;"),
            _ => o.push(c),
        }
    }
    o
}

/// A number for people: four significant digits, exponent form outside `[1e-3, 1e5)`, a real
/// minus sign.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    let s = if !(1e-3..1e5).contains(&a) {
        let e = a.log10().floor() as i32;
        let m = a / 10f64.powi(e);
        let (m, e) = if format!("{m:.3}").starts_with("10") {
            (m / 10.0, e + 1)
        } else {
            (m, e)
        };
        let ms = format!("{m:.3}");
        let ms = ms.trim_end_matches('0').trim_end_matches('.');
        format!("{ms}e{e}")
    } else {
        let digits = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{a:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    };
    if v < 0.0 {
        format!("−{s}")
    } else {
        s
    }
}

/// Nice tick values covering `[lo, hi]` (about `count` of them).
pub fn ticks(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    if hi.is_nan() || lo.is_nan() || hi <= lo {
        return vec![lo];
    }
    let raw = (hi - lo) / count.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|k| k * mag)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// Rounds a range outwards to nice ticks: returns `(lo, hi)`.
pub fn nice_range(lo: f64, hi: f64) -> (f64, f64) {
    let (lo, hi) = if hi - lo <= f64::EPSILON * (lo.abs() + hi.abs()).max(1e-300) {
        let d = if lo == 0.0 { 1.0 } else { lo.abs() * 0.5 };
        (lo - d, hi + d)
    } else {
        (lo, hi)
    };
    let t = ticks(lo, hi, 5);
    let step = if t.len() >= 2 { t[1] - t[0] } else { hi - lo };
    ((lo / step).floor() * step, (hi / step).ceil() * step)
}

/// How the text of a picture is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TextMode {
    /// Strokes of the built-in font, the text itself kept in a `<title>` (the default: the
    /// standalone `.svg` files, which must render with no fonts).
    #[default]
    Strokes,
    /// Real SVG `<text>` in the browser's sans-serif font: any script, searchable (the
    /// pictures inline in HTML).
    Real,
}

thread_local! {
    static TEXT_MODE: Cell<TextMode> = const { Cell::new(TextMode::Strokes) };
}

/// Runs `draw` with every [`Svg`] started inside it writing its text in `mode` (on this
/// thread; the previous mode is restored afterwards, also when `draw` panics).
pub fn with_text_mode<T>(mode: TextMode, draw: impl FnOnce() -> T) -> T {
    struct Restore(TextMode);
    impl Drop for Restore {
        fn drop(&mut self) {
            TEXT_MODE.with(|m| m.set(self.0));
        }
    }
    let _restore = Restore(TEXT_MODE.with(|m| m.replace(mode)));
    draw()
}

/// The text mode in force on this thread (see [`with_text_mode`]).
pub fn text_mode() -> TextMode {
    TEXT_MODE.with(|m| m.get())
}

/// Ratio of the font size of real text to the cap height the stroke font is sized by (the
/// cap height of common sans-serif faces is about 0.7 em).
const EM_PER_CAP: f64 = 1.4;

/// An SVG document being written.
pub struct Svg {
    body: String,
    mode: TextMode,
    title: String,
    /// The rightmost end of the horizontal text drawn (the picture is widened to hold it).
    right: f64,
    /// The leftmost start of the horizontal text drawn (the picture is shifted right and
    /// widened to hold it, when it starts before the left edge).
    left: f64,
    /// Width in pixels.
    pub width: f64,
    /// Height in pixels.
    pub height: f64,
}

impl Svg {
    /// An empty picture with a white background and a title (for accessibility).
    pub fn new(width: f64, height: f64, title: &str) -> Self {
        Svg {
            body: String::new(),
            mode: text_mode(),
            title: title.to_string(),
            right: 0.0,
            left: 0.0,
            width,
            height,
        }
    }

    /// Raw SVG markup.
    pub fn raw(&mut self, s: &str) {
        self.body.push_str(s);
        self.body.push('\n');
    }

    /// A straight line.
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), stroke: &str, width: f64, extra: &str) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{stroke}" stroke-width="{}"{extra}/>"#,
            n(a.0),
            n(a.1),
            n(b.0),
            n(b.1),
            n(width)
        );
    }

    /// An open polyline.
    pub fn polyline(&mut self, pts: &[(f64, f64)], stroke: &str, width: f64, extra: &str) {
        if pts.len() < 2 {
            return;
        }
        let _ = writeln!(
            self.body,
            r#"<polyline points="{}" fill="none" stroke="{stroke}" stroke-width="{}" stroke-linejoin="round"{extra}/>"#,
            points(pts),
            n(width)
        );
    }

    /// A closed polygon.
    pub fn polygon(
        &mut self,
        pts: &[(f64, f64)],
        fill: &str,
        stroke: &str,
        width: f64,
        extra: &str,
    ) {
        let _ = writeln!(
            self.body,
            r#"<polygon points="{}" fill="{fill}" stroke="{stroke}" stroke-width="{}" stroke-linejoin="round"{extra}/>"#,
            points(pts),
            n(width)
        );
    }

    /// A rectangle.
    #[allow(clippy::too_many_arguments)]
    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: &str, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="{stroke}" stroke-width="{}"/>"#,
            n(x),
            n(y),
            n(w),
            n(h),
            n(width)
        );
    }

    /// A circle.
    pub fn circle(&mut self, c: (f64, f64), r: f64, fill: &str, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<circle cx="{}" cy="{}" r="{}" fill="{fill}" stroke="{stroke}" stroke-width="{}"/>"#,
            n(c.0),
            n(c.1),
            n(r),
            n(width)
        );
    }

    /// An arrow from `a` to `b` (head at `b`).
    pub fn arrow(&mut self, a: (f64, f64), b: (f64, f64), color: &str, width: f64, head: f64) {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let l = dx.hypot(dy);
        if l < 1e-9 {
            return;
        }
        let (ux, uy) = (dx / l, dy / l);
        let h = head.min(0.6 * l).max(0.5 * head.min(l));
        let base = (b.0 - ux * h, b.1 - uy * h);
        self.line(a, base, color, width, r#" stroke-linecap="round""#);
        let w = 0.45 * h;
        self.polygon(
            &[
                b,
                (base.0 - uy * w, base.1 + ux * w),
                (base.0 + uy * w, base.1 - ux * w),
            ],
            color,
            "none",
            0.0,
            "",
        );
    }

    /// The way this picture writes its text.
    pub fn mode(&self) -> TextMode {
        self.mode
    }

    /// Text (plain).
    pub fn text(&mut self, s: &str, x: f64, y: f64, size: f64, anchor: Anchor, color: &str) {
        self.text_full(s, x, y, size, anchor, 0.0, color, false);
    }

    /// A chart's title (13 px at the top left) and its caption lines below it (9 px, 14 px
    /// apart from y = 46), as every chart of the report starts.
    pub fn heading(&mut self, title: &str, caption: &[String]) {
        self.text(title, 20.0, 26.0, 13.0, Anchor::Start, "#111111");
        for (i, l) in caption.iter().enumerate() {
            self.text(
                l,
                20.0,
                46.0 + 14.0 * i as f64,
                9.0,
                Anchor::Start,
                "#444444",
            );
        }
    }

    /// Text with subscripts (`z_n`).
    pub fn math(&mut self, s: &str, x: f64, y: f64, size: f64, anchor: Anchor, color: &str) {
        self.text_full(s, x, y, size, anchor, 0.0, color, true);
    }

    /// Text rotated `angle` degrees counter-clockwise, with subscripts when `rich`; its
    /// baseline passes through `(x, y)` and `size` is its cap height in pixels.
    #[allow(clippy::too_many_arguments)]
    pub fn text_full(
        &mut self,
        s: &str,
        x: f64,
        y: f64,
        size: f64,
        anchor: Anchor,
        angle: f64,
        color: &str,
        rich: bool,
    ) {
        if s.trim().is_empty() {
            return;
        }
        if angle == 0.0 {
            let w = if rich {
                font::width_rich(s, size)
            } else {
                font::width(s, size)
            };
            let (start, end) = match anchor {
                Anchor::Start => (x, x + w),
                Anchor::Middle => (x - w / 2.0, x + w / 2.0),
                Anchor::End => (x - w, x),
            };
            self.right = self.right.max(end);
            self.left = self.left.min(start);
        }
        if self.mode == TextMode::Real {
            self.real_text(s, x, y, size, anchor, angle, color, rich);
            return;
        }
        let d = font::path_data(s, x, y, size, anchor, angle, rich);
        let _ = writeln!(
            self.body,
            r#"<path d="{d}" fill="none" stroke="{color}" stroke-width="{}" stroke-linecap="round" stroke-linejoin="round"><title>{}</title></path>"#,
            n((size / 8.0).max(0.8)),
            esc(s)
        );
    }

    #[allow(clippy::too_many_arguments)]
    fn real_text(
        &mut self,
        s: &str,
        x: f64,
        y: f64,
        size: f64,
        anchor: Anchor,
        angle: f64,
        color: &str,
        rich: bool,
    ) {
        let anchor = match anchor {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        };
        let rotate = if angle != 0.0 {
            format!(r#" transform="rotate({} {} {})""#, n(-angle), n(x), n(y))
        } else {
            String::new()
        };
        let _ = write!(
            self.body,
            r#"<text x="{}" y="{}" font-size="{}" font-family="sans-serif" text-anchor="{anchor}" fill="{color}" xml:space="preserve"{rotate}>"#,
            n(x),
            n(y),
            n(size * EM_PER_CAP)
        );
        if rich {
            // `z_n`, `x_{t+}`: subscripts as the stroke font draws them
            let mut it = s.chars().peekable();
            let mut plain = String::new();
            while let Some(c) = it.next() {
                if c == '_' && it.peek().is_some() {
                    let mut sub = String::new();
                    if it.peek() == Some(&'{') {
                        it.next();
                        for d in it.by_ref() {
                            if d == '}' {
                                break;
                            }
                            sub.push(d);
                        }
                    } else if let Some(d) = it.next() {
                        sub.push(d);
                    }
                    self.body.push_str(&esc(&std::mem::take(&mut plain)));
                    let _ = write!(
                        self.body,
                        r#"<tspan baseline-shift="sub" font-size="{}">{}</tspan>"#,
                        n(0.7 * size * EM_PER_CAP),
                        esc(&sub),
                    );
                } else {
                    plain.push(c);
                }
            }
            self.body.push_str(&esc(&plain));
        } else {
            self.body.push_str(&esc(s));
        }
        self.body.push_str("</text>\n");
    }

    /// The finished document.
    pub fn finish(self) -> String {
        // wide enough for every line of text drawn (a long title on a one-panel chart ran
        // past the right edge and was cut; long pair names right-aligned on the scheme map's
        // left edge ran off it): the drawing shifted right by what runs off the left
        let shift = if self.left < 0.0 {
            (12.0 - self.left).ceil()
        } else {
            0.0
        };
        let width = (self.width + shift).max((self.right + shift + 12.0).ceil());
        let body = if shift > 0.0 {
            format!(
                "<g transform=\"translate({} 0)\">\n{}</g>\n",
                n(shift),
                self.body
            )
        } else {
            self.body
        };
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<title>{}</title>\n<rect x=\"0\" y=\"0\" width=\"{w}\" height=\"{h}\" fill=\"#ffffff\"/>\n{body}</svg>\n",
            esc(&self.title),
            w = n(width),
            h = n(self.height)
        )
    }
}

fn points(pts: &[(f64, f64)]) -> String {
    let mut s = String::new();
    for (i, p) in pts.iter().enumerate() {
        if i > 0 {
            s.push(' ');
        }
        push_n(&mut s, p.0);
        s.push(',');
        push_n(&mut s, p.1);
    }
    s
}

/// A colour `#rrggbb` from components in `[0, 1]`.
pub fn rgb(r: f64, g: f64, b: f64) -> String {
    let c = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", c(r), c(g), c(b))
}

fn interp(stops: &[(f64, [f64; 3])], t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    for w in stops.windows(2) {
        let (t0, c0) = w[0];
        let (t1, c1) = w[1];
        if t <= t1 {
            let s = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
            return rgb(
                c0[0] + s * (c1[0] - c0[0]),
                c0[1] + s * (c1[1] - c0[1]),
                c0[2] + s * (c1[2] - c0[2]),
            );
        }
    }
    let c = stops[stops.len() - 1].1;
    rgb(c[0], c[1], c[2])
}

/// A sequential colour map (dark blue → teal → yellow) for `t` in `[0, 1]`.
pub fn sequential(t: f64) -> String {
    interp(
        &[
            (0.0, [0.267, 0.005, 0.329]),
            (0.25, [0.230, 0.322, 0.546]),
            (0.5, [0.128, 0.567, 0.551]),
            (0.75, [0.369, 0.789, 0.383]),
            (1.0, [0.993, 0.906, 0.144]),
        ],
        t,
    )
}

/// A diverging colour map (blue → white → red) for `t` in `[0, 1]` (white at 0.5).
pub fn diverging(t: f64) -> String {
    interp(
        &[
            (0.0, [0.13, 0.40, 0.67]),
            (0.5, [0.97, 0.97, 0.97]),
            (1.0, [0.70, 0.09, 0.17]),
        ],
        t,
    )
}

#[cfg(test)]
mod tests {

    /// A line of text longer than the picture widens it (a chart of one panel, 330 px, had a
    /// title of 360 px cut at its edge): the width holds every horizontal line drawn, and
    /// the background covers it. Reference: the font's own width of the line.
    #[test]
    fn the_picture_holds_its_text() {
        let line = "Load path: contact forces of the pairs (traced with the tightening c = 1)";
        let mut g = Svg::new(330.0, 100.0, "t");
        g.text(line, 20.0, 26.0, 13.0, Anchor::Start, "#111111");
        let out = g.finish();
        let want = 20.0 + font::width(line, 13.0);
        assert!(want > 330.0);
        let w: f64 = out
            .split("width=\"")
            .nth(1)
            .and_then(|r| r.split('"').next())
            .unwrap()
            .parse()
            .unwrap();
        assert!(w >= want, "{w} < {want}");
        assert!(out.contains(&format!("<rect x=\"0\" y=\"0\" width=\"{}\"", n(w))));
        // a short one leaves the width as asked
        let mut g = Svg::new(330.0, 100.0, "t");
        g.text("short", 20.0, 26.0, 13.0, Anchor::Start, "#111111");
        let out = g.finish();
        assert!(out.contains("width=\"330\"") && !out.contains("translate"));
        // a label right-aligned near the left edge and longer than the room there shifts the
        // drawing right by what runs off, and widens it as much
        let label = "a_pair_name_of_sixty_four_characters_on_a_continuous_beam_1";
        let mut g = Svg::new(330.0, 100.0, "t");
        g.text(label, 56.0, 60.0, 9.0, Anchor::End, "#111111");
        let off = font::width(label, 9.0) - 56.0;
        assert!(off > 0.0);
        let out = g.finish();
        let shift = (12.0 + off).ceil();
        assert!(
            out.contains(&format!("translate({} 0)", n(shift))),
            "{}",
            &out[..300]
        );
        assert!(out.contains(&format!("width=\"{}\"", n(330.0 + shift))));
    }

    use super::*;

    #[test]
    fn numbers_read_well() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(1.5), "1.5");
        assert_eq!(num(-0.25), "−0.25");
        assert_eq!(num(1562.6), "1563");
        assert_eq!(num(1.5626e6), "1.563e6");
        assert_eq!(num(2.0e-5), "2e-5");
        assert_eq!(n(-0.001), "0");
        // the same text as the rounded value written with two decimals, trailing zeros cut
        for v in [
            0.004,
            0.005,
            -0.015,
            1.0,
            12.5,
            -12.5,
            3.14259,
            99.999,
            -0.3,
            1e6 + 0.25,
        ]
        .into_iter()
        // every hundredth from -20 to 20, and values between them, of every sign and size
        .chain((-200_000..200_000).map(|i| f64::from(i) * 0.000_1 + 0.000_049))
        .chain((0..2000).map(|i| (-1.0f64).powi(i) * 1.37f64.powi(i / 20) * 0.731))
        {
            let r = (v * 100.0f64).round() / 100.0;
            let want = format!("{r:.2}");
            let want = want.trim_end_matches('0').trim_end_matches('.');
            assert_eq!(n(v), if r == 0.0 { "0" } else { want }, "{v}");
        }
    }

    // Reference: the two modes' definitions. Strokes: a path with the text only in its
    // <title>; real: a <text> element whose content is the name itself (any script), escaped.
    #[test]
    fn text_is_strokes_or_real_text() {
        let draw = || {
            let mut g = Svg::new(100.0, 50.0, "t");
            g.text("опора.2 <a&b>", 10.0, 20.0, 8.0, Anchor::Start, "#222222");
            g.math("z_n", 10.0, 40.0, 8.0, Anchor::End, "#222222");
            g.finish()
        };
        let strokes = draw();
        assert!(strokes.contains("<path d=\"M"));
        assert!(strokes.contains("<title>опора.2 &lt;a&amp;b&gt;</title>"));
        assert!(!strokes.contains("<text"));
        let real = with_text_mode(TextMode::Real, draw);
        assert!(real.contains(
            r##"<text x="10" y="20" font-size="11.2" font-family="sans-serif" text-anchor="start" fill="#222222" xml:space="preserve">опора.2 &lt;a&amp;b&gt;</text>"##
        ));
        assert!(real.contains(r#"text-anchor="end""#));
        assert!(real.contains(">z<tspan"));
        assert!(!real.contains("<path"));
        // the mode is restored afterwards
        assert_eq!(text_mode(), TextMode::Strokes);
        assert_eq!(draw(), strokes);
    }

    #[test]
    fn ticks_are_nice() {
        assert_eq!(ticks(0.0, 1.0, 5).len(), 6);
        let (lo, hi) = nice_range(-0.3, 1.7);
        assert!(lo <= -0.3 && hi >= 1.7);
    }
}
