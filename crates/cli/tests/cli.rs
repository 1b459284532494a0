//! Integration tests that run the real `unilateral` binary.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// The repository root (two levels above this crate).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `tests/data/siconos/<sub>` of this repository (Apache-2.0 test data, see its README.md).
/// It is part of the repository: missing, it is a test failure, never a skip.
fn siconos(sub: &str) -> PathBuf {
    let dir = root().join("tests/data/siconos").join(sub);
    assert!(dir.is_dir(), "{} is missing", dir.display());
    dir
}

/// One run of the binary in a fresh temporary directory.
struct TestCommand {
    dir: tempfile::TempDir,
    args: Vec<String>,
    env: Vec<(String, String)>,
}

struct Output {
    code: i32,
    stdout: String,
    stderr: String,
}

impl TestCommand {
    fn new(args: &[&str]) -> Self {
        Self {
            dir: tempfile::tempdir().expect("temp dir"),
            args: args.iter().map(|s| s.to_string()).collect(),
            env: Vec::new(),
        }
    }

    fn env(mut self, key: &str, value: &str) -> Self {
        self.env.push((key.to_string(), value.to_string()));
        self
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn arg(mut self, a: impl AsRef<std::ffi::OsStr>) -> Self {
        self.args.push(a.as_ref().to_string_lossy().into_owned());
        self
    }

    fn args(mut self, more: &[&str]) -> Self {
        self.args.extend(more.iter().map(|s| s.to_string()));
        self
    }

    fn run(&self) -> Output {
        let out = Command::new(env!("CARGO_BIN_EXE_unilateral"))
            .args(&self.args)
            .envs(self.env.iter().map(|(k, v)| (k, v)))
            .current_dir(self.dir.path())
            .output()
            .expect("run unilateral");
        Output {
            code: out.status.code().unwrap_or(-1),
            stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
            stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
        }
    }

    fn json(&self, file: &str) -> Value {
        let text = std::fs::read_to_string(self.path(file)).expect("JSON written");
        serde_json::from_str(&text).expect("valid JSON")
    }
}

fn example1() -> PathBuf {
    root().join("examples/example1-contact-zone.toml")
}

fn close(v: &Value, want: f64, tol: f64) -> bool {
    v.as_f64().is_some_and(|x| (x - want).abs() <= tol)
}

#[test]
fn solve_example1_reports_the_papers_answer() {
    let cmd = TestCommand::new(&["solve"]).arg(example1());
    let cmd = cmd.arg("--json").arg("out.json");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.contains("status: ray"), "{}", out.stdout);
    assert!(out.stdout.contains("pair 1 opens"), "{}", out.stdout);
    assert!(out.stdout.contains("verified"));
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "ray");
    assert!(close(&j["p"], 1.0, 0.0));
    assert!(close(&j["steps"][0]["p"], 32.0 / 3.0, 1e-9));
    assert_eq!(j["steps"][0]["leaving"], "x_n1");
    assert_eq!(j["steps"][0]["events"][0], "pair 1 opens");
    let pairs = j["pairs"].as_array().unwrap();
    assert_eq!(pairs[0]["state"], "open");
    assert!(close(&pairs[0]["z_n"], 0.5, 1e-12));
    for p in &pairs[1..] {
        assert!(close(&p["x_n"], 0.5, 1e-12));
        assert!(close(&p["x_t"], 0.0, 1e-12));
        assert!(close(&p["z_n"], 0.0, 1e-12));
    }
    assert!(j["residual"]["equation"].as_f64().unwrap() <= 1e-12);
    assert!(j["p_limit"].is_null());
}

/// Where the ending has a load to report a solution at and none can be given, the output says
/// why. Two pairs of a floating body (`R_n` singular), the first pulled off by the load, with
/// the paper's tightening c = 1: the tightened path ends in a mechanism at p = 2 (by hand:
/// `x_n1 = 1 − p + z_n1` opens pair 1 at p = 1, then `z_n1 = p − 1` and `x_n2 = 1 − z_n1 = 2 − p`
/// open pair 2 at p = 2), and the real problem, pulled with nothing to hold it, has no solution
/// there: removing
/// the tightening and a fresh solve both fail, which is an answer (exit 0), not a fault.
#[test]
fn a_missing_solution_is_explained() {
    let cmd = TestCommand::new(&["solve", "pulled.toml", "--json", "out.json"]);
    std::fs::write(
        cmd.path("pulled.toml"),
        "[contact_zone]\nfriction = 0.5\nRnn = [[1.0, -1.0], [-1.0, 1.0]]\n\
         Rtt = [[1.0, -1.0], [-1.0, 1.0]]\n[load.variable]\nnormal = [-1.0, 0.0]\n\
         tangential = [0.0, 0.0]\n[solve]\ntightening = 1.0\ntarget = 3.0\ntrace = \"end\"\n",
    )
    .unwrap();
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    // Traced with the tightening, the mechanism's load is the traced path's (it depends on c).
    assert!(
        out.stdout.contains(
            "the path traced with the tightening c = 1 becomes a mechanism at p = 2.000000"
        ),
        "{}",
        out.stdout
    );
    assert!(
        out.stdout
            .contains("no solution to report (why: in the notes at the end)"),
        "{}",
        out.stdout
    );
    let j = cmd.json("out.json");
    assert!(j["p"].is_null());
    let notes: Vec<&str> = j["notes"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|n| n.as_str())
        .collect();
    let why = notes
        .iter()
        .find(|n| n.starts_with("no solution is reported at p = 2:"))
        .unwrap_or_else(|| panic!("no reason among {notes:?}"));
    assert!(
        why.contains("the tightening could not be removed")
            && why.contains("a fresh solve at that load found no solution"),
        "{why}"
    );
    assert!(out.stdout.contains(why), "{}", out.stdout);
}

/// The files are the same bits whatever the number of threads. The 300-bearing beam traced to
/// p* = 1.9543 makes 257 steps: the last block of breakpoints holds one step, whose forces are
/// a product of the 300 × 300 zone blocks with one column, which faer's parallel product splits
/// into per-thread partial sums (37 rows of path.csv changed in their last digits between 1
/// and 4 threads before that product was asked on one thread).
#[test]
fn the_files_do_not_depend_on_the_number_of_threads() {
    let written = |threads: &str| {
        let cmd = TestCommand::new(&[
            "solve",
            "beam.toml",
            "--trace",
            "target",
            "--target",
            "1.9543",
            "--csv",
            "csv",
            "--json",
            "out.json",
        ])
        .env("RAYON_NUM_THREADS", threads);
        std::fs::write(
            cmd.path("beam.toml"),
            unilateral_oracle::fixtures::bearings::beam_model(300),
        )
        .unwrap();
        let out = cmd.run();
        assert_eq!(out.code, 0, "{}", out.stderr);
        let steps = std::fs::read_to_string(cmd.path("csv/steps.csv")).unwrap();
        assert_eq!(steps.lines().count(), 258, "257 steps and the header");
        let path = std::fs::read(cmd.path("csv/path.csv")).unwrap();
        let mut json = cmd.json("out.json");
        json.as_object_mut().unwrap().remove("timings");
        (path, json)
    };
    let one = written("1");
    for threads in ["2", "4"] {
        let other = written(threads);
        assert!(one.0 == other.0, "path.csv differs with {threads} threads");
        assert_eq!(one.1, other.1, "the JSON differs with {threads} threads");
    }
}

/// The tables and the report are written side by side: when both fail, both failures are said
/// (the first on stderr before the one that sets the exit status), not only one.
#[test]
fn every_writer_that_fails_says_so() {
    let cmd = TestCommand::new(&["solve"]).arg(example1()).args(&[
        "--csv",
        "blocker/csv",
        "--report",
        "rep",
    ]);
    std::fs::write(cmd.path("blocker"), "a file where a directory is asked").unwrap();
    std::fs::create_dir_all(cmd.path("rep/report.html")).unwrap();
    let out = cmd.run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(out.stderr.contains("blocker"), "{}", out.stderr);
    assert!(out.stderr.contains("rep"), "{}", out.stderr);
    assert_eq!(out.stderr.matches("error:").count(), 2, "{}", out.stderr);
}

#[test]
fn default_trace_stops_at_the_target_with_the_same_answer() {
    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .arg("--trace")
        .arg("target")
        .arg("--json")
        .arg("out.json");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "target_reached");
    assert_eq!(j["steps"].as_array().unwrap().len(), 0);
    assert!(close(&j["pairs"][0]["z_n"], 0.5, 1e-12));
    assert!(close(&j["pairs"][1]["x_n"], 0.5, 1e-12));
    assert!(close(&j["pairs"][2]["x_n"], 0.5, 1e-12));
    assert!(out.stdout.contains("depend on c"), "{}", out.stdout);
}

#[test]
fn csv_tables_are_written() {
    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .arg("--csv")
        .arg("tables");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let pairs = std::fs::read_to_string(cmd.path("tables/pairs.csv")).unwrap();
    assert_eq!(pairs.lines().count(), 4);
    assert!(pairs.lines().nth(1).unwrap().ends_with(",open"));
    let steps = std::fs::read_to_string(cmd.path("tables/steps.csv")).unwrap();
    assert!(steps.contains("pair 1 opens"));
}

/// The paper's Tables 1-3 (docs/formulation.md §5), typed from the paper: entries by row in the
/// order x_n1..x_t3-, z_n1..z_t3-, p, then rhs. Table 2's rows x_t3± carry typos in the paper
/// (−1 where −0.6 and −0.5 belong); they are written here corrected, as docs/formulation.md §5 says.
#[test]
fn tableau_reproduces_tables_1_2_3() {
    let cmd = TestCommand::new(&["tableau"])
        .arg(example1())
        .arg("--json")
        .arg("t.json");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("t.json");
    let tables = j.as_array().unwrap();
    assert_eq!(tables.len(), 3);
    #[rustfmt::skip]
    let t1: [[f64; 20]; 9] = [
        [1., 0., 0., 0., 0., 0., 0., 0., 0., -0.1875, 0.375, -0.1875, 0., 0., 0., 0., 0., 0., 0.09375, 1.],
        [0., 1., 0., 0., 0., 0., 0., 0., 0., 0.375, -0.75, 0.375, 0., 0., 0., 0., 0., 0., -0.6875, 1.],
        [0., 0., 1., 0., 0., 0., 0., 0., 0., -0.1875, 0.375, -0.1875, 0., 0., 0., 0., 0., 0., -0.40625, 1.],
        [0., 0., 0., 1., 0., 0., 0., 0., 0., -0.1125, 0.225, -0.1125, -0.5, 0.5, 0., 0.5, -0.5, 0., 0.05625, 1.],
        [0., 0., 0., 0., 1., 0., 0., 0., 0., 0.225, -0.45, 0.225, 0.5, -1., 0.5, -0.5, 1., -0.5, -0.4125, 1.],
        [0., 0., 0., 0., 0., 1., 0., 0., 0., -0.1125, 0.225, -0.1125, 0., 0.5, -0.5, 0., -0.5, 0.5, -0.24375, 1.],
        [0., 0., 0., 0., 0., 0., 1., 0., 0., -0.1125, 0.225, -0.1125, 0.5, -0.5, 0., -0.5, 0.5, 0., 0.05625, 1.],
        [0., 0., 0., 0., 0., 0., 0., 1., 0., 0.225, -0.45, 0.225, -0.5, 1., -0.5, 0.5, -1., 0.5, -0.4125, 1.],
        [0., 0., 0., 0., 0., 0., 0., 0., 1., -0.1125, 0.225, -0.1125, 0., -0.5, 0.5, 0., 0.5, -0.5, -0.24375, 1.],
    ];
    let a = 32.0 / 3.0;
    #[rustfmt::skip]
    let t2: [[f64; 20]; 9] = [
        [a, 0., 0., 0., 0., 0., 0., 0., 0., -2., 4., -2., 0., 0., 0., 0., 0., 0., 1., a],
        [22. / 3., 1., 0., 0., 0., 0., 0., 0., 0., -1., 2., -1., 0., 0., 0., 0., 0., 0., 0., 25. / 3.],
        [13. / 3., 0., 1., 0., 0., 0., 0., 0., 0., -1., 2., -1., 0., 0., 0., 0., 0., 0., 0., 16. / 3.],
        [-0.6, 0., 0., 1., 0., 0., 0., 0., 0., 0., 0., 0., -0.5, 0.5, 0., 0.5, -0.5, 0., 0., 0.4],
        [4.4, 0., 0., 0., 1., 0., 0., 0., 0., -0.6, 1.2, -0.6, 0.5, -1., 0.5, -0.5, 1., -0.5, 0., 5.4],
        [2.6, 0., 0., 0., 0., 1., 0., 0., 0., -0.6, 1.2, -0.6, 0., 0.5, -0.5, 0., -0.5, 0.5, 0., 3.6],
        [-0.6, 0., 0., 0., 0., 0., 1., 0., 0., 0., 0., 0., 0.5, -0.5, 0., -0.5, 0.5, 0., 0., 0.4],
        [4.4, 0., 0., 0., 0., 0., 0., 1., 0., -0.6, 1.2, -0.6, -0.5, 1., -0.5, 0.5, -1., 0.5, 0., 5.4],
        [2.6, 0., 0., 0., 0., 0., 0., 0., 1., -0.6, 1.2, -0.6, 0., -0.5, 0.5, 0., 0.5, -0.5, 0., 3.6],
    ];
    #[rustfmt::skip]
    let t3: [[f64; 20]; 9] = [
        [-16. / 3., 0., 0., 0., 0., 0., 0., 0., 0., 1., -2., 1., 0., 0., 0., 0., 0., 0., -0.5, -16. / 3.],
        [2., 1., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., -0.5, 3.],
        [-1., 0., 1., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., 0., -0.5, 0.],
        [-0.6, 0., 0., 1., 0., 0., 0., 0., 0., 0., 0., 0., -0.5, 0.5, 0., 0.5, -0.5, 0., 0., 0.4],
        [1.2, 0., 0., 0., 1., 0., 0., 0., 0., 0., 0., 0., 0.5, -1., 0.5, -0.5, 1., -0.5, -0.3, 2.2],
        [-0.6, 0., 0., 0., 0., 1., 0., 0., 0., 0., 0., 0., 0., 0.5, -0.5, 0., -0.5, 0.5, -0.3, 0.4],
        [-0.6, 0., 0., 0., 0., 0., 1., 0., 0., 0., 0., 0., 0.5, -0.5, 0., -0.5, 0.5, 0., 0., 0.4],
        [1.2, 0., 0., 0., 0., 0., 0., 1., 0., 0., 0., 0., -0.5, 1., -0.5, 0.5, -1., 0.5, -0.3, 2.2],
        [-0.6, 0., 0., 0., 0., 0., 0., 0., 1., 0., 0., 0., 0., -0.5, 0.5, 0., 0.5, -0.5, -0.3, 0.4],
    ];
    let basis = [
        vec![
            "x_n1", "x_n2", "x_n3", "x_t1+", "x_t2+", "x_t3+", "x_t1-", "x_t2-", "x_t3-",
        ],
        vec![
            "p", "x_n2", "x_n3", "x_t1+", "x_t2+", "x_t3+", "x_t1-", "x_t2-", "x_t3-",
        ],
        vec![
            "z_n1", "x_n2", "x_n3", "x_t1+", "x_t2+", "x_t3+", "x_t1-", "x_t2-", "x_t3-",
        ],
    ];
    for (k, expect) in [t1, t2, t3].iter().enumerate() {
        let t = &tables[k];
        for i in 0..9 {
            assert_eq!(t["basis"][i], basis[k][i], "table {} row {i}", k + 1);
            for c in 0..19 {
                let got = t["entries"][i][c].as_f64().unwrap();
                assert!(
                    (got - expect[i][c]).abs() <= 1e-9,
                    "table {} [{i}][{c}] = {got}",
                    k + 1
                );
            }
            let rhs = t["rhs"][i].as_f64().unwrap();
            assert!(
                (rhs - expect[i][19]).abs() <= 1e-9,
                "table {} rhs {i} = {rhs}",
                k + 1
            );
        }
    }
    // Leading row and column, and the minimum-ratio column.
    assert_eq!(tables[0]["entering"], "p");
    assert_eq!(tables[0]["leaving_row"], 0);
    let ratios = &tables[0]["ratios"];
    assert!(close(&ratios[0], 32.0 / 3.0, 1e-9));
    assert!(close(&ratios[3], 160.0 / 9.0, 1e-9));
    assert!(close(&ratios[6], 160.0 / 9.0, 1e-9));
    for i in [1, 2, 4, 5, 7, 8] {
        assert!(ratios[i].is_null());
    }
    assert_eq!(tables[1]["entering"], "z_n1");
    assert!(tables[1]["leaving_row"].is_null());
    assert!(tables[1]["ratios"]
        .as_array()
        .unwrap()
        .iter()
        .all(Value::is_null));
    assert!(out.stdout.contains("leading column: p; leading row: x_n1"));
}

