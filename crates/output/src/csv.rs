//! CSV tables: pairs, steps and the whole path of a contact solution; displacements,
//! reactions, end forces and plane stresses of a structural analysis. Every number is checked
//! finite first and written with full precision (the shortest text that reads back as the same
//! number, never `-0e0`). With the file's units, the column names carry them (`x_n [N]`): a
//! first comment line would not be read by pandas or a spreadsheet by default.

use std::fmt::Write as _;
use std::path::Path;

use unilateral_contact::ContactSolution;

use crate::decimal::push_int;
use crate::finite::{self, full as n, push_full};
use crate::json::{breakpoint_blocks, dof_name, About, PathOutputError};

/// The name of the long table of the whole path: every pair at every breakpoint.
pub const PATH_CSV: &str = "path.csv";

/// Writes `pairs.csv`, `steps.csv` and `path.csv` into `dir` (created if needed), without
/// units in the column names ([`write_contact_csv_with`]).
///
/// A non-finite number in the solution is an error carrying a [`NonFiniteOutput`](crate::NonFiniteOutput)
/// ([`in_io_error`](crate::NonFiniteOutput::in_io_error)), and then nothing is written; a solution that cannot be
/// evaluated at a breakpoint is an error carrying the [`unilateral_contact::ContactError`].
pub fn write_contact_csv(
    sol: &ContactSolution,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    write_contact_csv_with(sol, dir, &About::default())
}

