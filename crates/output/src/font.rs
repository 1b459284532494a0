//! A small built-in stroke font: text drawn as SVG path strokes, so that pictures render the
//! same on a machine without any font installed.
//!
//! Each glyph is a set of polylines on a grid: `x` in `0..=4` (wider for a few), `y` upwards
//! with the baseline at 2, the x-height at 6, the cap height at 9 and descenders down to 0. A
//! point is written as two digits `xy`, points of a stroke are separated by spaces and strokes
//! by `|`. A stroke of one repeated point is a dot (drawn with round caps).

/// Height of capitals in grid units (baseline 2 to cap line 9).
const CAP: f64 = 7.0;
const BASE: f64 = 2.0;

fn glyph(c: char) -> Option<&'static str> {
    Some(match c {
        '0' => "19 39 48 43 32 12 03 08 19",
        '1' => "17 29 22|12 32",
        '2' => "08 19 39 48 46 02 42",
        '3' => "08 19 39 48 47 36 26|36 45 43 32 12 03",
        '4' => "32 39 04 44",
        '5' => "49 09 06 36 45 43 32 12 03",
        '6' => "48 39 19 08 03 12 32 43 45 36 06",
        '7' => "09 49 12",
        '8' => "19 39 48 47 36 16 07 08 19|16 05 03 12 32 43 45 36",
        '9' => "03 12 32 43 48 39 19 08 06 15 35 46",
        'A' => "02 29 42|15 35",
        'B' => "02 09 39 48 47 36 06|36 45 43 32 02",
        'C' => "48 39 19 08 03 12 32 43",
        'D' => "02 09 29 47 44 22 02",
        'E' => "49 09 02 42|06 36",
        'F' => "49 09 02|06 36",
        'G' => "48 39 19 08 03 12 32 43 45 25",
        'H' => "02 09|42 49|06 46",
        'I' => "19 39|29 22|12 32",
        'J' => "19 49|39 33 22 12 03",
        'K' => "02 09|49 05|16 42",
        'L' => "09 02 42",
        'M' => "02 09 25 49 42",
        'N' => "02 09 42 49",
        'O' => "19 39 48 43 32 12 03 08 19",
        'P' => "02 09 39 48 46 35 05",
        'Q' => "19 39 48 43 32 12 03 08 19|24 41",
        'R' => "02 09 39 48 46 35 05|25 42",
        'S' => "48 39 19 08 07 16 36 45 43 32 12 03",
        'T' => "09 49|29 22",
        'U' => "09 03 12 32 43 49",
        'V' => "09 22 49",
        'W' => "09 12 25 32 49",
        'X' => "09 42|49 02",
        'Y' => "09 25 49|25 22",
        'Z' => "09 49 02 42",
        'a' => "16 36 45 42|44 14 03 12 32 43",
        'b' => "09 02|05 16 36 45 43 32 12 03",
        'c' => "45 36 16 05 03 12 32 43",
        'd' => "49 42|45 36 16 05 03 12 32 43",
        'e' => "04 44 45 36 16 05 03 12 32 43",
        'f' => "39 29 18 12|06 36",
        'g' => "46 41 30 10 01|45 36 16 05 04 13 33 44",
        'h' => "09 02|05 16 36 45 42",
        'i' => "26 22|28 28",
        'j' => "36 31 20 10 01|38 38",
        'k' => "09 02|46 03|14 42",
        'l' => "19 29 22|12 32",
        'm' => "06 02|05 16 25 22|25 36 45 42",
        'n' => "06 02|05 16 36 45 42",
        'o' => "16 36 45 43 32 12 03 05 16",
        'p' => "06 00|05 16 36 45 43 32 12 03",
        'q' => "46 40|45 36 16 05 03 12 32 43",
        'r' => "06 02|04 26 46",
        's' => "45 36 16 05 14 34 43 32 12 03",
        't' => "18 13 22 32|06 36",
        'u' => "06 03 12 32 43|46 42",
        'v' => "06 22 46",
        'w' => "06 12 24 32 46",
        'x' => "06 42|46 02",
        'y' => "06 03 12 32 43|46 41 30 10 01",
        'z' => "06 46 02 42",
        '.' => "12 12",
        ',' => "12 01",
        ':' => "15 15|12 12",
        ';' => "15 15|12 01",
        '(' => "29 18 13 22",
        ')' => "09 18 13 02",
        '[' => "29 19 12 22",
        ']' => "09 19 12 02",
        '+' => "23 27|05 45",
        '-' => "05 35",
        '−' | '–' => "05 45",
        '=' => "04 44|06 46",
        '/' => "02 49",
        '_' => "01 41",
        '*' => "25 29|06 48|08 46",
        '%' => "02 49|08 08|43 43",
        '\'' => "29 27",
        '|' => "21 29",
        '!' => "29 24|22 22",
        '?' => "08 19 39 48 46 24 23|22 22",
        '<' => "47 05 43",
        '>' => "07 45 03",
        '≥' => "07 45 03|02 42",
        '≤' => "47 05 43|02 42",
        '±' => "24 28|06 46|03 43",
        '×' => "03 47|07 43",
        '·' => "25 25",
        '…' => "02 02|22 22|42 42",
        '→' => "05 45|27 45 23",
        '#' => "13 18|33 38|04 44|07 47",
        'σ' => "46 16 05 03 12 32 43 45 36",
        'τ' => "06 46|26 23 32",
        'Δ' => "02 29 42 02",
        'μ' => "06 00|03 12 32 43|46 42",
        _ => return None,
    })
}

/// Width of a space in grid units.
const SPACE: f64 = 3.5;

/// A glyph's strokes (grid units, left bearing one unit) and its advance.
type Glyph = (Vec<Vec<(f64, f64)>>, f64);