#[test]
fn example_lists_and_writes_a_solvable_file() {
    let list = TestCommand::new(&["example"]).run();
    assert_eq!(list.code, 0);
    assert!(list.stdout.contains("example1-contact-zone"));
    let cmd = TestCommand::new(&["example", "example1-contact-zone", "--to", "here"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let written = cmd.path("here/example1-contact-zone.toml");
    assert!(written.is_file());
    let again = TestCommand::new(&["solve"]).arg(&written).run();
    assert_eq!(again.code, 0, "{}", again.stderr);
    let missing = TestCommand::new(&["example", "no-such-example"]).run();
    assert_eq!(missing.code, 2);
    assert!(missing.stderr.contains("no example named"));
}

/// Every bundled example of `examples/` is listed and written out, the ones on Gmsh meshes with
/// their meshes beside them (`meshes/`), byte for byte the repository's files, and solves where
/// it was written (the mesh examples were not listed). A second write is refused without
/// `--force`, naming the file.
#[test]
fn every_bundled_example_is_written_with_its_meshes() {
    let list = TestCommand::new(&["example"]).run();
    let mut bundled: Vec<String> = std::fs::read_dir(root().join("examples"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    bundled.sort();
    for name in &bundled {
        assert!(list.stdout.contains(name.as_str()), "{name} is not listed");
    }
    for (name, meshes) in [
        (
            "cylinder-on-foundation",
            &[
                "meshes/disc-coarse.msh",
                "meshes/block-coarse.msh",
                "meshes/make.py",
            ][..],
        ),
        (
            "footing-on-soil",
            &["meshes/footing.msh", "meshes/soil.msh", "meshes/make.py"][..],
        ),
    ] {
        let cmd = TestCommand::new(&["example", name, "--to", "here"]);
        let out = cmd.run();
        assert_eq!(out.code, 0, "{name}: {}", out.stderr);
        for rel in meshes {
            let written = std::fs::read(cmd.path(&format!("here/{rel}"))).unwrap();
            assert_eq!(
                written,
                std::fs::read(root().join("examples").join(rel)).unwrap()
            );
        }
        let model = cmd.path(&format!("here/{name}.toml"));
        let solved = TestCommand::new(&["solve"]).arg(&model).run();
        assert_eq!(solved.code, 0, "{name}: {}", solved.stderr);
        let again = cmd.run();
        assert_eq!(again.code, 2, "{name}");
        assert!(again.stderr.contains("use --force"), "{}", again.stderr);
    }
    // both into one directory: the mesh script they share is written once, not refused
    let both = TestCommand::new(&["example", "cylinder-on-foundation", "--to", "d"]);
    assert_eq!(both.run().code, 0);
    let second = TestCommand::new(&["example", "footing-on-soil", "--to"])
        .arg(both.path("d"))
        .run();
    assert_eq!(second.code, 0, "{}", second.stderr);
}

#[test]
fn lcp_command_on_every_siconos_file() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(siconos("lcp"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "dat"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 10, "{files:?}");
    for f in files {
        let cmd = TestCommand::new(&["lcp"])
            .arg(&f)
            .arg("--json")
            .arg("r.json");
        let out = cmd.run();
        assert_eq!(out.code, 0, "{}: {}", f.display(), out.stderr);
        let j = cmd.json("r.json");
        let status = j["status"].as_str().unwrap().to_string();
        assert_eq!(status, "solved", "{}: {}", f.display(), out.stdout);
        let r = &j["residual"];
        for k in ["equation", "feasibility", "complementarity"] {
            assert!(r[k].as_f64().unwrap() <= 1e-10, "{}: {k}", f.display());
        }
    }
}

#[test]
fn vtk_needs_a_structural_model() {
    let out = TestCommand::new(&["solve"])
        .arg(example1())
        .arg("--vtk")
        .arg("v")
        .run();
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("--vtk"));
}

#[test]
fn command_line_errors_exit_2() {
    assert_eq!(TestCommand::new(&["frobnicate"]).run().code, 2);
    assert_eq!(TestCommand::new(&["solve"]).run().code, 2);
    let out = TestCommand::new(&["solve", "does-not-exist.toml"]).run();
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("does-not-exist.toml"), "{}", out.stderr);
    let out = TestCommand::new(&["solve"])
        .arg(example1())
        .arg("--target")
        .arg("-1")
        .run();
    assert_eq!(out.code, 2);
    assert!(out.stderr.contains("target"), "{}", out.stderr);
}

/// The exit statuses of the contract (docs/contact-zone.md, "Exit status") through real runs:
/// help and version are answers (0); an output path that cannot be written is the command
/// line's fault (2, naming the path), not the program's; bad data in a file is 2 naming the file.
/// (The internal failures, exit 1, are covered variant by variant by the unit tests of main.rs:
/// no input is known that makes the program fail, and a test hook would not be a real path.)
#[test]
fn exit_statuses_of_the_contract() {
    for args in [&["--help"][..], &["--version"], &["solve", "--help"]] {
        let out = TestCommand::new(args).run();
        assert_eq!(out.code, 0, "{args:?}: {}", out.stderr);
    }
    let out = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--json", "no-such-dir/out.json"])
        .run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(
        out.stderr.contains("no-such-dir/out.json"),
        "{}",
        out.stderr
    );
    assert!(out.stderr.starts_with("error: "), "{}", out.stderr);
    assert!(!out.stderr.contains("fault"), "{}", out.stderr);
    // A user's Rtt that is not positive semidefinite: the user's data, so 2 and the place.
    let bad = root().join("tests/data/bad/rtt_negative_diagonal.toml");
    let out = TestCommand::new(&["solve"]).arg(&bad).run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(
        out.stderr.contains("rtt_negative_diagonal.toml:4:25"),
        "{}",
        out.stderr
    );
    assert!(!out.stderr.contains("internal"), "{}", out.stderr);
}

/// States beyond double precision are the data's conditioning: exit 2, naming the file, the
/// place and the advice, where they were exit 1, "a fault of unilateral". A history
/// (`tests/data/unresolvable/block-soft-spring-history.toml`: a steel block on a 1 N/m spring
/// sliding 5099 m by hand): the JSON's stage `unresolved` with the state where the engine
/// stopped (every pair's slip within 1e-4 of the hand value). A load path
/// (`block-soft-spring-path.toml`: a block on a 1 N/m spring that has slid 5490 m by hand when it
/// tips, where the path stopped at a singular basis): the JSON's reading says the same, its
/// status the engine's `numerical_failure`.
#[test]
fn states_beyond_double_precision_exit_2_with_the_advice() {
    let dir = root().join("tests/data/unresolvable");
    let run = |name: &str, wants: &[&str]| -> Value {
        let cmd = TestCommand::new(&["solve"])
            .arg(dir.join(name))
            .args(&["--json", "out.json", "--csv", "csv", "--report", "rep"]);
        let cmd = if name.contains("history") {
            // Every output is written: the ParaView frames up to the failed stage (its states
            // are not the structure's: refused to recover them, they left the report
            // unwritten).
            cmd.args(&["--vtk", "vtk"])
        } else {
            cmd
        };
        let out = cmd.run();
        for file in ["rep/report.html", "csv"] {
            assert!(cmd.path(file).exists(), "{name}: no {file}: {}", out.stderr);
        }
        if name.contains("history") {
            let pvd = std::fs::read_to_string(cmd.path("vtk/history.pvd")).unwrap();
            // the unloaded start and the end of stage 1, not the failed stage 2
            assert_eq!(pvd.matches("<DataSet").count(), 4, "{pvd}");
        }
        assert_eq!(out.code, 2, "{name}: {}", out.stderr);
        let last = out.stderr.lines().last().unwrap_or_default();
        assert!(last.starts_with("error: "), "{name}: {}", out.stderr);
        assert!(!out.stderr.contains("fault"), "{name}: {}", out.stderr);
        for want in [
            name,
            "cannot be resolved in double precision",
            "keep the slips short",
        ]
        .iter()
        .chain(wants)
        {
            assert!(out.stderr.contains(want), "{name}: {want}: {}", out.stderr);
        }
        serde_json::from_str(&std::fs::read_to_string(cmd.path("out.json")).unwrap()).unwrap()
    };
    let j = run(
        "block-soft-spring-history.toml",
        &["stage 2 (`push1`)", "(largest 5.099e3)"],
    );
    assert_eq!(j["status"], "unresolved");
    let last = &j["history"][1];
    assert_eq!(last["status"], "unresolved");
    let slip = 8622.03 - 0.38 * 9271.0;
    for p in last["pairs"].as_array().unwrap() {
        let z_t = p["z_t"].as_f64().unwrap();
        assert!((z_t - slip).abs() <= 1e-4 * slip, "{p}");
    }
    let j = run("block-soft-spring-path.toml", &["(largest 5.490e3)"]);
    assert_eq!(j["status"], "numerical_failure");
    let reading = j["reading"].as_str().unwrap();
    assert!(
        reading.contains("cannot be resolved in double precision") && !reading.contains("fault"),
        "{reading}"
    );
}

/// The report of a structural history whose last stage ends early in a mechanism
/// (`tests/data/history/mesh-mechanism.toml`: the block slides off in stage 5 at s ≈ 0.455):
/// written like any other (its node curves once asked for the stage's last step a rounding
/// beyond the stage's end, and the run failed as an internal error), with the node curves the
/// report draws.
#[test]
fn a_history_report_of_a_stage_ending_in_a_mechanism() {
    let model = root().join("tests/data/history/mesh-mechanism.toml");
    let cmd = TestCommand::new(&["solve"])
        .arg(&model)
        .args(&["--report", "rep", "--json", "out.json"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "mechanism", "{}", j["status"]);
    let last = &j["history"][4];
    let s_end = last["s_end"].as_f64().unwrap();
    assert!(
        last["status"] == "mechanism" && s_end > 0.0 && s_end < 1.0,
        "{last}"
    );
    for f in ["report.html", "history-nodes.svg"] {
        assert!(cmd.path("rep").join(f).is_file(), "{f} not written");
    }
}

/// An option that only shapes an output not asked for is refused (exit 2, naming the option
/// it needs), not silently ignored: `--vtk-format` without `--vtk`, `--json-breakpoints`
/// without `--json`, `--report-pairs`, `--moments`, `--stress` and `--report-nodes` without
/// `--report`. With their output asked for they are accepted.
#[test]
fn options_of_an_output_not_asked_for_are_refused() {
    for (extra, needs) in [
        (&["--vtk-format", "binary"][..], "--vtk"),
        (&["--json-breakpoints"], "--json"),
        (&["--report-pairs", "support.1"], "--report"),
        (&["--moments"], "--report"),
        (&["--stress", "sxx"], "--report"),
        (&["--report-nodes", "A"], "--report"),
    ] {
        let out = TestCommand::new(&["solve"])
            .arg(root().join("examples/example1-beam.toml"))
            .args(extra)
            .run();
        assert_eq!(out.code, 2, "{extra:?}: {}", out.stderr);
        assert!(out.stderr.contains(needs), "{extra:?}: {}", out.stderr);
    }
    let out = TestCommand::new(&["solve"])
        .arg(root().join("examples/example1-beam.toml"))
        .args(&[
            "--vtk",
            "v",
            "--vtk-format",
            "binary",
            "--report",
            "r",
            "--moments",
        ])
        .args(&["--json", "o.json", "--json-breakpoints"])
        .run();
    assert_eq!(out.code, 0, "{}", out.stderr);
}

/// `lcp --json` says how the LCP was solved as data (it was Rust's debug text,
/// `"Lemke { covering: \"ones\" }"`): `lcp_CPS_3`, a bimatrix game whose Lemke paths all end
/// on rays (contact-zone.md), by enumeration; `lcp_mmc` by Lemke's method with the covering
/// vector of ones, the first tried.
#[test]
fn lcp_json_says_how_it_solved_as_data() {
    for (file, want) in [
        (
            "lcp_CPS_3.dat",
            serde_json::json!({ "method": "enumeration" }),
        ),
        (
            "lcp_mmc.dat",
            serde_json::json!({ "method": "lemke", "covering": "ones" }),
        ),
    ] {
        let cmd = TestCommand::new(&["lcp"])
            .arg(root().join("tests/data/siconos/lcp").join(file))
            .args(&["--json", "out.json"]);
        let out = cmd.run();
        assert_eq!(out.code, 0, "{}", out.stderr);
        assert_eq!(cmd.json("out.json")["strategy"], want, "{file}");
    }
}

/// A closed stderr (`unilateral … 2>&1 >/dev/null | head -1`) is no failure: the run's status
/// is what it would be (0 for a run that writes files and says so on stderr, 2 for bad input),
/// never a panic (101) on the first line written there.
#[test]
fn a_closed_stderr_changes_no_exit_status() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        Command::new(env!("CARGO_BIN_EXE_unilateral"))
            .args(args)
            .current_dir(dir.path())
            .stdout(std::process::Stdio::null())
            .stderr(writer)
            .status()
            .unwrap()
            .code()
    };
    let example = example1();
    let example = example.to_str().unwrap();
    assert_eq!(run(&["solve", example, "--csv", "tables"]), Some(0));
    assert!(dir.path().join("tables").is_dir());
    assert_eq!(run(&["solve", "no-such-file.toml"]), Some(2));
}

/// Finite numbers whose sums leave double precision are the model's (exit 2, "choose other
/// units"), not the program's: a load of 1e308 at x = 2 (its moment about the origin 2e308),
/// and the same reached by a target load p = 1e308. No output file is written.
#[test]
fn forces_too_large_for_their_units_are_the_models() {
    let model = |fy: &str, target: &str| {
        format!(
            "[[sections]]\nname = \"b\"\nE = 1.0\nA = 100.0\nI = 1.0\n\
             [[members]]\nname = \"beam\"\nstart = [0.0, 0.0]\nend = [4.0, 0.0]\n\
             divisions = 2\nsection = \"b\"\n\
             [[supports]]\nnodes = \"beam.start\"\npinned = true\n\
             [[supports]]\nnodes = \"beam.end\"\nuy = true\n\
             [[contact]]\nname = \"mid\"\nfrom = \"ground\"\nto = \"beam.1\"\n\
             normal = [0.0, 1.0]\nfriction = 0.3\ngap = 0.01\n\
             [[loads.variable.nodal]]\nnodes = \"beam.1\"\nfy = {fy}\n\
             [solve]\ntarget = {target}\n"
        )
    };
    for (fy, target) in [("-1e308", "1.0"), ("-1.0", "1e308")] {
        let cmd = TestCommand::new(&["solve", "big.toml", "--json", "out.json"]);
        std::fs::write(cmd.path("big.toml"), model(fy, target)).unwrap();
        let out = cmd.run();
        assert_eq!(out.code, 2, "fy = {fy}, target = {target}: {}", out.stderr);
        assert!(
            out.stderr.contains("overflows double precision")
                && out.stderr.contains("choose other units")
                && !out.stderr.contains("fault"),
            "{}",
            out.stderr
        );
        assert!(!cmd.path("out.json").exists());
    }
}

/// Stresses near the top of double precision (a block under a body force in units where
/// stresses are 1e307): their von Mises value is the same as in ordinary units, times the
/// scale (it squared them, and printed `inf` as an internal error). Stresses beyond the range
/// with finite displacements are the model's units (exit 2, naming the element), not the
/// program's fault. Reference: the problem has no constant load, so every stress is linear in
/// the body force; the same block under (2e3, −2e4) N/m³.
#[test]
fn stresses_near_the_top_of_the_range_are_the_models_units() {
    let block = std::fs::read_to_string(root().join("tests/data/models/body-block.toml")).unwrap();
    assert!(block.contains("force = [2000.0, -20000.0]"));
    let largest_von_mises = |text: &str| -> f64 {
        let line = text
            .lines()
            .find(|l| l.contains("largest von Mises"))
            .unwrap_or_else(|| panic!("no von Mises line in\n{text}"));
        line.split_whitespace().nth(3).unwrap().parse().unwrap()
    };
    let run = |model: &str| {
        let cmd = TestCommand::new(&["solve", "block.toml"]);
        std::fs::write(cmd.path("block.toml"), model).unwrap();
        cmd.run()
    };
    let plain = run(&block);
    assert_eq!(plain.code, 0, "{}", plain.stderr);
    let scaled = run(&block.replace("force = [2000.0, -20000.0]", "force = [8.0e306, -8.0e307]"));
    assert_eq!(scaled.code, 0, "{}", scaled.stderr);
    let (a, b) = (
        largest_von_mises(&plain.stdout),
        largest_von_mises(&scaled.stdout),
    );
    assert!(b.is_finite() && b > 1e307, "{b}");
    // six significant digits printed
    assert!((b / (4e303 * a) - 1.0).abs() < 1e-5, "{a} {b}");

    // a block 1000 times larger, 1e-10 m thick, under 2e306 N/m³: stresses of the order of
    // 2e309, its loads (about 1e301 N an element) and displacements finite
    let beyond = run(&block
        .replace("width = 2.0", "width = 2000.0")
        .replace("height = 1.0", "height = 1000.0")
        .replace("thickness = 0.4", "thickness = 1.0e-10")
        .replace("force = [2000.0, -20000.0]", "force = [2.0e304, -2.0e306]"));
    assert_eq!(beyond.code, 2, "{}", beyond.stderr);
    assert!(
        beyond
            .stderr
            .contains("a recovered stress or internal force of element `blk.")
            && beyond.stderr.contains("choose other units")
            && !beyond.stderr.contains("fault"),
        "{}",
        beyond.stderr
    );
}

/// Every file of the bad-input corpus: exit code 2, a message that names the file and the
/// expected problem, and never a panic.
#[test]
fn bad_inputs_exit_2_with_a_message_naming_the_file() {
    let dir = root().join("tests/data/bad");
    let table = std::fs::read_to_string(dir.join("EXPECTED.txt")).unwrap();
    let mut count = 0;
    for line in table.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line.split(" | ").collect();
        let (file, fragment) = (cols[0], cols[cols.len() - 1]);
        let command = if file.ends_with(".mtx") {
            continue; // Matrix Market files are read through a problem file.
        } else if file.starts_with("fc2d_") {
            continue; // no command reads the fc2d form
        } else if file.starts_with("lcp_") {
            "lcp"
        } else {
            "solve"
        };
        let out = TestCommand::new(&[command]).arg(dir.join(file)).run();
        assert_eq!(out.code, 2, "{file}: {}{}", out.stdout, out.stderr);
        let name = Path::new(file).file_name().unwrap().to_string_lossy();
        let stem = name.trim_end_matches(|c| c != '.');
        assert!(
            out.stderr.contains(&*name) || out.stderr.contains(stem),
            "{file}: message does not name the file: {}",
            out.stderr
        );
        if !file.starts_with("fc2d_") {
            assert!(
                out.stderr.contains(fragment),
                "{file}: expected '{fragment}' in: {}",
                out.stderr
            );
        }
        assert!(!out.stderr.contains("panicked"), "{file} panicked");
        count += 1;
    }
    assert!(count >= 20, "only {count} bad inputs");
}