/// [`write_contact_csv`] with the file's units in the column names (`x_n [N]`, `z_n [m]`).
///
/// `path.csv` has one row per pair and breakpoint: `step,p,pair,name,x_n,x_t,z_n,z_t,state`,
/// the same values as the JSON's `steps[k].pairs`: the solution at each step's `p` (one walk
/// along the path), or, for a path traced with the paper's tightening `c > 0`, the traced path
/// at its breakpoints, with `c` in its values as in its events, and a last column
/// `tightening_c` holding `c` on every row.
pub fn write_contact_csv_with(
    sol: &ContactSolution,
    dir: &Path,
    about: &About,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    finite::contact_solution(sol)?;
    let columns = about.pair_columns();
    let mut pairs = format!("pair,name,{columns},state\n");
    for (i, p) in sol.pairs.iter().enumerate() {
        let _ = writeln!(
            pairs,
            "{},{},{},{},{},{},{}",
            i + 1,
            csv_field(&p.name),
            n(p.x_n),
            n(p.x_t),
            n(p.z_n),
            n(p.z_t),
            p.state
        );
    }
    // Traced with the paper's tightening, the steps' loads depend on `c`: a last column says
    // so on every row, and carries `c` (a force).
    let tightened = sol.tightening > 0.0;
    let mut steps = String::from("step,p,entering,leaving,events,turning,beyond_target");
    if tightened {
        steps.push(',');
        steps.push_str(&about.column("tightening_c", |f, _| f.into()));
    }
    steps.push('\n');
    for st in &sol.steps {
        let ev: Vec<String> = st.events.iter().map(|e| e.to_string()).collect();
        let _ = write!(
            steps,
            "{},{},{},{},{},{},{}",
            st.index,
            n(st.p),
            st.entering,
            st.leaving,
            csv_field(&ev.join("; ")),
            st.turning,
            st.index > sol.steps_before_target
        );
        if tightened {
            let _ = write!(steps, ",{}", n(sol.tightening));
        }
        steps.push('\n');
    }
    // Traced with the tightening, the values are those of the traced path (they depend on c,
    // as the events do): the same last column as steps.csv says so on every row.
    let mut path = format!("step,p,pair,name,{columns},state");
    let c_column = if tightened {
        path.push(',');
        path.push_str(&about.column("tightening_c", |f, _| f.into()));
        format!(",{}", n(sol.tightening))
    } else {
        String::new()
    };
    path.push('\n');
    // path.csv is long (steps × pairs rows): it is streamed block by block (no more than one
    // block of values is held) over the file an earlier run left, moved aside and put back
    // when complete ([`crate::overwrite::Aside`]); on an error the file is removed, so no
    // path.csv is left half-written.
    std::fs::create_dir_all(dir)?;
    let c = dir.join(PATH_CSV);
    let (aside, file) = crate::overwrite::Aside::open(&c)?;
    let streamed = (|| -> std::io::Result<(std::fs::File, u64)> {
        use std::io::Write as _;
        let mut out = std::io::BufWriter::new(file);
        let mut len = path.len() as u64;
        out.write_all(path.as_bytes())?;
        let mut io_error = None;
        // The pairs named by their place (the breakpoints' own names left empty).
        let names = &sol.zone().pair_names;
        breakpoint_blocks(sol, false, |steps, block| {
            // Formatting the numbers is most of this file's time: each step's rows are
            // formatted on the thread pool, then written in order (the same bytes).
            use rayon::prelude::*;
            let texts: Vec<String> = steps
                .par_iter()
                .zip(&block)
                .map(|(st, ps)| {
                    // The step's load formatted once for all its rows; the rows' text in one
                    // buffer of about its final size; the pair names written as they are.
                    let mut p_text = String::with_capacity(24);
                    push_full(&mut p_text, st.p);
                    let pairs = ps.as_deref().unwrap_or(&[]);
                    let mut rows = String::with_capacity(pairs.len() * 128);
                    for (i, p) in pairs.iter().enumerate() {
                        push_int(&mut rows, st.index as i64);
                        rows.push(',');
                        rows.push_str(&p_text);
                        rows.push(',');
                        push_int(&mut rows, i as i64 + 1);
                        rows.push(',');
                        push_csv_field(&mut rows, names.get(i).map_or("", String::as_str));
                        for v in [p.x_n, p.x_t, p.z_n, p.z_t] {
                            rows.push(',');
                            push_full(&mut rows, v);
                        }
                        let _ = writeln!(rows, ",{}{c_column}", p.state);
                    }
                    rows
                })
                .collect();
            for rows in texts {
                len += rows.len() as u64;
                if let Err(e) = out.write_all(rows.as_bytes()) {
                    io_error = Some(e);
                    return Ok(());
                }
            }
            Ok(())
        })
        .map_err(|e| match e {
            PathOutputError::NonFinite(n) => std::io::Error::from(n),
            PathOutputError::Contact(c) => std::io::Error::other(c),
        })?;
        if let Some(e) = io_error {
            return Err(e);
        }
        let f = out
            .into_inner()
            .map_err(std::io::IntoInnerError::into_error)?;
        Ok((f, len))
    })();
    match streamed {
        Ok((f, len)) => aside.finish(f, len)?,
        Err(e) => {
            aside.abandon();
            return Err(e);
        }
    }
    let a = dir.join("pairs.csv");
    let b = dir.join("steps.csv");
    crate::overwrite::write_over(&a, pairs.as_bytes())?;
    crate::overwrite::write_over(&b, steps.as_bytes())?;
    Ok(vec![a, b, c])
}

fn csv_field(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    push_csv_field(&mut out, s);
    out
}

/// [`csv_field`] appended to `out`.
fn push_csv_field(out: &mut String, s: &str) {
    if s.contains([',', '"', '\n']) {
        out.push('"');
        out.push_str(&s.replace('"', "\"\""));
        out.push('"');
    } else {
        out.push_str(s);
    }
}

/// Writes the contact tables and one table per kind of structural result into `dir`, without
/// units in the column names ([`write_structural_csv_with`]).
pub fn write_structural_csv(
    a: &unilateral_analysis::Analysis,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    write_structural_csv_with(a, dir, &About::default())
}

