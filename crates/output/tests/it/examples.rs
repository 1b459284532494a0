//! The reports of the bundled examples: every SVG is well-formed XML without font-dependent
//! text, and report.html holds the pictures inline and the tables.
//!
//! Set `UNILATERAL_REPORT_OUT=DIR` to keep the files (one sub-folder per example), e.g. to
//! render them to PNG by hand.

use std::path::{Path, PathBuf};

use unilateral_analysis::analyze;
use unilateral_io::Problem;
use unilateral_output::{write_path_report, write_report, write_report_for, ReportOptions};

/// A small XML well-formedness checker: elements nest and close, attributes are quoted and
/// unique, entities are known, there is one root element. Returns the element names in order.
fn check_xml(s: &str) -> Result<Vec<String>, String> {
    let b = s.as_bytes();
    let mut i = 0;
    let mut stack: Vec<String> = Vec::new();
    let mut names = Vec::new();
    let mut roots = 0;
    let check_text = |t: &str| -> Result<(), String> {
        let mut rest = t;
        while let Some(k) = rest.find('&') {
            let end = rest[k..].find(';').ok_or("unterminated entity")?;
            let ent = &rest[k + 1..k + end];
            let ok = matches!(ent, "amp" | "lt" | "gt" | "quot" | "apos")
                || (ent.starts_with('#') && ent.len() > 1);
            if !ok {
                return Err(format!("unknown entity &{ent};"));
            }
            rest = &rest[k + end + 1..];
        }
        if t.contains('<') {
            return Err("'<' in text".into());
        }
        Ok(())
    };
    while i < b.len() {
        if b[i] != b'<' {
            let j = s[i..].find('<').map_or(b.len(), |k| i + k);
            let t = &s[i..j];
            if stack.is_empty() && !t.trim().is_empty() {
                return Err(format!("text outside the root: {t:?}"));
            }
            check_text(t)?;
            i = j;
            continue;
        }
        if s[i..].starts_with("<?") {
            i += s[i..].find("?>").ok_or("unterminated <?")? + 2;
            continue;
        }
        if s[i..].starts_with("<!--") {
            i += s[i..].find("-->").ok_or("unterminated comment")? + 3;
            continue;
        }
        let end = i + s[i..].find('>').ok_or("unterminated tag")?;
        let tag = &s[i + 1..end];
        if let Some(name) = tag.strip_prefix('/') {
            let open = stack.pop().ok_or("close without open")?;
            if open != name.trim() {
                return Err(format!("<{open}> closed by </{name}>"));
            }
        } else {
            let self_closing = tag.ends_with('/');
            let body = tag.trim_end_matches('/');
            let name: String = body.chars().take_while(|c| !c.is_whitespace()).collect();
            if name.is_empty()
                || !name
                    .chars()
                    .all(|c| c.is_alphanumeric() || ":-_".contains(c))
            {
                return Err(format!("bad element name in <{tag}>"));
            }
            // attributes
            let mut rest = body[name.len()..].trim_start();
            let mut seen: Vec<&str> = Vec::new();
            while !rest.is_empty() {
                let eq = rest
                    .find('=')
                    .ok_or(format!("attribute without value in <{tag}>"))?;
                let an = rest[..eq].trim();
                if an.is_empty() || an.contains(char::is_whitespace) || seen.contains(&an) {
                    return Err(format!("bad or repeated attribute {an:?} in <{name}>"));
                }
                seen.push(an);
                let after = rest[eq + 1..].trim_start();
                let q = after.chars().next().ok_or("missing quote")?;
                if q != '"' && q != '\'' {
                    return Err(format!("unquoted attribute {an} in <{name}>"));
                }
                let close = after[1..].find(q).ok_or("unterminated attribute")?;
                check_text(&after[1..1 + close])?;
                rest = after[close + 2..].trim_start();
            }
            if stack.is_empty() {
                roots += 1;
            }
            names.push(name.clone());
            if !self_closing {
                stack.push(name);
            }
        }
        i = end + 1;
    }
    if !stack.is_empty() {
        return Err(format!("unclosed elements {stack:?}"));
    }
    if roots != 1 {
        return Err(format!("{roots} root elements"));
    }
    Ok(names)
}

#[test]
fn the_checker_refuses_broken_xml() {
    assert!(check_xml("<svg><path d=\"M0 0\"/></svg>").is_ok());
    assert!(check_xml("<svg><path></svg>").is_err());
    assert!(check_xml("<svg a=\"1\" a=\"2\"/>").is_err());
    assert!(check_xml("<svg a=1/>").is_err());
    assert!(check_xml("<svg>&nbsp;</svg>").is_err());
    assert!(check_xml("<svg/><svg/>").is_err());
}

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn out_dir(name: &str) -> (Option<tempfile::TempDir>, PathBuf) {
    match std::env::var_os("UNILATERAL_REPORT_OUT") {
        Some(d) => (None, PathBuf::from(d).join(name)),
        None => {
            let t = tempfile::tempdir().unwrap();
            let p = t.path().to_path_buf();
            (Some(t), p)
        }
    }
}