thread_local! {
    /// The glyphs parsed so far: a picture asks for the same few characters many times.
    static GLYPHS: std::cell::RefCell<std::collections::HashMap<char, std::rc::Rc<Glyph>>> =
        std::cell::RefCell::new(std::collections::HashMap::new());
}

fn strokes(c: char) -> std::rc::Rc<Glyph> {
    GLYPHS.with(|g| {
        if let Some(v) = g.borrow().get(&c) {
            return v.clone();
        }
        let v = std::rc::Rc::new(parse_strokes(c));
        g.borrow_mut().insert(c, v.clone());
        v
    })
}

fn parse_strokes(c: char) -> Glyph {
    if c == ' ' {
        return (Vec::new(), SPACE);
    }
    let def = glyph(c).unwrap_or("02 09 49 42 02"); // a box for anything unknown
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    for s in def.split('|') {
        let pts: Vec<(f64, f64)> = s
            .split_whitespace()
            .map(|p| {
                let b = p.as_bytes();
                (f64::from(b[0] - b'0'), f64::from(b[1] - b'0'))
            })
            .collect();
        out.push(pts);
    }
    let min = out
        .iter()
        .flatten()
        .map(|p| p.0)
        .fold(f64::INFINITY, f64::min);
    let max = out
        .iter()
        .flatten()
        .map(|p| p.0)
        .fold(f64::NEG_INFINITY, f64::max);
    for s in &mut out {
        for p in s.iter_mut() {
            p.0 += 1.0 - min;
        }
    }
    (out, max - min + 2.0)
}

/// Horizontal placement of a text relative to its anchor point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// The text starts at the point.
    Start,
    /// The text is centred on the point.
    Middle,
    /// The text ends at the point.
    End,
}

/// A run of the text: its characters and whether it is a subscript.
fn runs(s: &str, rich: bool) -> Vec<(char, bool)> {
    let mut out = Vec::new();
    let mut it = s.chars().peekable();
    while let Some(c) = it.next() {
        if rich && c == '_' {
            if it.peek() == Some(&'{') {
                it.next();
                for d in it.by_ref() {
                    if d == '}' {
                        break;
                    }
                    out.push((d, true));
                }
                continue;
            }
            if let Some(d) = it.next() {
                out.push((d, true));
                continue;
            }
        }
        out.push((c, false));
    }
    out
}

const SUB_SCALE: f64 = 0.7;

/// The width of a text in pixels for a cap height `size` (plain text, no subscripts).
pub fn width(s: &str, size: f64) -> f64 {
    layout_width(&runs(s, false), size)
}

/// The width of a text with subscripts (`z_n`, `x_{t+}`).
pub fn width_rich(s: &str, size: f64) -> f64 {
    layout_width(&runs(s, true), size)
}

fn layout_width(r: &[(char, bool)], size: f64) -> f64 {
    let u = size / CAP;
    let units: f64 = r
        .iter()
        .map(|&(c, sub)| strokes(c).1 * if sub { SUB_SCALE } else { 1.0 })
        .sum();
    (units - 1.0).max(0.0) * u
}

/// Path data (`d` attribute) drawing `s` with its baseline through `(x, y)` (SVG coordinates,
/// `y` downwards), cap height `size` pixels, rotated by `angle` degrees counter-clockwise on
/// the page around the anchor point. With `rich`, `_x` and `_{xy}` are subscripts.
pub fn path_data(
    s: &str,
    x: f64,
    y: f64,
    size: f64,
    anchor: Anchor,
    angle: f64,
    rich: bool,
) -> String {
    let r = runs(s, rich);
    let u = size / CAP;
    let w = layout_width(&r, size);
    let mut pen = match anchor {
        Anchor::Start => 0.0,
        Anchor::Middle => -w / 2.0,
        Anchor::End => -w,
    } - u; // glyphs carry one unit of left bearing
    let (sin, cos) = angle.to_radians().sin_cos();
    let mut d = String::new();
    for (c, sub) in r {
        let k = if sub { SUB_SCALE } else { 1.0 };
        let drop = if sub { 1.2 * u } else { 0.0 };
        let g = strokes(c);
        let (glyph, adv) = (&g.0, g.1);
        for st in glyph {
            for (i, &(gx, gy)) in st.iter().enumerate() {
                // local coordinates: right and down from the anchor
                let lx = pen + gx * u * k;
                let ly = -(gy - BASE) * u * k + drop;
                let px = x + lx * cos + ly * sin;
                let py = y - lx * sin + ly * cos;
                d.push(if i == 0 { 'M' } else { 'L' });
                crate::svg::push_n(&mut d, px);
                d.push(' ');
                crate::svg::push_n(&mut d, py);
            }
            if st.len() == 1 {
                d.push_str("l0 0");
            }
        }
        pen += adv * u * k;
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_is_well_formed() {
        let all = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz.,:;()[]+-−–=/_*%'|!?<>≥≤±×·…→#στΔμ";
        for c in all.chars() {
            let def = glyph(c).unwrap_or_else(|| panic!("no glyph for {c}"));
            for s in def.split('|') {
                for p in s.split_whitespace() {
                    assert_eq!(p.len(), 2, "glyph {c}: point {p}");
                    assert!(p.bytes().all(|b| b.is_ascii_digit()), "glyph {c}: {p}");
                }
            }
        }
    }

    #[test]
    fn widths_grow_with_text_and_subscripts_are_smaller() {
        assert!(width("abc", 10.0) > width("ab", 10.0));
        assert!(width_rich("z_n", 10.0) < width("zn", 10.0));
        let d = path_data("p*", 0.0, 0.0, 7.0, Anchor::Start, 0.0, false);
        assert!(d.starts_with('M'));
    }
}