#[test]
fn structural_example1_reports_the_papers_answer_with_full_results() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example1-beam.toml"))
        .arg("--json")
        .arg("out.json")
        .arg("--csv")
        .arg("tables");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(
        out.stdout.contains("largest displacement"),
        "{}",
        out.stdout
    );
    assert!(out.stdout.contains("equilibrium"));
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "ray");
    assert!(close(&j["steps"][0]["p"], 32.0 / 3.0, 1e-9));
    let pairs = j["pairs"].as_array().unwrap();
    assert_eq!(pairs[0]["state"], "open");
    // The uplift of the left support is P·L³/(16·EI) = 0.5; the others carry 0.5 each.
    assert!(close(&pairs[0]["z_n"], 0.5, 1e-9));
    assert!(close(&pairs[1]["x_n"], 0.5, 1e-9) && close(&pairs[2]["x_n"], 0.5, 1e-9));
    assert!(!j["nodes"].as_array().unwrap().is_empty());
    assert!(!j["frames"].as_array().unwrap().is_empty());
    assert!(j["equilibrium"]["relative"].as_f64().unwrap() < 1e-9);
    for f in [
        "pairs.csv",
        "steps.csv",
        "displacements.csv",
        "reactions.csv",
        "frame_end_forces.csv",
        "plane_stresses.csv",
    ] {
        assert!(cmd.path("tables").join(f).is_file(), "{f}");
    }
}

#[test]
fn sheet_pile_wall_main_job() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .arg("--json")
        .arg("out.json");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "ray");
    let state = |name: &str| {
        j["pairs"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == name)
            .map(|p| p["state"].as_str().unwrap().to_string())
            .unwrap()
    };
    // The paper's pattern: left opens at the top, right opens at the bottom and slides at the top.
    assert_eq!(state("left.12"), "open");
    assert_ne!(state("left.2"), "open");
    assert_eq!(state("right.1"), "open");
    assert!(state("right.12").starts_with("slip"));
    assert!(!j["plane_elements"].as_array().unwrap().is_empty());
}

/// Every bad structural model: exit code 2 and a message naming the file and the problem.
#[test]
fn bad_models_exit_2_with_located_messages() {
    let dir = root().join("tests/data/bad-models");
    let table = std::fs::read_to_string(dir.join("EXPECTED.txt")).unwrap();
    let mut count = 0;
    for line in table.lines().map(str::trim) {
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line.split(" | ").collect();
        let (file, place, fragment) = (cols[0], cols[1], cols[cols.len() - 1]);
        let out = TestCommand::new(&["solve"]).arg(dir.join(file)).run();
        assert_eq!(out.code, 2, "{file}: {}{}", out.stdout, out.stderr);
        assert!(out.stderr.contains(file), "{file}: {}", out.stderr);
        if place != "analysis" {
            assert!(
                out.stderr.contains(place),
                "{file}: expected '{place}' in {}",
                out.stderr
            );
        }
        assert!(
            out.stderr.contains(fragment),
            "{file}: expected '{fragment}' in {}",
            out.stderr
        );
        assert!(!out.stderr.contains("panicked"));
        count += 1;
    }
    assert!(count >= 15, "only {count} bad models");
}

#[test]
fn report_writes_pictures_and_a_self_contained_html() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .arg("--report")
        .arg("rep");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    for f in [
        "load-path-forces.svg",
        "load-path-displacements.svg",
        "structure.svg",
    ] {
        let svg = std::fs::read_to_string(cmd.path("rep").join(f)).unwrap();
        assert!(svg.starts_with("<svg") || svg.starts_with("<?xml"), "{f}");
        assert!(!svg.contains("<text"), "{f}: text must not depend on fonts");
    }
    let html = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
    assert!(html.matches("<svg").count() >= 3, "pictures inline");
    // Self-contained: no link to anything but XML namespaces.
    let stripped = html
        .replace("http://www.w3.org/2000/svg", "")
        .replace("http://www.w3.org/1999/xlink", "");
    assert!(!stripped.contains("http://") && !stripped.contains("https://"));
    assert!(!html.contains("<script src") && !html.contains("<link"));
    let contact = TestCommand::new(&["solve"])
        .arg(example1())
        .arg("--report")
        .arg("r2");
    assert_eq!(contact.run().code, 0);
    assert!(contact.path("r2/report.html").is_file());
    let picked = TestCommand::new(&["solve"])
        .arg(root().join("examples/example1-beam.toml"))
        .args(&[
            "--report",
            "r",
            "--report-pairs",
            "support.1,support.3",
            "--moments",
            "--stress",
            "sxx",
        ]);
    assert_eq!(picked.run().code, 0);
    let unknown = TestCommand::new(&["solve"])
        .arg(root().join("examples/example1-beam.toml"))
        .args(&["--report", "r", "--report-pairs", "nosuch"])
        .run();
    assert_eq!(unknown.code, 2);
    assert!(
        unknown.stderr.contains("no pair named 'nosuch'"),
        "{}",
        unknown.stderr
    );
}

#[test]
fn vtk_writes_a_collection_over_the_load_path() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example2-cantilever.toml"))
        .arg("--vtk")
        .arg("vtk");
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let pvd = std::fs::read_to_string(cmd.path("vtk/unilateral.pvd")).unwrap();
    let steps = pvd.matches("<DataSet").count();
    assert!(
        steps >= 2 * 17,
        "start, 16 events, the reported load: {steps} data sets"
    );
    assert!(cmd.path("vtk/mesh_000.vtu").is_file() && cmd.path("vtk/pairs_000.vtu").is_file());
}

/// The `timings` of a result document: every key in `present` is a number ≥ 0 (JSON has no
/// non-finite numbers: `as_f64` fails on anything else), every key in `absent` is missing, no
/// other key is there, and the parts add up to no more than `wall`, the wall-clock time the test
/// measured around the whole process (the parts do not overlap and all lie inside it).
fn check_timings(j: &Value, present: &[&str], absent: &[&str], wall: f64, what: &str) {
    let t = j["timings"]
        .as_object()
        .unwrap_or_else(|| panic!("{what}: no timings object"));
    let mut sum = 0.0;
    for k in present {
        let s = t
            .get(*k)
            .and_then(Value::as_f64)
            .unwrap_or_else(|| panic!("{what}: timings.{k} missing: {t:?}"));
        assert!(s.is_finite() && s >= 0.0, "{what}: timings.{k} = {s}");
        sum += s;
    }
    for k in absent {
        assert!(!t.contains_key(*k), "{what}: timings.{k} present: {t:?}");
    }
    assert_eq!(t.len(), present.len(), "{what}: {t:?}");
    assert!(
        sum <= wall,
        "{what}: parts {sum} s > the process's {wall} s"
    );
}

/// `run` and the wall-clock seconds around it.
fn timed(cmd: &TestCommand) -> (Output, f64) {
    let start = std::time::Instant::now();
    let out = cmd.run();
    (out, start.elapsed().as_secs_f64())
}

/// The last line of the summary: `time: ` and the parts done by then, in the order of a run.
fn time_line(stdout: &str) -> &str {
    let last = stdout.lines().last().unwrap_or_default();
    assert!(last.starts_with("time: read "), "{stdout}");
    last
}

