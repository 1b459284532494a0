//! No writer emits a non-finite number: every number a writer would print is checked first,
//! and a NaN or an infinity is a [`NonFiniteOutput`] error instead of a `null`, `NaN` or `inf`
//! in a file. Such a number can only come from a fault of the program (the readers refuse
//! non-finite input), so the error says so.

use std::io;

use unilateral_contact::{ContactSolution, Outcome};
use unilateral_lcp::{LcpSolution, Residual, Tableau};

/// A result that is not a finite number, found before anything was written.
///
/// This is an **internal failure** (the command-line program exits with status 1): the input
/// was read and checked, so a NaN or an infinity in a result is the program's fault.
/// `field` names the number in the terms of the output (`pairs[2].z_n`, `nodes[4].uy`, …).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "the result {field} is {value}, not a finite number; this is a fault of the program, \
     not of the input, and no output was written"
)]
pub struct NonFiniteOutput {
    /// The number, named as in the output (1-based indices).
    pub field: String,
    /// The value found (NaN or ±infinity).
    pub value: f64,
}

impl NonFiniteOutput {
    /// The `NonFiniteOutput` inside an error of a file writer ([`crate::write_contact_csv`],
    /// [`crate::write_structural_csv`], [`crate::write_vtk_for`]), if that is what stopped it.
    pub fn in_io_error(e: &io::Error) -> Option<&NonFiniteOutput> {
        e.get_ref()?.downcast_ref::<NonFiniteOutput>()
    }
}

impl From<NonFiniteOutput> for io::Error {
    fn from(e: NonFiniteOutput) -> Self {
        io::Error::new(io::ErrorKind::InvalidData, e)
    }
}

/// A number for files read by programs (CSV): full precision, the shortest text that reads back
/// as the same `f64`, in exponent form (`1.5e-3`), and a negative zero as `0e0`.
pub(crate) fn full(v: f64) -> String {
    let mut s = String::with_capacity(24);
    push_full(&mut s, v);
    s
}

/// [`full`] appended to `s` (the long tables write millions of them).
pub(crate) fn push_full(s: &mut String, v: f64) {
    if v == 0.0 {
        s.push_str("0e0");
    } else {
        crate::decimal::push_exp(s, v);
    }
}

/// A number for people (the summary, the report): 6 significant digits, plain between 1e-4
/// and 1e6 and in exponent form outside (`1.23457e7`), trailing zeros dropped, and never `-0`.
pub(crate) fn plain(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v == 0.0 { "0".into() } else { v.to_string() };
    }
    fn trim(s: &str) -> &str {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.')
        } else {
            s
        }
    }
    // The exponent after rounding to 6 digits (999999.7 is 1e6, written in exponent form).
    let rounded: f64 = format!("{v:.5e}").parse().unwrap_or(v);
    let e = rounded.abs().log10().floor() as i32;
    let s = if (-4..6).contains(&e) {
        let d = (5 - e) as usize;
        trim(&format!("{v:.d$}")).to_string()
    } else {
        let s = format!("{v:.5e}");
        let (m, x) = s.split_once('e').unwrap_or((&s, "0"));
        format!("{}e{x}", trim(m))
    };
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// `Ok` if `v` is finite, else the error naming `field` (built only on failure).
pub(crate) fn finite(v: f64, field: impl FnOnce() -> String) -> Result<(), NonFiniteOutput> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(NonFiniteOutput {
            field: field(),
            value: v,
        })
    }
}

fn all<'a>(
    values: impl IntoIterator<Item = &'a f64>,
    field: impl Fn(usize) -> String,
) -> Result<(), NonFiniteOutput> {
    for (k, v) in values.into_iter().enumerate() {
        finite(*v, || field(k + 1))?;
    }
    Ok(())
}

pub(crate) fn residual(r: &Residual, at: &str) -> Result<(), NonFiniteOutput> {
    finite(r.equation, || format!("{at}.equation"))?;
    finite(r.feasibility, || format!("{at}.feasibility"))?;
    finite(r.complementarity, || format!("{at}.complementarity"))
}