fn check_report(files: &[PathBuf], with_structure: bool, pairs: &[String]) {
    let mut svgs = 0;
    for f in files {
        let text = std::fs::read_to_string(f).unwrap();
        if f.extension().is_some_and(|e| e == "svg") {
            let names = check_xml(&text).unwrap_or_else(|e| panic!("{}: {e}", f.display()));
            assert_eq!(names[0], "svg", "{}", f.display());
            assert!(
                !names.iter().any(|n| n == "text" || n == "tspan"),
                "{}: font text",
                f.display()
            );
            assert!(
                names.iter().filter(|n| *n == "path").count() >= 3,
                "{}: no stroke text",
                f.display()
            );
            svgs += 1;
        }
    }
    // the working-scheme map, the two load-path charts and the structure
    assert_eq!(svgs, if with_structure { 4 } else { 3 });
    let html = files
        .iter()
        .find(|f| f.ends_with("report.html"))
        .expect("report.html");
    let html = std::fs::read_to_string(html).unwrap();
    assert!(html.starts_with("<!DOCTYPE html>"));
    assert!(!html.contains("http://") || !html.contains("<link") && !html.contains("<script src"));
    assert_eq!(html.matches("<svg ").count(), svgs, "every picture inline");
    for part in html.split("<svg ").skip(1) {
        let end = part.find("</svg>").expect("closed svg") + "</svg>".len();
        check_xml(&format!("<svg {}", &part[..end])).unwrap();
    }
    assert!(html.contains("<table class=\"events\">"));
    assert!(html.contains("<table class=\"pairs\">"));
    for p in pairs {
        assert!(
            html.contains(&format!("<tr><td>{p}</td>")),
            "pair {p} in the table"
        );
    }
}

fn run_structural(file: &str, name: &str, options: &ReportOptions) {
    let Problem::Structural(pb) = unilateral_io::read_problem(&examples().join(file)).unwrap()
    else {
        panic!("{file} is a structural model");
    };
    let a = analyze(&pb.model, &pb.settings).unwrap();
    let (_keep, dir) = out_dir(name);
    let mut opt = options.clone();
    opt.title = pb.title.clone();
    let files = write_report_for(&pb.model, &a, &dir, &opt).unwrap();
    let pairs: Vec<String> = a.solution.pairs.iter().map(|r| r.name.clone()).collect();
    check_report(&files, true, &pairs);
    let (_keep2, dir2) = out_dir(&format!("{name}-no-model"));
    let files = write_report(&a, &dir2, &opt).unwrap();
    check_report(&files, false, &pairs);
}

#[test]
fn example1_beam() {
    run_structural(
        "example1-beam.toml",
        "example1",
        &ReportOptions {
            moments: true,
            ..Default::default()
        },
    );
}

#[test]
fn example2_cantilever() {
    run_structural(
        "example2-cantilever.toml",
        "example2",
        &ReportOptions {
            moments: true,
            ..Default::default()
        },
    );
}

#[test]
fn example3_sheet_pile() {
    run_structural(
        "example3-sheet-pile.toml",
        "example3",
        &ReportOptions::default(),
    );
}

#[test]
fn example3_selected_pairs_and_sigma_xx() {
    run_structural(
        "example3-sheet-pile.toml",
        "example3-selected",
        &ReportOptions {
            pairs: Some(vec![
                "right.12".into(),
                "left.1".into(),
                "no-such-pair".into(),
            ]),
            stress: unilateral_output::StressComponent::Sxx,
            ..Default::default()
        },
    );
}

#[test]
fn contact_zone_problem() {
    let Problem::ContactZone(pb) =
        unilateral_io::read_problem(&examples().join("example1-contact-zone.toml")).unwrap()
    else {
        panic!("a contact-zone problem");
    };
    let sol = unilateral_contact::solve(&pb.zone, &pb.settings).unwrap();
    let (_keep, dir) = out_dir("example1-contact-zone");
    let files = write_path_report(&sol, &dir, &ReportOptions::default()).unwrap();
    let pairs: Vec<String> = sol.pairs.iter().map(|r| r.name.clone()).collect();
    check_report(&files, false, &pairs);
}

/// Small contact forces beside large ones stay visible: on the sheet pile wall the forces of
/// the lower pairs are a few per cent of the largest, which at the picture's scale would be
/// arrows of 2–3 px; every force arrow is drawn at least 14 px long (its shaft from the tail to
/// the 8 px head, at least 6 px). Reference: the arrow's geometry (`Svg::arrow`).
#[test]
fn small_contact_forces_get_a_visible_arrow() {
    let Problem::Structural(pb) =
        unilateral_io::read_problem(&examples().join("example3-sheet-pile.toml")).unwrap()
    else {
        panic!("a structural model");
    };
    let a = analyze(&pb.model, &pb.settings).unwrap();
    let svg = unilateral_output::structure_svg(&pb.model, &a, &ReportOptions::default());
    let num = |l: &str, key: &str| -> f64 {
        let at = l.find(&format!(" {key}=\"")).unwrap() + key.len() + 3;
        l[at..].split('"').next().unwrap().parse().unwrap()
    };
    let shafts: Vec<f64> = svg
        .lines()
        .filter(|l| l.starts_with("<line") && l.contains("#2e7d32"))
        .map(|l| (num(l, "x2") - num(l, "x1")).hypot(num(l, "y2") - num(l, "y1")))
        .collect();
    // The pressed pairs' arrows and the legend's.
    let pressed = a.solution.pairs.iter().filter(|p| p.x_n > 0.0).count();
    assert!(shafts.len() > pressed.min(3), "{} arrows", shafts.len());
    // (coordinates are written to 0.01 px)
    assert!(shafts.iter().all(|&l| l >= 6.0 - 0.02), "{shafts:?}");
    let fmax = a
        .solution
        .pairs
        .iter()
        .fold(0.0f64, |m, p| m.max(p.x_n.hypot(p.x_t)));
    assert!(a
        .solution
        .pairs
        .iter()
        .any(|p| p.x_n > 0.0 && p.x_n.hypot(p.x_t) < 0.05 * fmax));
}