/// [`write_structural_csv`] with the file's units in the column names (`ux [m]`, `M1 [N·m]`,
/// `sxx [N/m²]`; rotations in `rad`; the reactions' `value` is a force or a moment by its
/// `dof`: a column `unit` says which on each row).
pub fn write_structural_csv_with(
    a: &unilateral_analysis::Analysis,
    dir: &Path,
    about: &About,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    finite::analysis(a)?;
    let mut files = write_contact_csv_with(&a.solution, dir, about)?;
    let Some(r) = &a.results else {
        return Ok(files);
    };
    let names = a.names();
    let force = |c: &str| about.column(c, |f, _| f.into());
    let length = |c: &str| about.column(c, |_, l| l.into());
    let moment = |c: &str| about.column(c, |f, l| format!("{f}·{l}"));
    let stress = |c: &str| about.column(c, |f, l| format!("{f}/{l}²"));
    let rad = |c: &str| about.column(c, |_, _| "rad".into());
    let mut t = format!("node,{},{},{}\n", length("ux"), length("uy"), rad("rz"));
    for (i, d) in r.displacements.iter().enumerate() {
        let _ = writeln!(
            t,
            "{},{},{},{}",
            csv_field(&names.node(unilateral_fem::NodeId(i))),
            n(d[0]),
            n(d[1]),
            n(d[2])
        );
    }
    files.push(write_table(dir, "displacements.csv", t)?);
    // A reaction is a force or a moment by its DOF: with the file's units, a `unit` column
    // says which, row by row.
    let units = about.force_length();
    let mut t = String::from(if units.is_some() {
        "node,dof,value,unit\n"
    } else {
        "node,dof,value\n"
    });
    for x in &r.reactions {
        let _ = write!(
            t,
            "{},{},{}",
            csv_field(&names.node(x.node)),
            csv_field(&dof_name(&x.dof)),
            n(x.value)
        );
        if let Some((f, l)) = units {
            let unit = match x.dof {
                unilateral_fem::SupportDof::Rz => format!("{f}·{l}"),
                _ => f.to_string(),
            };
            let _ = write!(t, ",{}", csv_field(&unit));
        }
        t.push('\n');
    }
    files.push(write_table(dir, "reactions.csv", t)?);
    let mut t = format!(
        "element,{},{},{},{},{},{}\n",
        force("N1"),
        force("V1"),
        moment("M1"),
        force("N2"),
        force("V2"),
        moment("M2")
    );
    for l in &r.lines {
        let f = l.end_forces;
        let _ = writeln!(
            t,
            "{},{},{},{},{},{},{}",
            csv_field(&names.element(l.element)),
            n(f[0]),
            n(f[1]),
            n(f[2]),
            n(f[3]),
            n(f[4]),
            n(f[5])
        );
    }
    files.push(write_table(dir, "frame_end_forces.csv", t)?);
    let mut t = format!(
        "element,gauss_point,{},{},{},{},{},{}\n",
        length("x"),
        length("y"),
        stress("sxx"),
        stress("syy"),
        stress("txy"),
        stress("szz")
    );
    for pl in &r.planes {
        for (g, (xy, st)) in pl.gauss_points.iter().zip(&pl.stress).enumerate() {
            let _ = writeln!(
                t,
                "{},{},{},{},{},{},{},{}",
                csv_field(&names.element(pl.element)),
                g + 1,
                n(xy[0]),
                n(xy[1]),
                n(st[0]),
                n(st[1]),
                n(st[2]),
                n(st[3])
            );
        }
    }
    files.push(write_table(dir, "plane_stresses.csv", t)?);
    Ok(files)
}

fn write_table(dir: &Path, name: &str, text: String) -> std::io::Result<std::path::PathBuf> {
    let path = dir.join(name);
    crate::overwrite::write_over(&path, text.as_bytes())?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::{csv_field, push_csv_field};

    /// A field with a comma, a quote or a line break is quoted, its quotes doubled (RFC 4180);
    /// any other is written as it is; appending gives the same text as the field alone.
    #[test]
    fn fields_are_quoted_where_csv_needs_it() {
        for (name, want) in [
            ("bearing.12", "bearing.12"),
            ("a,b", "\"a,b\""),
            ("say \"hi\"", "\"say \"\"hi\"\"\""),
            ("two\nlines", "\"two\nlines\""),
            ("", ""),
        ] {
            assert_eq!(csv_field(name), want);
            let mut row = String::from("1,");
            push_csv_field(&mut row, name);
            assert_eq!(row, format!("1,{want}"));
        }
    }
}
