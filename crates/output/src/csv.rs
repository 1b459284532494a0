//! CSV tables: pairs and steps of a contact solution; displacements, reactions, end forces and
//! plane stresses of a structural analysis. Every number is checked finite first.

use std::fmt::Write as _;
use std::path::Path;

use unilateral_contact::ContactSolution;

use crate::finite;
use crate::json::dof_name;

/// Writes `pairs.csv` and `steps.csv` into `dir` (created if needed).
///
/// A non-finite number in the solution is an error carrying a [`NonFiniteOutput`]
/// ([`NonFiniteOutput::in_io_error`]), and then nothing is written.
pub fn write_contact_csv(
    sol: &ContactSolution,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    finite::contact_solution(sol)?;
    std::fs::create_dir_all(dir)?;
    let mut pairs = String::from("pair,name,x_n,x_t,z_n,z_t,state\n");
    for (i, p) in sol.pairs.iter().enumerate() {
        let _ = writeln!(
            pairs,
            "{},{},{:e},{:e},{:e},{:e},{}",
            i + 1,
            csv_field(&p.name),
            p.x_n,
            p.x_t,
            p.z_n,
            p.z_t,
            p.state
        );
    }
    let mut steps = String::from("step,p,entering,leaving,events,turning,beyond_target\n");
    for st in &sol.steps {
        let ev: Vec<String> = st.events.iter().map(|e| e.to_string()).collect();
        let _ = writeln!(
            steps,
            "{},{:e},{},{},{},{},{}",
            st.index,
            st.p,
            st.entering,
            st.leaving,
            csv_field(&ev.join("; ")),
            st.turning,
            st.index > sol.steps_before_target
        );
    }
    let a = dir.join("pairs.csv");
    let b = dir.join("steps.csv");
    std::fs::write(&a, pairs)?;
    std::fs::write(&b, steps)?;
    Ok(vec![a, b])
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Writes the contact tables and one table per kind of structural result into `dir`.
pub fn write_structural_csv(
    a: &unilateral_analysis::Analysis,
    dir: &Path,
) -> std::io::Result<Vec<std::path::PathBuf>> {
    finite::analysis(a)?;
    let mut files = write_contact_csv(&a.solution, dir)?;
    let Some(r) = &a.results else {
        return Ok(files);
    };
    let names = a.names();
    let mut t = String::from("node,ux,uy,rz\n");
    for (i, d) in r.displacements.iter().enumerate() {
        let _ = writeln!(
            t,
            "{},{:e},{:e},{:e}",
            csv_field(&names.node(unilateral_fem::NodeId(i))),
            d[0],
            d[1],
            d[2]
        );
    }
    files.push(write_table(dir, "displacements.csv", t)?);
    let mut t = String::from("node,dof,value\n");
    for x in &r.reactions {
        let _ = writeln!(
            t,
            "{},{},{:e}",
            csv_field(&names.node(x.node)),
            csv_field(&dof_name(&x.dof)),
            x.value
        );
    }
    files.push(write_table(dir, "reactions.csv", t)?);
    let mut t = String::from("element,N1,V1,M1,N2,V2,M2\n");
    for l in &r.lines {
        let f = l.end_forces;
        let _ = writeln!(
            t,
            "{},{:e},{:e},{:e},{:e},{:e},{:e}",
            csv_field(&names.element(l.element)),
            f[0],
            f[1],
            f[2],
            f[3],
            f[4],
            f[5]
        );
    }
    files.push(write_table(dir, "frame_end_forces.csv", t)?);
    let mut t = String::from("element,gauss_point,x,y,sxx,syy,txy,szz\n");
    for pl in &r.planes {
        for (g, (xy, st)) in pl.gauss_points.iter().zip(&pl.stress).enumerate() {
            let _ = writeln!(
                t,
                "{},{},{:e},{:e},{:e},{:e},{:e},{:e}",
                csv_field(&names.element(pl.element)),
                g + 1,
                xy[0],
                xy[1],
                st[0],
                st[1],
                st[2],
                st[3]
            );
        }
    }
    files.push(write_table(dir, "plane_stresses.csv", t)?);
    Ok(files)
}

fn write_table(dir: &Path, name: &str, text: String) -> std::io::Result<std::path::PathBuf> {
    let path = dir.join(name);
    std::fs::write(&path, text)?;
    Ok(path)
}