/// Every number of a contact solution that the summary, the JSON document or the CSV tables
/// print.
pub(crate) fn contact_solution(sol: &ContactSolution) -> Result<(), NonFiniteOutput> {
    if let Some(p) = sol.p {
        finite(p, || "p".into())?;
    }
    finite(sol.tightening, || "tightening".into())?;
    finite(sol.settings.target, || "target".into())?;
    match &sol.outcome {
        Outcome::Ray { p_from } => finite(*p_from, || "the load of the ray".into())?,
        Outcome::Mechanism { p_limit, mode } => {
            finite(*p_limit, || "p_limit".into())?;
            for (i, (dn, dt)) in mode.iter().enumerate() {
                finite(*dn, || format!("mechanism[{}].dz_n", i + 1))?;
                finite(*dt, || format!("mechanism[{}].dz_t", i + 1))?;
            }
        }
        _ => {}
    }
    for s in &sol.steps {
        finite(s.p, || format!("steps[{}].p", s.index))?;
    }
    for (i, p) in sol.pairs.iter().enumerate() {
        let at = |what: &str| format!("pairs[{}].{what}", i + 1);
        finite(p.x_n, || at("x_n"))?;
        finite(p.x_t, || at("x_t"))?;
        finite(p.z_n, || at("z_n"))?;
        finite(p.z_t, || at("z_t"))?;
    }
    if let Some(r) = &sol.residual {
        residual(r, "residual")?;
    }
    Ok(())
}

/// Every number of a structural analysis that its summary, JSON document or CSV tables print
/// (the contact solution included).
pub(crate) fn analysis(a: &unilateral_analysis::Analysis) -> Result<(), NonFiniteOutput> {
    contact_solution(&a.solution)?;
    let Some(r) = &a.results else {
        return Ok(());
    };
    finite(r.p, || "structure.p".into())?;
    for (i, d) in r.displacements.iter().enumerate() {
        all(d, |k| {
            format!("nodes[{}].{}", i + 1, unilateral_fem::DofLabel::ALL[k - 1])
        })?;
    }
    for (i, x) in r.reactions.iter().enumerate() {
        finite(x.value, || format!("reactions[{}].value", i + 1))?;
        if let unilateral_fem::SupportDof::Along(v) = &x.dof {
            all(v, |k| {
                format!("reactions[{}].dof direction component {k}", i + 1)
            })?;
        }
    }
    for (i, l) in r.lines.iter().enumerate() {
        all(&l.end_forces, |k| {
            format!(
                "frames[{}].end_forces.{}",
                i + 1,
                ["N1", "V1", "M1", "N2", "V2", "M2"][k - 1]
            )
        })?;
        for (j, d) in l.diagram.iter().enumerate() {
            all([&d.s, &d.n, &d.q, &d.m], |k| {
                format!(
                    "frames[{}].diagram[{}].{}",
                    i + 1,
                    j + 1,
                    ["s", "N", "Q", "M"][k - 1]
                )
            })?;
        }
    }
    for (i, pl) in r.planes.iter().enumerate() {
        for (g, (xy, st)) in pl.gauss_points.iter().zip(&pl.stress).enumerate() {
            all(xy, |k| {
                format!("plane_elements[{}].gauss_points[{}][{k}]", i + 1, g + 1)
            })?;
            all(st, |k| {
                format!(
                    "plane_elements[{}].stress[{}].{}",
                    i + 1,
                    g + 1,
                    ["sxx", "syy", "txy", "szz"][k - 1]
                )
            })?;
        }
    }
    let e = &r.equilibrium;
    for (name, v) in [
        ("applied", &e.applied),
        ("reactions", &e.reactions),
        ("contact", &e.contact),
        ("springs", &e.springs),
        ("resultant", &e.resultant),
    ] {
        all(v, |k| format!("equilibrium.{name}[{k}]"))?;
    }
    finite(e.relative(), || "equilibrium.relative".into())?;
    if let Some(ex) = a.extremes() {
        if let Some(d) = &ex.displacement {
            finite(d.value, || "the largest displacement".into())?;
        }
        for (what, v) in [
            ("|M|", &ex.moment),
            ("|N|", &ex.axial),
            ("|Q|", &ex.shear),
            ("von Mises stress", &ex.von_mises),
        ] {
            if let Some(v) = v {
                finite(v.value, || format!("the largest {what}"))?;
                all(&v.at, |k| format!("the place of the largest {what} [{k}]"))?;
            }
        }
    }
    Ok(())
}