#[test]
fn results_carry_the_timings_of_the_parts_that_happened() {
    // A structural model: all five parts, `write` covering the summary and the CSV tables.
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example1-beam.toml"))
        .args(&["--json", "out.json", "--csv", "tables"]);
    let (out, wall) = timed(&cmd);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let all = ["read", "condense", "solve", "recover", "write"];
    check_timings(&cmd.json("out.json"), &all, &[], wall, "structural");
    let line = time_line(&out.stdout);
    let shape: String = line
        .chars()
        .filter(|c| !c.is_ascii_digit() && *c != '.')
        .collect();
    assert_eq!(
        shape, "time: read  s, condense  s, solve  s, recover  s",
        "{line}"
    );

    // A contact zone: nothing to condense or recover.
    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--json", "out.json"]);
    let (out, wall) = timed(&cmd);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let zone = ["read", "solve", "write"];
    check_timings(
        &cmd.json("out.json"),
        &zone,
        &["condense", "recover"],
        wall,
        "zone",
    );
    assert!(
        time_line(&out.stdout).contains(", solve "),
        "{}",
        out.stdout
    );

    // The JSON on stdout and nothing else: nothing is written before it, so no `write`.
    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--json", "-"]);
    let (out, wall) = timed(&cmd);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j: Value = serde_json::from_str(&out.stdout).expect("JSON on stdout");
    check_timings(
        &j,
        &["read", "solve"],
        &["condense", "recover", "write"],
        wall,
        "stdout",
    );

    // A plain LCP.
    let cmd = TestCommand::new(&["lcp"])
        .arg(siconos("lcp").join("lcp_CPS_3.dat"))
        .args(&["--json", "out.json"]);
    let (out, wall) = timed(&cmd);
    assert_eq!(out.code, 0, "{}", out.stderr);
    check_timings(
        &cmd.json("out.json"),
        &zone,
        &["condense", "recover"],
        wall,
        "lcp",
    );
    assert!(
        time_line(&out.stdout).contains(", solve "),
        "{}",
        out.stdout
    );
}

/// The JSON is written last, after the report: its `write` covers the report (and the JSON is
/// still written when the report cannot be: here its directory would be inside a file).
#[test]
fn the_json_is_written_after_the_other_outputs() {
    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--json", "out.json", "--report", "rep"]);
    let (out, wall) = timed(&cmd);
    assert_eq!(out.code, 0, "{}", out.stderr);
    let json_time = std::fs::metadata(cmd.path("out.json"))
        .unwrap()
        .modified()
        .unwrap();
    let html_time = std::fs::metadata(cmd.path("rep/report.html"))
        .unwrap()
        .modified()
        .unwrap();
    assert!(json_time >= html_time);
    check_timings(
        &cmd.json("out.json"),
        &["read", "solve", "write"],
        &[],
        wall,
        "report",
    );

    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--json", "out.json", "--report", "file/rep"]);
    std::fs::write(cmd.path("file"), "").unwrap();
    let out = cmd.run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert_eq!(cmd.json("out.json")["status"], "ray");
}

/// A command line refused (a pair name that the model does not have, `--vtk` for a contact
/// zone) is refused before the solve: exit 2, nothing on stdout, no file written.
#[test]
fn a_bad_command_line_writes_nothing() {
    for (file, bad) in [
        (
            root().join("examples/example1-beam.toml"),
            ["--report", "r", "--report-pairs", "nosuch"],
        ),
        (example1(), ["--report", "r", "--report-pairs", "nosuch"]),
        (example1(), ["--vtk", "v", "--report", "r"]),
    ] {
        let cmd = TestCommand::new(&["solve"])
            .arg(&file)
            .args(&bad)
            .args(&["--json", "out.json", "--csv", "t"]);
        let out = cmd.run();
        assert_eq!(out.code, 2, "{bad:?}: {}", out.stderr);
        assert!(out.stdout.is_empty(), "{bad:?}: {}", out.stdout);
        for f in ["out.json", "t", "r", "v"] {
            assert!(!cmd.path(f).exists(), "{bad:?}: {f} written");
        }
    }
}

/// A load history through the binary (`tests/data/history/zone-cycle.toml`: one pair, k_t = 100,
/// f = 0.5, N = 10, T* = 8 > f·N, pushed, released, pulled, released). By hand (x_t = T + k_t·z_t,
/// sliding at |x_t| = 5, a sticking pair keeps its slip): after the push z_t = −(8 − 5)/100 =
/// −0.03, x_t = +5; released, x_t = 100·(−0.03) = −3 (stick); pulled, it slides back from
/// T = −2 (s = 0.25) to z_t = +0.03, x_t = −5; released, x_t = +3 (stick).
#[test]
fn history_through_the_binary_by_hand() {
    let file = root().join("tests/data/history/zone-cycle.toml");
    let cmd = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--json", "out.json", "--csv", "csv", "--report", "rep"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(
        out.stdout.contains("every stage was completed"),
        "{}",
        out.stdout
    );
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "completed");
    let stages = j["history"].as_array().unwrap();
    assert_eq!(stages.len(), 5);
    let want = [
        (0.0, 0.0, "stick"),
        (-0.03, 5.0, "slip-"),
        (-0.03, -3.0, "stick"),
        (0.03, -5.0, "slip+"),
        (0.03, 3.0, "stick"),
    ];
    for (st, (z_t, x_t, state)) in stages.iter().zip(want) {
        assert_eq!(st["status"], "completed");
        assert!(close(&st["s_end"], 1.0, 0.0));
        let p = &st["pairs"][0];
        assert_eq!(p["state"], state, "{st}");
        assert!(
            close(&p["z_t"], z_t, 1e-12) && close(&p["x_t"], x_t, 1e-12),
            "{st}"
        );
        assert!(close(&p["x_n"], 10.0, 1e-12));
        for key in ["equation", "complementarity", "feasibility", "dissipation"] {
            assert!(
                st["residual"][key].as_f64().unwrap() <= 1e-12,
                "{key}: {st}"
            );
        }
    }
    assert_eq!(stages[2]["name"], "stage 3");
    assert!(close(&stages[1]["factors_end"]["push"], 1.0, 0.0));
    assert!(close(&stages[3]["factors_start"]["push"], 0.0, 0.0));
    // The pull: the slip starts at s = 0.25 (T = −2), in the + direction.
    let pull = stages[3]["steps"].as_array().unwrap();
    assert!(
        pull.iter().any(|s| close(&s["s"], 0.25, 1e-12)
            && s["events"]
                .as_array()
                .unwrap()
                .iter()
                .any(|e| e.as_str().unwrap().contains("slip"))),
        "{pull:?}"
    );
    // The files.
    for f in [
        "csv/history_events.csv",
        "csv/history_breakpoints.csv",
        "rep/report.html",
    ] {
        assert!(cmd.path(f).is_file(), "{f} not written");
    }
    let html = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("stage 3"));
}

/// Bad histories through the binary: exit 2 with the file, line, column and key.
#[test]
fn bad_histories_exit_2_with_their_place() {
    let data = root().join("tests/data/history");
    for (file, place) in [
        (
            "bad-unknown-case.toml",
            "bad-unknown-case.toml:16:13: history[2].factors.puhs",
        ),
        (
            "bad-tightening.toml",
            "bad-tightening.toml:10:1: solve.tightening",
        ),
        ("bad-empty.json", "bad-empty.json:4:14: history"),
    ] {
        let out = TestCommand::new(&["solve"]).arg(data.join(file)).run();
        assert_eq!(out.code, 2, "{file}: {}", out.stderr);
        assert!(out.stderr.contains(place), "{file}: {}", out.stderr);
        assert!(out.stdout.is_empty());
    }
    // The paper's path options on the command line do not apply either.
    let out = TestCommand::new(&["solve"])
        .arg(data.join("zone-cycle.toml"))
        .args(&["--tightening", "5"])
        .run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(out
        .stderr
        .contains("--tightening does not apply to a file with a [[history]]"));
    // Nor --json-breakpoints, which the history's JSON would ignore (its steps carry every
    // pair already); no file is written.
    let cmd = TestCommand::new(&["solve"])
        .arg(data.join("zone-cycle.toml"))
        .args(&["--json", "h.json", "--json-breakpoints"]);
    let out = cmd.run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(cmd.path(".").is_dir() && !cmd.path("h.json").exists());
    assert!(out
        .stderr
        .contains("--json-breakpoints does not apply to a file with a [[history]]"));
}

/// The bundled deck on sliding bearings under a daily ±20 K cycle. References: Coulomb's law at
/// every bearing that slides (|x_t| = f·x_n, f = 0.05, the file's friction), and shakedown: a symmetric cycle repeats — the state at the end of every cold (and every warm)
/// stage after the first day is the same.
#[test]
fn deck_on_sliding_bearings_shakes_down() {
    let file = root().join("examples/deck-bearings-temperature.toml");
    let cmd = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--json", "out.json", "--vtk", "vtk"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "completed");
    let stages = j["history"].as_array().unwrap();
    assert_eq!(stages.len(), 8);
    let pairs = |k: usize| stages[k]["pairs"].as_array().unwrap().clone();
    for k in 1..8 {
        for p in pairs(k) {
            let (xn, xt) = (p["x_n"].as_f64().unwrap(), p["x_t"].as_f64().unwrap());
            assert!(xn > 0.0, "{p}");
            if p["state"] != "stick" {
                assert!(
                    (xt.abs() - 0.05 * xn).abs() <= 1e-9 * xn,
                    "stage {}: {p}",
                    k + 1
                );
            }
        }
    }
    for (a, b) in [(2, 4), (4, 6), (3, 5)] {
        for (p, q) in pairs(a).iter().zip(pairs(b).iter()) {
            for key in ["x_n", "x_t", "z_t"] {
                let (u, v) = (p[key].as_f64().unwrap(), q[key].as_f64().unwrap());
                assert!(
                    (u - v).abs() <= 1e-9 * u.abs().max(1e-3),
                    "stages {a}, {b}: {p} {q}"
                );
            }
        }
    }
    // Every bearing slides in the first warming (the end piers could only follow 12 mm with
    // about 1.2 MN, far more than f·N): it is slipping at the end of the stage.
    assert!(
        pairs(1).iter().all(|p| p["state"] != "stick"),
        "{:?}",
        pairs(1)
    );
    // The ParaView collection: the unloaded start, every change strictly inside a stage (at
    // distinct s), every stage end — each a mesh and a pairs file, in increasing pseudo-time.
    let inner: usize = stages
        .iter()
        .map(|st| {
            let mut s: Vec<f64> = st["steps"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| p["s"].as_f64().unwrap())
                .filter(|&s| s > 0.0 && s < 1.0)
                .collect();
            s.dedup();
            s.len()
        })
        .sum();
    let pvd = std::fs::read_to_string(cmd.path("vtk/history.pvd")).unwrap();
    let times: Vec<f64> = pvd
        .lines()
        .filter_map(|l| l.split("timestep=\"").nth(1))
        .map(|t| t.split('"').next().unwrap().parse().unwrap())
        .collect();
    assert!(inner > 0);
    assert_eq!(times.len(), 2 * (1 + inner + 8), "{pvd}");
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "{times:?}");
    assert_eq!(*times.last().unwrap(), 8.0);
}

/// `--report-nodes` on a structural history draws the chosen nodes' load–displacement curves;
/// a node the model does not have is bad input, refused before any work.
#[test]
fn history_report_with_node_curves() {
    let file = root().join("examples/deck-bearings-temperature.toml");
    let cmd = TestCommand::new(&["solve"]).arg(&file).args(&[
        "--report",
        "rep",
        "--report-nodes",
        "deck.24,pier2.4",
    ]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let svg = std::fs::read_to_string(cmd.path("rep/history-nodes.svg")).unwrap();
    assert!(svg.contains("node deck.24") && svg.contains("node pier2.4"));
    let html = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
    assert!(html.contains("node(s) deck.24, pier2.4"));
    let out = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--report", "rep", "--report-nodes", "deck.99"])
        .run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(
        out.stderr.contains("no node named 'deck.99'"),
        "{}",
        out.stderr
    );
    // Without a structural history there are no node curves to draw.
    let out = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--report", "rep", "--report-nodes", "1"])
        .run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(
        out.stderr
            .contains("--report-nodes charts the load history"),
        "{}",
        out.stderr
    );
    // Each kind of file is told what it lacks: a structural model without stages, a contact
    // zone with a history (it has one: no nodes), a contact zone without.
    for (file, lacks) in [
        (
            root().join("examples/example2-cantilever.toml"),
            "this model has no [[history]] stages",
        ),
        (
            root().join("tests/data/history/zone-cycle.toml"),
            "this file is a contact zone, whose history has pairs but no nodes",
        ),
        (
            root().join("examples/example1-contact-zone.toml"),
            "this file is a contact zone, with no nodes and no [[history]]",
        ),
    ] {
        let out = TestCommand::new(&["solve"])
            .arg(file.clone())
            .args(&["--report", "rep", "--report-nodes", "1"])
            .run();
        assert_eq!(out.code, 2, "{}", out.stderr);
        assert!(out.stderr.contains(lacks), "{file:?}: {}", out.stderr);
    }
}

/// A reader that closes the pipe early (`unilateral solve … | head -1`) is no failure: no
/// panic, exit 0.
#[test]
fn a_closed_stdout_is_no_panic() {
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_unilateral"))
        .arg("solve")
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run unilateral");
    drop(child.stdout.take());
    let out = child.wait_with_output().expect("wait");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}

/// The zone `unilateral zone` writes for a finely meshed structure reads back and solves like
/// its model: Example 1's beam (EI = 1, EA = 2, spans of 2 m) with 200 frames a span, whose
/// `Rnn` (singular: rank one) carries the condensation's round-off in its zero eigenvalues —
/// −4.5e-8 of its largest entry (numpy), refused by a semidefinite check at round-off level —
/// and must not be refused. The answer at p = 1 is the paper's (formulation §5), each pair's
/// force and state the same from the model and from its zone file.
#[test]
fn a_finely_meshed_zone_reads_back_and_solves_like_its_model() {
    let model = "[[sections]]\nname = \"b\"\nE = 1.0\nA = 2.0\nI = 1.0\n\
                 [[members]]\nname = \"m0\"\nstart = [0.0, 0.0]\nend = [2.0, 0.0]\n\
                 divisions = 200\nsection = \"b\"\n\
                 [[members]]\nname = \"m1\"\nstart = \"m0.end\"\nend = [4.0, 0.0]\n\
                 divisions = 200\nsection = \"b\"\n\
                 [[contact]]\nname = \"s\"\nfrom = \"ground\"\n\
                 to = [\"m0.start\", \"m0.end\", \"m1.end\"]\nnormal = [0.0, 1.0]\nfriction = 0.6\n\
                 [[loads.variable.nodal]]\nnodes = \"m1.100\"\nfy = -1.0\n\
                 [solve]\ntightening = 1.0\n";
    let cmd = TestCommand::new(&["zone", "fine.toml", "--out", "zone.toml"]);
    std::fs::write(cmd.path("fine.toml"), model).unwrap();
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let solve = |file: &str, json: &str| {
        let c = TestCommand::new(&["solve"])
            .arg(cmd.path(file))
            .arg("--json")
            .arg(cmd.path(json));
        let out = c.run();
        assert_eq!(out.code, 0, "{file}: {}", out.stderr);
        let text = std::fs::read_to_string(cmd.path(json)).unwrap();
        serde_json::from_str::<Value>(&text).unwrap()
    };
    let (a, b) = (solve("fine.toml", "a.json"), solve("zone.toml", "b.json"));
    let pairs = |j: &Value| -> Vec<(f64, String)> {
        j["pairs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                (
                    p["x_n"].as_f64().unwrap(),
                    p["state"].as_str().unwrap().to_string(),
                )
            })
            .collect()
    };
    let (pa, pb) = (pairs(&a), pairs(&b));
    assert_eq!(pa.len(), 3);
    for ((xa, sa), (xb, sb)) in pa.iter().zip(&pb) {
        assert_eq!(sa, sb, "{pa:?} / {pb:?}");
        assert!((xa - xb).abs() <= 1e-6, "{pa:?} / {pb:?}");
    }
}

