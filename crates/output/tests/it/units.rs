//! The file's title and units in the outputs, the values of every pair at every breakpoint
//! (JSON on request, `path.csv` always), on the paper's Example 1.

use std::path::{Path, PathBuf};

use unilateral_output::{
    contact_json_with, contact_summary_with, structural_summary_with, write_contact_csv_with,
    write_path_report, write_structural_csv_with, About, PathJsonOptions, ReportOptions, PATH_CSV,
};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

fn example1() -> unilateral_contact::ContactSolution {
    let pb = unilateral_io::read_contact_zone(&example("example1-contact-zone.toml")).unwrap();
    let mut settings = pb.settings;
    settings.follow = unilateral_contact::Follow::ToEnd;
    unilateral_contact::solve(&pb.zone, &settings).unwrap()
}

fn about(units: &str) -> About {
    About {
        title: Some("Example 1, in other words".into()),
        units: Some(units.into()),
    }
}

/// The force and length units are the first two words of `units`; anything less labels no
/// column. Reference: the strings themselves.
#[test]
fn the_force_and_length_units_are_read_from_the_units_text() {
    assert_eq!(about("N, m").force_length(), Some(("N", "m")));
    assert_eq!(about(" kN , mm, K").force_length(), Some(("kN", "mm")));
    assert_eq!(about("SI").force_length(), None);
    assert_eq!(about("N,").force_length(), None);
    assert_eq!(About::default().force_length(), None);
}

/// Example 1 traced with the paper's tightening c = 1: its one breakpoint is p = 32/3 (pair 1
/// opens). On the traced segment before it every pair is closed and sticks with no
/// displacement (`z = 0`), so the traced normal forces are `x_n = c + p·d_n` with the file's
/// `d_n = (−3/32, 11/16, 13/32)`: at p = 32/3 that is `(0, 25/3, 16/3)` by hand, no
/// tangential force, no slip. These c-dependent values — not the tightening-free solution at
/// 32/3 — are what the JSON's `steps[0].pairs` and `path.csv` hold beside the c-dependent
/// event (to round-off relative to 25/3), both labelled so, and both writers agree to the last
/// bit.
#[test]
fn the_values_at_the_breakpoints_of_a_tightened_path_are_the_traced_ones() {
    let sol = example1();
    assert_eq!(sol.tightening, 1.0);
    assert_eq!(sol.steps.len(), 1);
    assert_eq!(sol.steps[0].p, 32.0 / 3.0);
    let options = PathJsonOptions {
        breakpoints: true,
        about: about("kN, mm"),
    };
    let j = contact_json_with(&sol, &options).unwrap();
    assert_eq!(j["units"], "kN, mm");
    assert_eq!(j["title"], "Example 1, in other words");
    let label = j["step_pairs"].as_str().unwrap();
    assert!(
        label.contains("tightening c = 1") && label.contains("depend on c"),
        "{label}"
    );
    let pairs = j["steps"][0]["pairs"].as_array().unwrap();
    let want = [0.0, 25.0 / 3.0, 16.0 / 3.0];
    let tol = 1e-12 * 25.0 / 3.0;
    for (p, x_n) in pairs.iter().zip(want) {
        assert!((p["x_n"].as_f64().unwrap() - x_n).abs() <= tol, "{p}");
        for key in ["x_t", "z_n", "z_t"] {
            assert!(p[key].as_f64().unwrap().abs() <= tol, "{p}");
        }
    }
    assert_eq!(pairs[0]["state"], "open", "the event: pair 1 opens");
    assert_eq!(pairs[1]["state"], "stick");
    assert_eq!(pairs[2]["state"], "stick");
    // Without the request the document has no values at the breakpoints.
    let plain = contact_json_with(&sol, &PathJsonOptions::default()).unwrap();
    assert!(plain["steps"][0].get("pairs").is_none() && plain.get("step_pairs").is_none());
    assert!(plain.get("units").is_none() && plain.get("title").is_none());

    let dir = tempfile::tempdir().unwrap();
    let files = write_contact_csv_with(&sol, dir.path(), &options.about).unwrap();
    assert_eq!(files.len(), 3);
    let path = std::fs::read_to_string(dir.path().join(PATH_CSV)).unwrap();
    let mut lines = path.lines();
    assert_eq!(
        lines.next(),
        Some("step,p,pair,name,x_n [kN],x_t [kN],z_n [mm],z_t [mm],state,tightening_c [kN]")
    );
    for (line, p) in lines.zip(pairs) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[1].parse::<f64>().unwrap(), 32.0 / 3.0);
        for (k, key) in [(4, "x_n"), (5, "x_t"), (6, "z_n"), (7, "z_t")] {
            assert_eq!(
                f[k].parse::<f64>().unwrap(),
                p[key].as_f64().unwrap(),
                "{line}"
            );
        }
        assert_eq!(f[8], p["state"]);
        assert_eq!(f[9].parse::<f64>().unwrap(), 1.0);
    }
    let pairs_csv = std::fs::read_to_string(dir.path().join("pairs.csv")).unwrap();
    assert!(pairs_csv.starts_with("pair,name,x_n [kN],x_t [kN],z_n [mm],z_t [mm],state\n"));
}

