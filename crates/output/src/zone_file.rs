//! A model's contact zone written as a contact-zone file (`docs/contact-zone.md`): the contact
//! stiffness matrix, friction, gaps, every load case and the history's stages, readable by
//! `unilateral solve` and by any other program (TOML, numbers at full precision).

use std::fmt::Write as _;

use unilateral_contact::{ContactZone, SolveSettings, Stage};

use crate::finite::{finite, NonFiniteOutput};

/// A TOML number that reads back to the same `f64` (the shortest round-trip form; `-0` as `0`).
fn number(v: f64) -> String {
    if v == 0.0 {
        return "0.0".into();
    }
    let s = format!("{v:?}");
    if s.contains(['.', 'e', 'E']) {
        s
    } else {
        format!("{s}.0")
    }
}

/// A TOML basic string.
fn string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn vector(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|&x| number(x)).collect();
    format!("[{}]", items.join(", "))
}

fn matrix(m: usize, at: impl Fn(usize, usize) -> f64) -> String {
    let rows: Vec<String> = (0..m)
        .map(|i| {
            let row: Vec<f64> = (0..m).map(|j| at(i, j)).collect();
            format!("  {}", vector(&row))
        })
        .collect();
    format!("[\n{},\n]", rows.join(",\n"))
}

/// The contact-zone file of `zone`: `[contact_zone]` (friction, gap, names, `Rnn`, `Rtt`, `Rnt`,
/// `Rtn`), one `[load.NAME]` per case of the zone (`zone.cases`; `constant`/`variable` from
/// their fields when the zone has no cases), the `[[history]]` stages if given (their factors
/// named by case), and `[solve]` (the settings of the paper's path, without a history).
/// `header` lines are written as comments first. Every number is checked finite.
pub fn zone_toml(
    zone: &ContactZone,
    settings: &SolveSettings,
    history: Option<&[Stage]>,
    header: &[String],
    about: &crate::About,
) -> Result<String, NonFiniteOutput> {
    let m = zone.pairs();
    let blocks = [
        ("Rnn", &zone.rnn),
        ("Rtt", &zone.rtt),
        ("Rnt", &zone.rnt),
        ("Rtn", &zone.rtn),
    ];
    for (name, mat) in blocks {
        for i in 0..m {
            for j in 0..m {
                finite(mat[(i, j)], || format!("{name}[{}, {}]", i + 1, j + 1))?;
            }
        }
    }
    let mut s = String::new();
    for h in header {
        let _ = writeln!(s, "# {h}");
    }
    // The model's title and units, read back by the zone's reader (and printed by its runs).
    if let Some(t) = &about.title {
        let _ = writeln!(s, "title = {}", string(t));
    }
    if let Some(u) = &about.units {
        let _ = writeln!(s, "units = {}", string(u));
    }
    let _ = writeln!(s, "[contact_zone]");
    let _ = writeln!(s, "friction = {}", vector(&zone.friction));
    let _ = writeln!(s, "gap = {}", vector(&zone.gap));
    let names: Vec<String> = zone.pair_names.iter().map(|n| string(n)).collect();
    let _ = writeln!(s, "names = [{}]", names.join(", "));
    for (name, mat) in blocks {
        let _ = writeln!(s, "{name} = {}", matrix(m, |i, j| mat[(i, j)]));
    }
    let cases: Vec<(String, &unilateral_contact::ContactLoad)> = if zone.cases.is_empty() {
        vec![
            ("constant".to_string(), &zone.constant),
            ("variable".to_string(), &zone.variable),
        ]
    } else {
        zone.cases
            .iter()
            .map(|c| (c.name.clone(), &c.load))
            .collect()
    };
    for (name, load) in &cases {
        for (part, v) in [("normal", &load.normal), ("tangential", &load.tangential)] {
            for (i, &x) in v.iter().enumerate() {
                finite(x, || format!("load.{name}.{part}[{}]", i + 1))?;
            }
        }
        let key = if name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        {
            name.clone()
        } else {
            string(name)
        };
        let _ = writeln!(s, "\n[load.{key}]");
        let _ = writeln!(s, "normal = {}", vector(&load.normal));
        let _ = writeln!(s, "tangential = {}", vector(&load.tangential));
    }
    match history {
        Some(stages) => {
            for st in stages {
                let parts: Vec<String> = st
                    .factors
                    .iter()
                    .zip(&cases)
                    .filter_map(|(f, (name, _))| {
                        f.map(|f| format!("{} = {}", string(name), number(f)))
                    })
                    .collect();
                let _ = writeln!(
                    s,
                    "\n[[history]]\nname = {}\nfactors = {{ {} }}",
                    string(&st.name),
                    parts.join(", ")
                );
            }
        }
        None => {
            let _ = writeln!(s, "\n[solve]");
            let _ = writeln!(s, "target = {}", number(settings.target));
            let _ = writeln!(
                s,
                "trace = {}",
                match settings.follow {
                    unilateral_contact::Follow::ToTarget => "\"target\"",
                    unilateral_contact::Follow::ToEnd => "\"end\"",
                }
            );
            let _ = writeln!(s, "tightening = {}", number(settings.tightening));
        }
    }
    Ok(s)
}