/// `unilateral zone` writes a model's contact zone as a contact-zone file. References: the
/// paper's Example 1 zone (formulation §5: Rnn, Rtt, Rv_n written out by hand there) from the
/// structural beam; and round trips — the zone file of the sheet pile wall follows the same path
/// as the model (the same 39 events at the same loads, the same pairs), the zone file of the
/// deck the same history.
#[test]
fn zone_command_writes_a_solvable_contact_zone() {
    let cmd = TestCommand::new(&["zone"])
        .arg(root().join("examples/example1-beam.toml"))
        .args(&["--out", "z1.toml"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let text = std::fs::read_to_string(cmd.path("z1.toml")).unwrap();
    let doc: toml::Table = text.parse().expect("TOML");
    // The model's title and units as the zone file's own keys (they were comments).
    assert_eq!(
        doc["title"].as_str(),
        Some("Example 1: beam on three unilateral supports")
    );
    assert_eq!(doc["units"].as_str(), Some("N, m"));
    let rows = |key: &str| -> Vec<Vec<f64>> {
        doc["contact_zone"][key]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| {
                r.as_array()
                    .unwrap()
                    .iter()
                    .map(|v| v.as_float().unwrap())
                    .collect()
            })
            .collect()
    };
    let rnn = [
        [0.1875, -0.375, 0.1875],
        [-0.375, 0.75, -0.375],
        [0.1875, -0.375, 0.1875],
    ];
    let rtt = [[1.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]];
    for (got, want) in [(rows("Rnn"), rnn), (rows("Rtt"), rtt)] {
        for i in 0..3 {
            for j in 0..3 {
                assert!((got[i][j] - want[i][j]).abs() < 1e-9, "{got:?}");
            }
        }
    }
    let rv: Vec<f64> = doc["load"]["variable"]["normal"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_float().unwrap())
        .collect();
    for (a, b) in rv.iter().zip([-0.09375, 0.6875, 0.40625]) {
        assert!((a - b).abs() < 1e-9, "{rv:?}");
    }
    // Round trip of the sheet pile wall: the same path.
    let model = root().join("examples/example3-sheet-pile.toml");
    let cmd = TestCommand::new(&["zone"])
        .arg(&model)
        .args(&["--out", "z3.toml"]);
    assert_eq!(cmd.run().code, 0);
    let a = TestCommand::new(&["solve"])
        .arg(cmd.path("z3.toml"))
        .args(&["--json", "-"])
        .run();
    let b = TestCommand::new(&["solve"])
        .arg(&model)
        .args(&["--json", "-"])
        .run();
    let (a, b): (Value, Value) = (
        serde_json::from_str(&a.stdout).unwrap(),
        serde_json::from_str(&b.stdout).unwrap(),
    );
    assert_eq!(a["status"], b["status"]);
    assert_eq!(a["steps"].as_array().unwrap().len(), 39);
    for (x, y) in a["steps"]
        .as_array()
        .unwrap()
        .iter()
        .zip(b["steps"].as_array().unwrap())
    {
        assert_eq!(x["events"], y["events"]);
        assert!(close(
            &x["p"],
            y["p"].as_f64().unwrap(),
            1e-9 * y["p"].as_f64().unwrap().abs()
        ));
    }
    for (x, y) in a["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .zip(b["pairs"].as_array().unwrap())
    {
        assert_eq!(x["name"], y["name"]);
        assert_eq!(x["state"], y["state"]);
        for k in ["x_n", "x_t", "z_n", "z_t"] {
            let v = y[k].as_f64().unwrap();
            assert!(close(&x[k], v, 1e-9 * v.abs().max(1e-6)), "{k}: {x} {y}");
        }
    }
    // A history model: the zone file keeps its cases and stages.
    let deck = root().join("examples/deck-bearings-temperature.toml");
    let cmd = TestCommand::new(&["zone"])
        .arg(&deck)
        .args(&["--out", "zd.toml"]);
    assert_eq!(cmd.run().code, 0);
    let a = TestCommand::new(&["solve"])
        .arg(cmd.path("zd.toml"))
        .args(&["--json", "-"])
        .run();
    assert_eq!(a.code, 0, "{}", a.stderr);
    let b = TestCommand::new(&["solve"])
        .arg(&deck)
        .args(&["--json", "-"])
        .run();
    let (a, b): (Value, Value) = (
        serde_json::from_str(&a.stdout).unwrap(),
        serde_json::from_str(&b.stdout).unwrap(),
    );
    assert_eq!(a["history"].as_array().unwrap().len(), 8);
    for (x, y) in a["pairs"]
        .as_array()
        .unwrap()
        .iter()
        .zip(b["pairs"].as_array().unwrap())
    {
        let v = y["x_t"].as_f64().unwrap();
        assert!(close(&x["x_t"], v, 1e-9 * v.abs()), "{x} {y}");
    }
    // A contact-zone file is not a model.
    let out = TestCommand::new(&["zone"])
        .arg(example1())
        .args(&["--out", "x.toml"])
        .run();
    assert_eq!(out.code, 2, "{}", out.stderr);
}

/// `tableau` on a structural model prints the tableaux of its condensed zone: for the paper's
/// Example 1 beam the very tableaux of the contact-zone Example 1 (the paper's Tables 1–3).
#[test]
fn tableau_of_a_structural_model() {
    let beam = TestCommand::new(&["tableau"])
        .arg(root().join("examples/example1-beam.toml"))
        .run();
    let zone = TestCommand::new(&["tableau"]).arg(example1()).run();
    assert_eq!(beam.code, 0, "{}", beam.stderr);
    let body = |s: &str| s.lines().skip(1).collect::<Vec<_>>().join("\n");
    let (b, z) = (body(&beam.stdout), body(&zone.stdout));
    // The same tableaux up to round-off of the condensation, printed to 4 decimals (0.09375
    // may print as 0.0937 or 0.0938): compare the printed numbers to their last digit.
    let nums = |s: &str| -> Vec<f64> {
        s.split_whitespace()
            .filter_map(|w| w.parse::<f64>().ok())
            .collect()
    };
    let (nb, nz) = (nums(&b), nums(&z));
    assert_eq!(nb.len(), nz.len());
    for (x, y) in nb.iter().zip(&nz) {
        assert!((x - y).abs() <= 1.01e-4 * y.abs().max(1.0), "{x} vs {y}");
    }
    assert!(b.contains("10.6667"));
}

/// Node-to-segment pairs are drawn at their A point on the segment, not at the segment's first
/// node: `tests/data/models/footing-surface.toml` (the footing's base nodes at x = −0.5, −1/6,
/// 1/6, 0.5 on the soil's top, whose nodes are 0.4 apart) — by hand, each A point is the
/// footing node's own position (the base lies on the soil's top line, y = 0).
#[test]
fn segment_pairs_are_drawn_at_their_point_on_the_segment() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("tests/data/models/footing-surface.toml"))
        .args(&["--vtk", "vtk"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let vtu = std::fs::read_to_string(cmd.path("vtk/pairs_001.vtu")).unwrap();
    let block = vtu
        .split("Name=\"Points\"")
        .nth(1)
        .and_then(|s| s.split('>').nth(1))
        .and_then(|s| s.split('<').next())
        .unwrap();
    let v: Vec<f64> = block
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(v.len(), 8 * 3, "{block}");
    let xs = [-0.5, -1.0 / 6.0, 1.0 / 6.0, 0.5];
    for (k, x) in xs.iter().enumerate() {
        // B (the footing node) and A (its projection on the soil's top) at the same place.
        for p in [k, 4 + k] {
            assert!(
                (v[3 * p] - x).abs() < 1e-12 && v[3 * p + 1].abs() < 1e-12,
                "point {p}: {v:?}"
            );
        }
    }
}

// ---- issue 14: tables of the whole path, units and provenance, one line for the files ----

/// A beam on `m` frictional supports pressed by its weight (the oracle's fixture: the zone is
/// exact for the beam), written as a contact-zone file with a title and units.
fn beam_zone_file(
    dir: &Path,
    m: usize,
    seed: u64,
) -> (PathBuf, unilateral_oracle::fixtures::beam::BeamZone) {
    let z = unilateral_oracle::fixtures::beam::beam_on_supports(m, seed);
    let names: Vec<String> = (1..=m).map(|i| format!("\"s{i}\"")).collect();
    let text = format!(
        "title = \"beam on {m} supports\"\nunits = \"kN, mm\"\n\n[contact_zone]\nnames = [{}]\n\
         friction = {:?}\nRnn = {:?}\nRtt = {:?}\n\n[load.constant]\nnormal = {:?}\n\n\
         [load.variable]\nnormal = {:?}\ntangential = {:?}\n\n[solve]\ntightening = 0.0\n\
         trace = \"end\"\n",
        names.join(", "),
        z.friction,
        z.rnn,
        z.rtt,
        z.constant_normal,
        z.variable_normal,
        z.variable_tangential
    );
    let path = dir.join("beam.toml");
    std::fs::write(&path, text).unwrap();
    (path, z)
}

/// The columns of a CSV table by name (a unit in brackets after the name is allowed).
fn csv_rows(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let head: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|c| c.split(" [").next().unwrap().to_string())
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (head, rows)
}

/// `path.csv` and the JSON's `changes` of a zone with a constant load and several events,
/// through the binary. Reference: at every breakpoint, brute-force enumeration of the 3m LCP
/// (the oracle's exact rational solver, `x = q0 + p·d + M z` with `M`, `d` and `q0` from
/// formulation.md §3) must hold a solution with the pairs' values (`x_t = (x_t+ − x_t−)/2`,
/// `z_t = (z_t+ − z_t−)/2`); a pair that opens there has `x_n = 0`, one that closes `z_n = 0`,
/// one that starts to slip `|x_t| = f·x_n` (the definitions of the events). One line on stderr
/// names the files.
#[test]
fn path_csv_holds_every_pair_at_every_breakpoint() {
    use unilateral_oracle::{
        enumerate_parametric_exact, fixtures::frictional_lcp, rat, rat_matrix, rat_vec, to_f64,
    };
    let cmd = TestCommand::new(&["solve"]);
    let m = 3;
    let (file, z) = beam_zone_file(cmd.dir.path(), m, 7);
    let cmd = cmd.arg(&file).args(&["--csv", "out", "--json", "r.json"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(
        out.stderr.trim_end(),
        "wrote 3 files in out: pairs.csv, steps.csv, path.csv",
        "one line for the files written"
    );
    // Exact products of the file's numbers: `f·Rnn` is then exactly `f` times `Rnn`, so an
    // open pair's two friction rows agree (rounded products would leave no exact solution).
    let (rnn, rtt, f) = (rat_matrix(&z.rnn), rat_matrix(&z.rtt), rat_vec(&z.friction));
    let zero = rat_vec(&vec![0.0; m]);
    let lcp = frictional_lcp(
        &rnn,
        &rtt,
        &f,
        &rat_vec(&z.variable_normal),
        &rat_vec(&z.variable_tangential),
    );
    let q0 = frictional_lcp(&rnn, &rtt, &f, &rat_vec(&z.constant_normal), &zero).d;
    let (head, rows) = csv_rows(&std::fs::read_to_string(cmd.path("out/path.csv")).unwrap());
    let col = |name: &str| {
        head.iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{name}"))
    };
    let (c_step, c_p, c_pair, c_name) = (col("step"), col("p"), col("pair"), col("name"));
    let (c_xn, c_xt, c_zn, c_zt, c_state) =
        (col("x_n"), col("x_t"), col("z_n"), col("z_t"), col("state"));
    let j = cmd.json("r.json");
    let steps = j["steps"].as_array().unwrap();
    assert!(
        steps.len() >= 3,
        "the fixture has several events: {}",
        steps.len()
    );
    assert_eq!(rows.len(), steps.len() * m, "every pair at every step");
    let (_, step_rows) = csv_rows(&std::fs::read_to_string(cmd.path("out/steps.csv")).unwrap());
    for (k, (st, srow)) in steps.iter().zip(&step_rows).enumerate() {
        let block = &rows[k * m..(k + 1) * m];
        let p: f64 = block[0][c_p].parse().unwrap();
        assert_eq!(
            p,
            st["p"].as_f64().unwrap(),
            "full precision, as in the JSON"
        );
        assert_eq!(block[0][c_p], srow[1], "the step's p as in steps.csv");
        // At a mechanism's limit load no solution exists beyond it, and the rounded `p_lim`
        // may lie just beyond the exact one: that breakpoint is checked by its load only.
        if j["status"] == "mechanism" && k + 1 == steps.len() {
            assert_eq!(j["p_limit"].as_f64(), Some(p));
            continue;
        }
        let sols = enumerate_parametric_exact(&lcp.m, &q0, &lcp.d, &rat(p));
        let vals: Vec<[f64; 4]> = block
            .iter()
            .map(|r| [c_xn, c_xt, c_zn, c_zt].map(|c| r[c].parse::<f64>().unwrap()))
            .collect();
        let xs = vals
            .iter()
            .flat_map(|v| [v[0], v[1]])
            .fold(1e-300, |a: f64, b| a.max(b.abs()));
        let zs = vals
            .iter()
            .flat_map(|v| [v[2], v[3]])
            .fold(1e-300, |a: f64, b| a.max(b.abs()));
        let found = sols.iter().any(|s| {
            let w: Vec<f64> = s.w.iter().map(to_f64).collect();
            let zz: Vec<f64> = s.z.iter().map(to_f64).collect();
            (0..m).all(|i| {
                let want = [
                    w[i],
                    (w[m + i] - w[2 * m + i]) / 2.0,
                    zz[i],
                    (zz[m + i] - zz[2 * m + i]) / 2.0,
                ];
                (0..4).all(|c| {
                    let scale = if c < 2 { xs } else { zs };
                    (vals[i][c] - want[c]).abs() <= 1e-9 * scale
                })
            })
        });
        assert!(
            found,
            "step {}: {block:?} is no solution of the LCP at p = {p}",
            k + 1
        );
        for (i, r) in block.iter().enumerate() {
            assert_eq!(r[c_step], (k + 1).to_string());
            assert_eq!(r[c_pair], (i + 1).to_string());
            assert_eq!(r[c_name], format!("s{}", i + 1));
            assert!(["open", "stick", "slip+", "slip-"].contains(&r[c_state].as_str()));
        }
        let changes = st["changes"].as_array().unwrap();
        assert_eq!(changes.len(), st["events"].as_array().unwrap().len());
        for (c, sentence) in changes.iter().zip(st["events"].as_array().unwrap()) {
            let i = c["pair"].as_u64().unwrap() as usize - 1;
            assert_eq!(c["name"], format!("s{}", i + 1));
            assert!(sentence
                .as_str()
                .unwrap()
                .starts_with(&format!("pair s{} ", i + 1)));
            let [x_n, x_t, z_n, _] = vals[i];
            match (c["what"].as_str().unwrap(), c["direction"].as_str()) {
                ("opens", None) => assert!(x_n.abs() <= 1e-9 * xs, "{c}: x_n = {x_n}"),
                ("closes", None) => assert!(z_n.abs() <= 1e-9 * zs, "{c}: z_n = {z_n}"),
                ("slips", Some(d)) => {
                    assert!(d == "+" || d == "-", "{c}");
                    if !c["while_open"].as_bool().unwrap() {
                        let limit = z.friction[i] * x_n;
                        assert!(
                            (x_t.abs() - limit).abs() <= 1e-9 * xs,
                            "{c}: {x_t} vs {limit}"
                        );
                    }
                }
                ("sticks", None) => {}
                other => panic!("unexpected change {other:?}"),
            }
        }
    }
}

/// Every JSON document carries `program` (name and version) and `schema: 1`: the paper's path,
/// a plain LCP, a load history. Reference: the package's own name and version.
#[test]
fn every_json_document_says_which_program_and_schema() {
    for (args, file) in [
        (vec!["solve", "EX", "--json", "o.json"], example1()),
        (
            vec!["lcp", "EX", "--json", "o.json"],
            root().join("tests/data/good/lcp_small.toml"),
        ),
        (
            vec!["solve", "EX", "--json", "o.json"],
            root().join("tests/data/history/zone-cycle.toml"),
        ),
    ] {
        let args: Vec<String> = args
            .iter()
            .map(|a| {
                if *a == "EX" {
                    file.display().to_string()
                } else {
                    a.to_string()
                }
            })
            .collect();
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let cmd = TestCommand::new(&args);
        let out = cmd.run();
        assert_eq!(out.code, 0, "{args:?}: {}", out.stderr);
        let j = cmd.json("o.json");
        assert_eq!(j["program"]["name"], "unilateral", "{args:?}");
        assert_eq!(j["program"]["version"], env!("CARGO_PKG_VERSION"));
        assert_eq!(j["schema"], 1);
    }
}

/// Numbers written plainly through the binary on the sheet pile wall: no `-0` field in any CSV
/// table (the fixed wall base's rotation was `-0e0`), none in the summary or the report, at
/// most 6 significant digits in the report's tables and the summary's loads. Reference: the
/// rule itself, checked on every number written.
#[test]
fn numbers_are_written_plainly_through_the_binary() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .args(&["--csv", "csv", "--report", "rep"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(
        out.stderr.lines().count(),
        2,
        "one line per directory: {}",
        out.stderr
    );
    assert!(out
        .stderr
        .starts_with("wrote 7 files in csv: pairs.csv, steps.csv, path.csv,"));
    let negative_zero = |t: &str| {
        t.trim_start_matches('-')
            .chars()
            .all(|c| c == '0' || c == '.' || c == 'e')
            && t.starts_with('-')
            && t.len() > 1
    };
    for f in std::fs::read_dir(cmd.path("csv")).unwrap() {
        let f = f.unwrap().path();
        let text = std::fs::read_to_string(&f).unwrap();
        for field in text.lines().skip(1).flat_map(|l| l.split(',')) {
            assert!(!negative_zero(field), "{}: {field}", f.display());
        }
    }
    let digits = |t: &str| {
        let mantissa = t.trim_start_matches('-').split('e').next().unwrap();
        mantissa
            .trim_start_matches(['0', '.'])
            .chars()
            .filter(char::is_ascii_digit)
            .count()
    };
    for word in out.stdout.split_whitespace() {
        assert!(
            !negative_zero(word.trim_end_matches([',', ')'])),
            "summary: {word}"
        );
    }
    for line in out
        .stdout
        .lines()
        .filter(|l| l.trim_start().starts_with(char::is_numeric))
    {
        let p = line.split_whitespace().nth(1).unwrap();
        assert!(digits(p) <= 6, "a load for people: {line}");
    }
    let html = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
    let mut cells = 0;
    for cell in html.split("<td class=\"n\">").skip(1) {
        let v = cell.split('<').next().unwrap();
        assert!(v.parse::<f64>().is_ok(), "{v}");
        assert!(!negative_zero(v) && digits(v) <= 6, "report: {v}");
        cells += 1;
    }
    assert!(
        cells > 24 * 4,
        "the pairs' table and the events' loads were checked: {cells}"
    );
}

/// A contact-zone file may give `title` and `units` (as a structural model does); anything but
/// a string there is bad input, named with its place. Reference: the file as written.
#[test]
fn a_contact_zone_file_may_give_its_title_and_units() {
    let dir = tempfile::tempdir().unwrap();
    let (file, _) = beam_zone_file(dir.path(), 3, 1);
    let out = TestCommand::new(&["solve"]).arg(&file).run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let text = std::fs::read_to_string(&file)
        .unwrap()
        .replace("units = \"kN, mm\"", "units = 3");
    std::fs::write(&file, text).unwrap();
    let out = TestCommand::new(&["solve"]).arg(&file).run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(
        out.stderr.contains("beam.toml:2:") && out.stderr.contains("units"),
        "{}",
        out.stderr
    );
}

/// The file's units and title reach the outputs through the command line, and
/// `--json-breakpoints` puts every pair's values at every step into the JSON (Example 3:
/// `units = "N, m"`, 39 steps, 24 pairs).
#[test]
fn units_title_and_breakpoints_through_the_command_line() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .args(&["--json", "out.json", "--json-breakpoints", "--csv", "csv"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(out.stdout.contains("units: N, m"), "{}", out.stdout);
    let j = cmd.json("out.json");
    assert_eq!(j["units"], "N, m");
    assert!(j["title"].as_str().unwrap().starts_with("Example 3"));
    let steps = j["steps"].as_array().unwrap();
    assert_eq!(steps.len(), 39);
    assert!(steps
        .iter()
        .all(|s| s["pairs"].as_array().map(|p| p.len()) == Some(24)));
    let header = std::fs::read_to_string(cmd.path("csv/path.csv")).unwrap();
    assert!(
        header.lines().next().unwrap().contains("x_n [N]"),
        "{header}"
    );
}

/// The JSON is written beside its place and renamed into it when complete (the values at the
/// breakpoints are formed while it is written, so a failure may come after the first byte):
/// a file already there is replaced whole, nothing is left beside it, and a folder that does
/// not exist is a clear error naming the file (exit 2).
#[test]
fn the_json_replaces_an_old_file_whole_and_leaves_nothing_beside_it() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .args(&["--json", "out.json", "--json-breakpoints"]);
    std::fs::write(cmd.path("out.json"), "an old result ".repeat(100_000)).unwrap();
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("out.json");
    assert_eq!(j["steps"].as_array().unwrap().len(), 39);
    let names: Vec<String> = std::fs::read_dir(cmd.dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, vec!["out.json".to_string()], "{names:?}");

    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .args(&["--json", "no/such/folder/out.json"]);
    let out = cmd.run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(
        out.stderr.contains("cannot write no/such/folder/out.json"),
        "{}",
        out.stderr
    );
}

/// The README's main job: the sheet pile wall with real loads (the soil's weight constant, the
/// push growing). No tightening: every event is a change of the working scheme at a load
/// p > 0, none settles the start; the path ends in a ray; the paper's method notes where its
/// friction law stops being a real one (the soil's weight left slips that the push gives
/// back).
#[test]
fn sheet_pile_wall_with_real_loads_is_the_main_job() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    assert!(readme.contains("cargo run --release -- solve examples/sheet-pile-wall.toml"));
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/sheet-pile-wall.toml"))
        .args(&["--json", "out.json"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("out.json");
    assert_eq!(j["status"], "ray");
    assert!(close(&j["tightening"], 0.0, 0.0));
    let steps = j["steps"].as_array().unwrap();
    assert!(steps
        .iter()
        .all(|s| s["settling"] == false && s["p"].as_f64().unwrap() > 0.0));
    assert!(j["residual"]["equation"].as_f64().unwrap() < 1e-12);
    assert!(out
        .stdout
        .contains("a [[history]] gives the path-dependent answer"));
    // The incremental law disagrees from the push's start: in the history of
    // `sheet-pile-stages.toml` the pairs the soil's weight left slipping stick at s = 0 of the
    // push, keeping their slip, where the paper's total-slip law starts giving slip back.
    let h = TestCommand::new(&["solve"])
        .arg(root().join("examples/sheet-pile-stages.toml"))
        .args(&["--json", "-"])
        .run();
    let h: Value = serde_json::from_str(&h.stdout).unwrap();
    let kept = h["history"][1]["steps"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["s"].as_f64() == Some(0.0))
        .flat_map(|s| s["events"].as_array().unwrap().clone())
        .filter(|e| e.as_str().unwrap().contains("kept"))
        .count();
    assert!(kept > 0);
}

/// The summary says how many pairs each `[[contact]]` entry made (Example 3: 12 wall nodes above
/// the base on each side, by the file's geometry).
#[test]
fn summary_counts_the_pairs_of_each_contact_entry() {
    let out = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert!(
        out.stdout.lines().nth(1) == Some("pairs by [[contact]] entry: left 12, right 12"),
        "{}",
        out.stdout
    );
}

/// For many pairs the summary scales: counts of the states (which add up to m), the first and
/// last events, the pairs with the largest forces and slips; `--verbose` lists everything (a
/// beam on 60 frictional supports, the oracle's fixture).
#[test]
fn the_summary_scales_with_the_pairs() {
    let dir = tempfile::tempdir().unwrap();
    let (file, _) = beam_zone_file(dir.path(), 60, 3);
    let short = TestCommand::new(&["solve"]).arg(&file).run();
    assert_eq!(short.code, 0, "{}", short.stderr);
    let long = TestCommand::new(&["solve"])
        .arg(&file)
        .arg("--verbose")
        .run();
    assert_eq!(long.code, 0, "{}", long.stderr);
    let line = short
        .stdout
        .lines()
        .find(|l| l.contains("(60 pairs):"))
        .unwrap_or_else(|| panic!("{}", short.stdout));
    let counts: usize = line
        .split(':')
        .nth(1)
        .unwrap()
        .split(',')
        .filter_map(|w| w.split_whitespace().next()?.parse::<usize>().ok())
        .sum();
    assert_eq!(counts, 60, "{line}");
    assert!(
        short.stdout.contains("largest normal forces") && short.stdout.contains("largest slips")
    );
    // Every pair is in the verbose table, and the short summary is much shorter.
    assert!((1..=60).all(|i| long
        .stdout
        .lines()
        .any(|l| l.trim_start().starts_with(&format!("s{i} ")))));
    assert!(
        short.stdout.lines().count() * 2 < long.stdout.lines().count(),
        "{}",
        short.stdout
    );
}

/// `--verbose` lists every step of the path, as its help says: the table has one row for each
/// of the JSON's steps (the sheet-pile wall: 45, of which 16 change no pair's state), where the
/// default lists the 29 that change a pair's state.
#[test]
fn verbose_lists_every_step() {
    let file = root().join("examples/sheet-pile-wall.toml");
    let cmd = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--verbose", "--json", "out.json"]);
    let long = cmd.run();
    assert_eq!(long.code, 0, "{}", long.stderr);
    let doc: Value =
        serde_json::from_str(&std::fs::read_to_string(cmd.path("out.json")).unwrap()).unwrap();
    let steps = doc["steps"].as_array().unwrap();
    let rows = |text: &str| -> Vec<usize> {
        text.lines()
            .skip_while(|l| !l.starts_with("load path ("))
            .skip(2)
            .map_while(|l| l.split_whitespace().next()?.parse::<usize>().ok())
            .collect()
    };
    let all = rows(&long.stdout);
    assert_eq!(
        all,
        (1..=steps.len()).collect::<Vec<_>>(),
        "{}",
        long.stdout
    );
    assert_eq!(steps.len(), 45);
    let short = TestCommand::new(&["solve"]).arg(&file).run();
    let listed = rows(&short.stdout);
    let changing = steps
        .iter()
        .filter(|s| !s["events"].as_array().unwrap().is_empty())
        .count();
    assert_eq!(changing, 29);
    assert_eq!(listed.len(), changing, "{}", short.stdout);
}

/// `--moments` and `--stress` draw on a structural model's structure picture: the reports of a
/// contact zone and of load histories have none, and the options, which were accepted and
/// ignored there (a byte-identical report), are refused; on a structural model they act.
#[test]
fn structure_picture_options_where_there_is_no_structure_picture() {
    for (file, what) in [
        (
            "examples/example1-contact-zone.toml",
            "the report of a contact zone has none",
        ),
        (
            "examples/deck-bearings-temperature.toml",
            "the report of a load history has none",
        ),
        (
            "tests/data/history/zone-cycle.toml",
            "the report of a contact zone's load history has none",
        ),
    ] {
        for opt in [&["--moments"][..], &["--stress", "sxx"][..]] {
            let cmd = TestCommand::new(&["solve"])
                .arg(root().join(file))
                .args(&["--report", "rep"])
                .args(opt);
            let out = cmd.run();
            assert_eq!(out.code, 2, "{file} {opt:?}: {}", out.stderr);
            assert!(
                out.stderr.contains(opt[0]) && out.stderr.contains(what),
                "{file} {opt:?}: {}",
                out.stderr
            );
            assert!(!cmd.path("rep").exists(), "{file} {opt:?}");
        }
    }
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example3-sheet-pile.toml"))
        .args(&["--report", "rep", "--stress", "sxx"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let picture = std::fs::read_to_string(cmd.path("rep/structure.svg")).unwrap();
    assert!(picture.contains("σ_{xx}"), "the colour bar's label");
}

/// A history's summary and JSON carry the file's units and title too (the deck: `units =
/// "N, m, K"`).
#[test]
fn history_outputs_carry_units_and_title() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/deck-bearings-temperature.toml"))
        .args(&["--json", "out.json"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    assert_eq!(
        out.stdout.lines().nth(1),
        Some("units: N, m, K"),
        "{}",
        out.stdout
    );
    let j = cmd.json("out.json");
    assert_eq!(j["units"], "N, m, K");
    assert_eq!(
        j["title"],
        "Deck on sliding bearings: a daily temperature cycle"
    );
    assert_eq!(j["schema"], 1);
}

// ---------------------------------------------------------------------------------------------
// The structure picture and binary VTK (issue 14, "Pictures" and "VTK").

/// `--vtk-format`: the same files in every format, the same collection; `binary` appends raw
/// arrays (`header_type="UInt64"`), `compressed` zlib blocks, `lz4` LZ4 blocks; the default is
/// ascii. Reference: the ascii run of the same problem — the points of the pairs' file decoded
/// from the binary one (an 8-byte count, then little-endian doubles) are the ascii file's
/// numbers; the full decoding of every array, compressed too, is
/// `crates/output/tests/it/vtk_binary.rs`.
#[test]
fn vtk_format_binary_and_compressed_through_the_binary() {
    let file = root().join("examples/example2-cantilever.toml");
    let run = |dir: &str, format: Option<&str>| {
        let mut cmd = TestCommand::new(&["solve"])
            .arg(&file)
            .args(&["--vtk", dir]);
        if let Some(f) = format {
            cmd = cmd.args(&["--vtk-format", f]);
        }
        let out = cmd.run();
        assert_eq!(out.code, 0, "{}", out.stderr);
        let mut names: Vec<String> = std::fs::read_dir(cmd.path(dir))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        let read = |n: &str| std::fs::read(cmd.path(&format!("{dir}/{n}"))).unwrap();
        let files: Vec<(String, Vec<u8>)> = names.iter().map(|n| (n.clone(), read(n))).collect();
        files
    };
    let ascii = run("a", None);
    let binary = run("b", Some("binary"));
    let compressed = run("z", Some("compressed"));
    let lz4 = run("l", Some("lz4"));
    let names = |f: &[(String, Vec<u8>)]| f.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&ascii), names(&binary));
    assert_eq!(names(&ascii), names(&compressed));
    assert_eq!(names(&ascii), names(&lz4));
    let find = |f: &[(String, Vec<u8>)], n: &str| f.iter().find(|x| x.0 == n).unwrap().1.clone();
    let pvd = "unilateral.pvd";
    assert_eq!(find(&ascii, pvd), find(&binary, pvd));
    assert_eq!(find(&ascii, pvd), find(&compressed, pvd));
    assert_eq!(find(&ascii, pvd), find(&lz4, pvd));
    let contains = |b: &[u8], s: &str| b.windows(s.len()).any(|w| w == s.as_bytes());
    for (name, bytes) in &ascii {
        if name.ends_with(".vtu") {
            assert!(!contains(bytes, "appended"), "{name}");
        }
    }
    for (name, bytes) in &binary {
        if name.ends_with(".vtu") {
            assert!(contains(bytes, "header_type=\"UInt64\""), "{name}");
            assert!(!contains(bytes, "compressor"), "{name}");
            assert!(contains(bytes, "<AppendedData encoding=\"raw\">"), "{name}");
        }
    }
    for (files, compressor) in [
        (&compressed, "vtkZLibDataCompressor"),
        (&lz4, "vtkLZ4DataCompressor"),
    ] {
        for (name, bytes) in files {
            if name.ends_with(".vtu") {
                let tag = format!("compressor=\"{compressor}\"");
                assert!(contains(bytes, &tag), "{name}");
            }
        }
    }
    // The points of a pairs file, from the text and from the appended bytes.
    let text = String::from_utf8(find(&ascii, "pairs_001.vtu")).unwrap();
    let from_text: Vec<f64> = text
        .split("Name=\"Points\"")
        .nth(1)
        .and_then(|s| s.split('>').nth(1))
        .and_then(|s| s.split('<').next())
        .unwrap()
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let bytes = find(&binary, "pairs_001.vtu");
    let tag_at = bytes
        .windows(13)
        .position(|w| w == b"Name=\"Points\"")
        .unwrap();
    let tag = String::from_utf8_lossy(&bytes[tag_at..tag_at + 200]).into_owned();
    let offset: usize = tag
        .split("offset=\"")
        .nth(1)
        .and_then(|s| s.split('"').next())
        .unwrap()
        .parse()
        .unwrap();
    let mark = b"<AppendedData encoding=\"raw\">";
    let data_at = bytes.windows(mark.len()).position(|w| w == mark).unwrap() + mark.len();
    let underscore = data_at + bytes[data_at..].iter().position(|&b| b == b'_').unwrap() + 1;
    let data = &bytes[underscore + offset..];
    let count = u64::from_le_bytes(data[..8].try_into().unwrap()) as usize;
    let from_bytes: Vec<f64> = data[8..8 + count]
        .chunks(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(from_text, from_bytes);
    // A format that does not exist is refused by the command line.
    let out = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--vtk", "v", "--vtk-format", "xml"])
        .run();
    assert_eq!(out.code, 2, "{}", out.stderr);
    assert!(out.stderr.contains("--vtk-format"), "{}", out.stderr);
}

/// A history's ParaView files in the compressed formats: the same names and collection as in
/// ascii, each `.vtu` with zlib blocks (`compressed`) or LZ4 blocks (`lz4`) (reference: the
/// ascii run; the values are compared in `crates/output/tests/it/vtk_binary.rs`).
#[test]
fn history_vtk_format_compressed() {
    let file = root().join("examples/deck-bearings-temperature.toml");
    let a = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--vtk", "a"]);
    assert_eq!(a.run().code, 0);
    let z =
        TestCommand::new(&["solve"])
            .arg(&file)
            .args(&["--vtk", "z", "--vtk-format", "compressed"]);
    assert_eq!(z.run().code, 0);
    let pvd_a = std::fs::read_to_string(a.path("a/history.pvd")).unwrap();
    let pvd_z = std::fs::read_to_string(z.path("z/history.pvd")).unwrap();
    assert_eq!(pvd_a, pvd_z);
    let vtu = std::fs::read(z.path("z/history_mesh_001.vtu")).unwrap();
    let s = "compressor=\"vtkZLibDataCompressor\"";
    assert!(vtu.windows(s.len()).any(|w| w == s.as_bytes()));
    let l = TestCommand::new(&["solve"])
        .arg(&file)
        .args(&["--vtk", "l", "--vtk-format", "lz4"]);
    assert_eq!(l.run().code, 0);
    let pvd_l = std::fs::read_to_string(l.path("l/history.pvd")).unwrap();
    assert_eq!(pvd_a, pvd_l);
    let vtu = std::fs::read(l.path("l/history_mesh_001.vtu")).unwrap();
    let s = "compressor=\"vtkLZ4DataCompressor\"";
    assert!(vtu.windows(s.len()).any(|w| w == s.as_bytes()));
}

/// The structure picture of `--report` through the binary. References: the model files —
/// Example 1 has three pairs (`support.1…3`) and no support, a variable nodal load; the sheet
/// pile wall pins its wall's foot, fixes the soil's bottom (plane-element nodes have no rotation:
/// ux and uy, drawn pinned), puts the soil's outer sides on rollers
/// (`ux = true`), loads the soil by its weight (a body force, constant) and pushes the wall's
/// top with `p·F` (a variable nodal force).
#[test]
fn structure_picture_names_pairs_and_draws_supports_and_loads() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/example1-beam.toml"))
        .args(&["--report", "r"]);
    assert_eq!(cmd.run().code, 0);
    let svg = std::fs::read_to_string(cmd.path("r/structure.svg")).unwrap();
    for k in 1..=3 {
        assert!(svg.contains(&format!("support.{k}")), "support.{k}");
    }
    assert!(svg.contains("every pair labelled with its name"));
    assert_eq!(svg.matches("<g class=\"support ").count(), 0);
    assert_eq!(svg.matches("<g class=\"load variable force\">").count(), 1);
    assert_eq!(svg.matches("<g class=\"load constant").count(), 0);

    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/sheet-pile-wall.toml"))
        .args(&["--report", "r"]);
    assert_eq!(cmd.run().code, 0);
    let svg = std::fs::read_to_string(cmd.path("r/structure.svg")).unwrap();
    assert!(svg.matches("<g class=\"support pinned\">").count() > 2);
    assert!(svg.matches("<g class=\"support roller\">").count() > 2);
    assert_eq!(svg.matches("<g class=\"support fixed\">").count(), 0);
    assert_eq!(svg.matches("<g class=\"load variable force\">").count(), 1);
    assert!(svg.contains("body forces on"), "the soil's weight is said");
    let report = std::fs::read_to_string(cmd.path("r/report.html")).unwrap();
    assert!(report.contains("<g class=\"support pinned\">"));
}

// ---- charts15: the working-scheme map, the traced path in the charts, real text in the report ----

/// Example 1 with pair names outside ASCII.
fn zone_with_names(cmd: &TestCommand) -> PathBuf {
    let text = std::fs::read_to_string(example1()).unwrap().replace(
        r#"names = ["1", "2", "3"]"#,
        r#"names = ["Stütze.1", "опора.2", "3"]"#,
    );
    assert!(text.contains("опора.2"));
    let path = cmd.path("names.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// A pair named `Stütze.1` or `опора.2` appears as such in report.html, as real SVG text
/// (searchable, any script), while the standalone pictures keep the stroke font (no `<text>`:
/// they render to PNG with no fonts) with the name in a `<title>`. The working-scheme map is
/// the report's first picture and a file of its own.
#[test]
fn report_has_real_text_and_the_scheme_map_first() {
    let cmd = TestCommand::new(&["solve"]);
    let file = zone_with_names(&cmd);
    let cmd = cmd.arg(&file).args(&["--report", "rep"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let html = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
    for name in ["Stütze.1", "опора.2"] {
        let in_text = html.split("<text ").skip(1).any(|t| {
            let content = &t[t.find('>').unwrap() + 1..t.find("</text>").unwrap()];
            content.starts_with(name)
        });
        assert!(in_text, "{name} as <text> in report.html");
    }
    let map = std::fs::read_to_string(cmd.path("rep/scheme-map.svg")).unwrap();
    assert!(!map.contains("<text"), "stroke font in the file");
    assert!(map.contains("<title>Stütze.1</title>"));
    assert!(map.contains("<title>опора.2</title>"));
    for f in ["load-path-forces.svg", "load-path-displacements.svg"] {
        let svg = std::fs::read_to_string(cmd.path(&format!("rep/{f}"))).unwrap();
        assert!(!svg.contains("<text"), "{f}: stroke font");
    }
    let (scheme, path) = (
        html.find("id=\"scheme\"").expect("map section"),
        html.find("id=\"load-path\"").unwrap(),
    );
    assert!(scheme < path);
    assert!(
        html[..scheme].matches("<svg").count() == 0,
        "the map is the first picture"
    );
    assert!(out.stderr.contains("scheme-map.svg"), "{}", out.stderr);
}

/// The paper's procedure (Example 1's file has c = 1) is labelled as depending on c, with c's
/// value, in the HTML and on the charts and the map; without the tightening nothing is.
#[test]
fn tightened_report_is_labelled_c_dependent() {
    let cmd = TestCommand::new(&["solve"])
        .arg(example1())
        .args(&["--report", "rep"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let html = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
    assert!(html.contains("class=\"c-dependent\""));
    assert!(html.contains("traced with the tightening c = 1"));
    for f in ["scheme-map.svg", "load-path-forces.svg"] {
        let svg = std::fs::read_to_string(cmd.path(&format!("rep/{f}"))).unwrap();
        assert!(svg.contains("tightening c = 1"), "{f}");
    }
    let free = TestCommand::new(&["solve"]).arg(example1()).args(&[
        "--tightening",
        "0",
        "--report",
        "rep",
    ]);
    let out = free.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let html = std::fs::read_to_string(free.path("rep/report.html")).unwrap();
    assert!(!html.contains("c-dependent"));
    assert!(!html.contains("traced with the tightening"));
}

// Issue 14 (progress15): progress on stderr, the tightened path's events labelled as depending
// on c in the tables, units in the history's CSV column names.

/// A run of the binary in `cmd`'s directory with the progress delay set (the test-only knob
/// `UNILATERAL_PROGRESS_AFTER_MS`).
fn run_with_progress_delay(cmd: &TestCommand, after_ms: &str) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_unilateral"))
        .args(&cmd.args)
        .env("UNILATERAL_PROGRESS_AFTER_MS", after_ms)
        .current_dir(cmd.dir.path())
        .output()
        .expect("run unilateral");
    Output {
        code: out.status.code().unwrap_or(-1),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

/// The totals of the last progress line (`unilateral: done in 0.1 s: [stage 8, ]52 steps,
/// 60 pivots, p = 15.6261`): (stage, steps, pivots, load).
fn progress_totals(stderr: &str) -> (Option<u64>, u64, u64, Option<f64>) {
    let line = stderr
        .lines()
        .rev()
        .find(|l| l.starts_with("unilateral: done in "))
        .unwrap_or_else(|| panic!("no final progress line in:\n{stderr}"));
    let (_, totals) = line["unilateral: done in ".len()..]
        .split_once(": ")
        .expect("the totals after the time");
    let (mut stage, mut steps, mut pivots, mut load) = (None, None, None, None);
    for part in totals.split(", ") {
        let num = |s: &str| s.split(' ').next().unwrap().parse::<u64>().unwrap();
        if let Some(v) = part.strip_prefix("stage ") {
            stage = Some(v.parse().unwrap());
        } else if part.ends_with("steps") || part.ends_with("step") {
            steps = Some(num(part));
        } else if part.ends_with("pivots") || part.ends_with("pivot") {
            pivots = Some(num(part));
        } else if let Some(v) = part
            .strip_prefix("p = ")
            .or_else(|| part.strip_prefix("s = "))
        {
            load = Some(v.parse().unwrap());
        } else {
            panic!("unexpected part '{part}' in '{line}'");
        }
    }
    (stage, steps.unwrap(), pivots.unwrap(), load)
}

/// `--progress always` draws on a stderr that is not a terminal: plain lines, ending with the
/// totals. Reference: the result document of the same run — the steps of the path are its
/// `pivots` (every step listed), the pivots at least those plus the pivots that removed the
/// tightening, the load that of the last step (to the six digits shown). The answer is the same
/// as without progress (stdout byte for byte, minus the timings line), and `--progress never`
/// and the default (stderr not a terminal) leave stderr as it was: only the files line.
#[test]
fn progress_always_reports_the_steps_pivots_and_load_of_the_run() {
    let cmd = TestCommand::new(&["solve"]);
    let (file, _) = beam_zone_file(cmd.dir.path(), 60, 11);
    let cmd = cmd
        .arg(&file)
        .args(&["--json", "r.json", "--csv", "out", "--progress", "always"]);
    let out = run_with_progress_delay(&cmd, "0");
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("r.json");
    let steps = j["steps"].as_array().unwrap();
    assert!(
        steps.len() >= 100,
        "a run of some hundred pivots: {}",
        steps.len()
    );
    let (stage, n_steps, pivots, load) = progress_totals(&out.stderr);
    assert_eq!(stage, None);
    assert_eq!(n_steps, j["pivots"].as_u64().unwrap(), "{}", out.stderr);
    assert!(n_steps + j["tightening_pivots"].as_u64().unwrap() <= pivots);
    let last_p = steps.last().unwrap()["p"].as_f64().unwrap();
    let shown = load.expect("the load reached");
    assert!(
        (shown - last_p).abs() <= 1e-5 * last_p.abs(),
        "{shown} vs {last_p}"
    );
    // Every progress line is one of ours; the files line is still there, once.
    for l in out.stderr.lines() {
        assert!(
            l.starts_with("unilateral: ") || l.starts_with("wrote 3 files in out"),
            "{l}"
        );
    }
    let without_timings = |s: &str| -> String {
        s.lines()
            .filter(|l| !l.starts_with("time: "))
            .collect::<Vec<_>>()
            .join("\n")
    };
    for mode in [None, Some("never"), Some("auto")] {
        let mut args: Vec<&str> = vec!["--json", "q.json", "--csv", "out2"];
        if let Some(m) = mode {
            args.extend(["--progress", m]);
        }
        let quiet = TestCommand::new(&["solve"]).arg(&file).args(&args);
        let q = run_with_progress_delay(&quiet, "0");
        assert_eq!(q.code, 0, "{}", q.stderr);
        assert_eq!(
            q.stderr, "wrote 3 files in out2: pairs.csv, steps.csv, path.csv\n",
            "{mode:?}: stderr as before"
        );
        assert_eq!(without_timings(&q.stdout), without_timings(&out.stdout));
        assert_eq!(quiet.json("q.json")["steps"], j["steps"]);
    }
    // With the default delay of a second a run this short shows nothing, even when asked.
    let short = run_with_progress_delay(&cmd, "60000");
    assert!(
        !short.stderr.contains("unilateral:"),
        "nothing before the delay: {}",
        short.stderr
    );
}

/// A load history reports its stages and steps. Reference: the history's document — the stage
/// reached is the last stage, the steps the sum of every stage's steps (and its `pivots`).
#[test]
fn progress_of_a_history_counts_its_stages_and_steps() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/deck-bearings-temperature.toml"))
        .args(&["--json", "h.json", "--progress", "always"]);
    let out = run_with_progress_delay(&cmd, "0");
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("h.json");
    let stages = j["history"].as_array().unwrap();
    let steps: u64 = stages
        .iter()
        .map(|s| s["steps"].as_array().unwrap().len() as u64)
        .sum();
    let (stage, n_steps, pivots, _) = progress_totals(&out.stderr);
    assert_eq!(stage, Some(stages.len() as u64), "{}", out.stderr);
    assert_eq!(n_steps, steps, "{}", out.stderr);
    assert_eq!(pivots, j["pivots"].as_u64().unwrap());
}

/// `unilateral lcp` reports its pivots. Reference: the result document's `pivots`.
#[test]
fn progress_of_a_plain_lcp_counts_its_pivots() {
    let file = siconos("lcp").join("lcp_exp_murty.dat");
    let cmd =
        TestCommand::new(&["lcp"])
            .arg(&file)
            .args(&["--json", "l.json", "--progress", "always"]);
    let out = run_with_progress_delay(&cmd, "0");
    assert_eq!(out.code, 0, "{}", out.stderr);
    let j = cmd.json("l.json");
    let (_, _, pivots, _) = progress_totals(&out.stderr);
    assert_eq!(pivots, j["pivots"].as_u64().unwrap(), "{}", out.stderr);
    assert!(pivots > 0);
}

/// Example 3 is traced with the paper's tightening c = 1000: the summary says its events are
/// the paper's procedure's and depend on c, the JSON says so with c, and `steps.csv` carries c
/// in a last column `tightening_c [N]` on every row (a rectangular table, as pandas reads it).
/// The sheet pile wall (c = 0, physical events) has no such label. Reference: the files'
/// `[solve] tightening` (1000 and 0). Example 3 has no constant load: the structure's own path
/// (one working scheme for every p > 0, that of the reported solution) is said first — in the
/// summary before the status, in the JSON as `physical_path`, in the report's facts.
#[test]
fn tightened_events_are_labelled_as_depending_on_c() {
    let run = |name: &str| {
        let cmd = TestCommand::new(&["solve"])
            .arg(root().join("examples").join(name))
            .args(&["--json", "r.json", "--csv", "csv", "--report", "rep"]);
        let out = cmd.run();
        assert_eq!(out.code, 0, "{}", out.stderr);
        let steps = std::fs::read_to_string(cmd.path("csv/steps.csv")).unwrap();
        let report = std::fs::read_to_string(cmd.path("rep/report.html")).unwrap();
        (out.stdout, cmd.json("r.json"), steps, report)
    };
    let (summary, j, steps, report) = run("example3-sheet-pile.toml");
    let physical = "no constant load: the solution at p = 1 below, every force and \
                    displacement scaled by p, is a solution at every p > 0";
    let first = summary
        .lines()
        .position(|l| l.starts_with("physical path: "))
        .expect("the physical path said");
    let status = summary
        .lines()
        .position(|l| l.starts_with("status: "))
        .unwrap();
    assert!(first < status, "{summary}");
    assert!(
        summary.lines().nth(first).unwrap().contains(physical),
        "{summary}"
    );
    assert!(
        j["physical_path"].as_str().unwrap().contains(physical),
        "{}",
        j["physical_path"]
    );
    assert!(report.contains("<dt>Physical path</dt><dd>no constant load"));
    assert!(
        summary.contains(
            "these are the events of the paper's procedure: their loads depend on c (the \
             solution at p = 1 is free of c)"
        ),
        "{summary}"
    );
    assert_eq!(j["events_depend_on_tightening"], true);
    assert_eq!(j["tightening"], 1000.0);
    let mut lines = steps.lines();
    let head = lines.next().unwrap();
    assert!(head.ends_with(",beyond_target,tightening_c [N]"), "{head}");
    let columns = head.split(',').count();
    let mut rows = 0;
    for l in lines {
        // Fields are quoted only when they hold a comma: count outside quotes.
        let mut quoted = false;
        let fields = 1 + l
            .chars()
            .filter(|&c| {
                if c == '"' {
                    quoted = !quoted;
                }
                c == ',' && !quoted
            })
            .count();
        assert_eq!(fields, columns, "{l}");
        assert_eq!(
            l.rsplit(',').next().unwrap().parse::<f64>().unwrap(),
            1000.0
        );
        rows += 1;
    }
    assert_eq!(rows, j["steps"].as_array().unwrap().len());

    let (summary, j, steps, report) = run("sheet-pile-wall.toml");
    assert!(!summary.contains("depend on c"), "{summary}");
    assert!(!summary.contains("physical path"), "{summary}");
    assert!(!report.contains("Physical path"));
    assert_eq!(j["physical_path"], serde_json::Value::Null);
    assert_eq!(j["events_depend_on_tightening"], false);
    assert!(!steps.lines().next().unwrap().contains("tightening"));
}

/// The history's CSV tables name their columns with the file's units, as the paper's path
/// does. Reference: the deck's `units = "N, m, K"` (forces in N, lengths in m).
#[test]
fn history_csv_columns_carry_the_units() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/deck-bearings-temperature.toml"))
        .args(&["--csv", "csv"]);
    let out = cmd.run();
    assert_eq!(out.code, 0, "{}", out.stderr);
    let head = |name: &str| {
        std::fs::read_to_string(cmd.path(&format!("csv/{name}")))
            .unwrap()
            .lines()
            .next()
            .unwrap()
            .to_string()
    };
    let values = "pair,name,x_n [N],x_t [N],z_n [m],z_t [m],state";
    assert!(head("history_breakpoints.csv").ends_with(values));
    assert_eq!(head("history_stage_01.csv"), values);
    assert!(head("history_events.csv").ends_with("direction,slip_kept [m],description"));
}

// ---- the file's units in the pictures (issue 14: "units … in the pictures") ----

/// The sheet pile wall says `units = "N, m"`: the structure picture's header gives the largest
/// displacement in m and the longest contact arrow in N, the stress bar N/(m·m), and the
/// charts' quantities `x_n [N]`, `z_n [m]`; the test data's Example 1 zone gives no units,
/// and no picture names one. Reference: the files' `units` keys.
#[test]
fn pictures_carry_the_files_units() {
    let cmd = TestCommand::new(&["solve"])
        .arg(root().join("examples/sheet-pile-wall.toml"))
        .args(&["--report", "r"]);
    assert_eq!(cmd.run().code, 0);
    let svg = std::fs::read_to_string(cmd.path("r/structure.svg")).unwrap();
    let header = svg
        .lines()
        .find(|l| l.contains("largest displacement"))
        .expect("the header line");
    assert!(
        header.contains(" m).") && header.contains(" N."),
        "{header}"
    );
    assert!(svg.contains("[N/(m·m)]"));
    assert!(svg.contains("longest load arrow") && svg.contains(" N;"));
    let forces = std::fs::read_to_string(cmd.path("r/load-path-forces.svg")).unwrap();
    assert!(forces.contains("x_n [N]") && forces.contains("x_t [N]"));
    let disp = std::fs::read_to_string(cmd.path("r/load-path-displacements.svg")).unwrap();
    assert!(disp.contains("z_n [m]") && disp.contains("z_t [m]"));

    let plain = TestCommand::new(&["solve"])
        .arg(root().join("tests/data/good/example1.json"))
        .args(&["--report", "r"]);
    assert_eq!(plain.run().code, 0);
    let forces = std::fs::read_to_string(plain.path("r/load-path-forces.svg")).unwrap();
    assert!(forces.contains("x_n (normal force") && !forces.contains("x_n ["));
}

/// The tables and the report are written over an earlier run's files in place: a second run
/// into a directory whose `path.csv` is longer than the new one, whose `pairs.csv` is a
/// symbolic link and whose `report.html` is read-only gives, byte for byte, the files of a run
/// into an empty directory, and the file the link named keeps its bytes.
#[cfg(unix)]
#[test]
fn tables_and_report_are_written_over_an_earlier_runs_files() {
    let cmd = TestCommand::new(&["solve"]);
    let (file, _) = beam_zone_file(cmd.dir.path(), 4, 3);
    let run = |csv: &str, rep: &str| {
        let out = Command::new(env!("CARGO_BIN_EXE_unilateral"))
            .arg("solve")
            .arg(&file)
            .args(["--csv", csv, "--report", rep])
            .current_dir(cmd.dir.path())
            .output()
            .expect("run unilateral");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    };
    run("fresh_csv", "fresh_rep");
    std::fs::create_dir_all(cmd.path("csv")).unwrap();
    std::fs::create_dir_all(cmd.path("rep")).unwrap();
    std::fs::write(cmd.path("csv/path.csv"), vec![b'x'; 1 << 20]).unwrap();
    let other = cmd.path("other.txt");
    std::fs::write(&other, b"not a table").unwrap();
    std::os::unix::fs::symlink(&other, cmd.path("csv/pairs.csv")).unwrap();
    std::fs::write(cmd.path("rep/report.html"), b"old").unwrap();
    let mut ro = std::fs::metadata(cmd.path("rep/report.html"))
        .unwrap()
        .permissions();
    ro.set_readonly(true);
    std::fs::set_permissions(cmd.path("rep/report.html"), ro).unwrap();
    run("csv", "rep");
    for (a, b) in [("fresh_csv", "csv"), ("fresh_rep", "rep")] {
        let names_in = |d: &str| {
            let mut names: Vec<_> = std::fs::read_dir(cmd.path(d))
                .unwrap()
                .map(|e| e.unwrap().file_name())
                .collect();
            names.sort();
            names
        };
        let names = names_in(a);
        assert!(names.len() >= 3, "{names:?}");
        // the same files, and no `.part` file left beside them
        assert_eq!(names_in(b), names);
        for n in names {
            let (fa, fb) = (cmd.path(a).join(&n), cmd.path(b).join(&n));
            assert!(
                std::fs::read(&fa).unwrap() == std::fs::read(&fb).unwrap(),
                "{} differs",
                fb.display()
            );
        }
    }
    assert_eq!(std::fs::read(&other).unwrap(), b"not a table");
}