/// The summary's header and the report carry the title and the units. Reference: the text
/// given.
#[test]
fn the_summary_and_the_report_say_the_units() {
    let sol = example1();
    let s = contact_summary_with(&sol, "unilateral — example1", &about("kN, mm")).unwrap();
    let head: Vec<&str> = s.lines().take(3).collect();
    assert_eq!(
        head,
        [
            "unilateral — example1",
            "title: Example 1, in other words",
            "units: kN, mm"
        ]
    );
    let dir = tempfile::tempdir().unwrap();
    let options = ReportOptions {
        title: Some("Example 1".into()),
        units: Some("kN, mm".into()),
        ..Default::default()
    };
    write_path_report(&sol, dir.path(), &options).unwrap();
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert!(html.contains("<title>Example 1 (kN, mm)</title>"), "{html}");
    assert!(html.contains("<dt>Units</dt><dd>kN, mm</dd>"));
    assert!(html.contains("x<sub>n</sub> [kN] (compression +)"));
    assert!(html.contains("z<sub>t</sub> [mm]</th>"));
}

/// A structural model's tables: lengths, rotations, forces, moments and stresses labelled from
/// `"N, m"`. Reference: the units of each quantity (a moment is a force times a length).
#[test]
fn structural_tables_label_every_quantity() {
    let Ok(unilateral_io::Problem::Structural(pb)) =
        unilateral_io::read_problem(&example("example1-beam.toml"))
    else {
        panic!("a structural model");
    };
    let a = unilateral_analysis::analyze(&pb.model, &pb.settings).unwrap();
    let about = About {
        title: pb.title.clone(),
        units: Some("N, m".into()),
    };
    let dir = tempfile::tempdir().unwrap();
    write_structural_csv_with(&a, dir.path(), &about).unwrap();
    let head = |f: &str| {
        let t = std::fs::read_to_string(dir.path().join(f)).unwrap();
        t.lines().next().unwrap().to_string()
    };
    assert_eq!(head("displacements.csv"), "node,ux [m],uy [m],rz [rad]");
    assert_eq!(
        head("frame_end_forces.csv"),
        "element,N1 [N],V1 [N],M1 [N·m],N2 [N],V2 [N],M2 [N·m]"
    );
    assert_eq!(head("reactions.csv"), "node,dof,value,unit");
    // each reaction's unit by its DOF, on two clamped cantilevers (tests/data/models/
    // gap-tips.toml): forces in N, the clamps' moments in N·m
    let Ok(unilateral_io::Problem::Structural(wall)) = unilateral_io::read_problem(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../tests/data/models/gap-tips.toml"),
    ) else {
        panic!("a structural model");
    };
    let aw = unilateral_analysis::analyze(&wall.model, &wall.settings).unwrap();
    let dw = tempfile::tempdir().unwrap();
    write_structural_csv_with(&aw, dw.path(), &about).unwrap();
    let rows = std::fs::read_to_string(dw.path().join("reactions.csv")).unwrap();
    let mut kinds = std::collections::BTreeSet::new();
    for row in rows.lines().skip(1) {
        let cols: Vec<&str> = row.split(',').collect();
        let want = if cols[1] == "rz" { "N·m" } else { "N" };
        assert_eq!(cols[3], want, "{row}");
        kinds.insert(cols[3].to_string());
    }
    assert_eq!(kinds.len(), 2, "forces and a moment: {rows}");
    let s = structural_summary_with(&a, "unilateral — beam", &about).unwrap();
    assert!(s.lines().any(|l| l == "units: N, m"), "{s}");
}