/// Every number of a plain LCP solution.
pub(crate) fn lcp_solution(sol: &LcpSolution) -> Result<(), NonFiniteOutput> {
    if let Some(p) = &sol.point {
        all(&p.z, |i| format!("z[{i}]"))?;
        all(&p.w, |i| format!("w[{i}]"))?;
        residual(&p.residual, "residual")?;
    }
    Ok(())
}

/// Every number of a list of tableaux.
pub(crate) fn tableaux(ts: &[Tableau]) -> Result<(), NonFiniteOutput> {
    for (t_no, t) in ts.iter().enumerate() {
        let t_no = t_no + 1;
        for (i, row) in t.entries.iter().enumerate() {
            all(row, |j| format!("tableaux[{t_no}].entries[{}][{j}]", i + 1))?;
        }
        all(&t.rhs, |i| format!("tableaux[{t_no}].rhs[{i}]"))?;
        for (i, r) in t.ratios.iter().enumerate() {
            if let Some(r) = r {
                finite(*r, || format!("tableaux[{t_no}].ratios[{}]", i + 1))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// Hand-written expectations: 6 significant digits for people, the shortest round-trip
    /// text for programs, no negative zero in either.
    #[test]
    fn numbers_are_written_plainly() {
        use super::{full, plain};
        for (v, want) in [
            (0.0, "0"),
            (-0.0, "0"),
            (1.0, "1"),
            (-1.5, "-1.5"),
            (213518.46, "213518"),
            (1562.634, "1562.63"),
            (0.000123456789, "0.000123457"),
            (-2.5e-7, "-2.5e-7"),
            (12345678.0, "1.23457e7"),
            (999999.7, "1e6"),
            (1e-300, "1e-300"),
        ] {
            assert_eq!(plain(v), want, "{v:e}");
        }
        assert_eq!(full(-0.0), "0e0");
        assert_eq!(full(0.1), "1e-1");
        for v in [0.1, -1.0 / 3.0, 1e-300, 6.02214076e23] {
            assert_eq!(full(v).parse::<f64>().unwrap(), v, "round trip");
        }
    }

    use unilateral_io::{read_contact_zone, read_lcp};

    use crate::{
        contact_json, contact_summary, lcp_json, lcp_summary, write_contact_csv, NonFiniteOutput,
    };

    fn good(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/good")
            .join(name)
    }

    /// A solved example with one number spoiled: every contact writer must refuse it, name
    /// the number, and write no file. (The reference is the field we spoiled.)
    #[test]
    fn contact_writers_refuse_a_non_finite_number() {
        let pb = read_contact_zone(&good("example1.toml")).unwrap();
        let sol = unilateral_contact::solve(&pb.zone, &pb.settings).unwrap();
        assert!(contact_json(&sol).is_ok() && contact_summary(&sol, "t").is_ok());
        for (spoil, field) in [
            (f64::NAN, "pairs[2].z_n"),
            (f64::INFINITY, "pairs[2].z_n"),
            (f64::NEG_INFINITY, "pairs[2].z_n"),
        ] {
            let mut bad = sol.clone();
            bad.pairs[1].z_n = spoil;
            let e = contact_json(&bad).unwrap_err();
            assert_eq!(e.field, field);
            assert!(e.to_string().contains("fault of the program"), "{e}");
            assert_eq!(contact_summary(&bad, "t").unwrap_err().field, field);
            let dir = tempfile::tempdir().unwrap();
            let out = dir.path().join("csv");
            let io = write_contact_csv(&bad, &out).unwrap_err();
            assert_eq!(NonFiniteOutput::in_io_error(&io).unwrap().field, field);
            assert!(!out.exists(), "nothing may be written");
        }
        let mut bad = sol.clone();
        bad.steps[0].p = f64::NAN;
        assert_eq!(
            contact_json(&bad).unwrap_err().field,
            format!("steps[{}].p", sol.steps[0].index)
        );
    }

    #[test]
    fn lcp_writers_refuse_a_non_finite_number() {
        let lcp = read_lcp(&good("lcp_small.toml")).unwrap();
        let sol = unilateral_lcp::solve_lcp(&lcp, &Default::default()).unwrap();
        assert!(sol.point.is_some(), "the small LCP has a solution");
        let mut bad = sol.clone();
        bad.point.as_mut().unwrap().w[0] = f64::NAN;
        assert_eq!(lcp_json(&bad).unwrap_err().field, "w[1]");
        assert_eq!(lcp_summary(&bad, "t").unwrap_err().field, "w[1]");
    }
}
