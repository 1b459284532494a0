//! Whole-process timings: what a user waits for, reading and writing included.
//!
//! For each size `m` (pairs; the LCP has `n = 3m` unknowns) the benchmark writes the files a user
//! would give, runs the release `unilateral` binary on them, and measures wall time, CPU time
//! (user + system) and peak memory (maximum resident set) of each process with `/usr/bin/time`.
//! The yardstick is one dense LU of order `n` (faer, `partial_piv_lu`, best of three) in this
//! process, in the same run, so that the ratios do not depend on how busy the machine is.
//!
//! Cases:
//! * `lcp`: the beam's `3m` LCP at `p = 1` as a Siconos `.dat` file, `unilateral lcp`;
//! * `zone`: the beam's contact zone with `Rnn`, `Rtt` in Matrix Market files, `unilateral solve
//!   --trace end --tightening 1` (the paper's procedure);
//! * `zone+out`: the same with `--csv` and `--report` as well (sizes up to
//!   `UNILATERAL_BENCH_REPORT_MAX`, default 300);
//! * `model`: a structural model, a continuous deck on `m` frictional elastic bearings (an
//!   elastomer layer meshed with QM6 under a frame member, the bearings' bases on the ground),
//!   condensed and traced to the end in the process (an early mechanism at m = 2000: a short
//!   path);
//! * `beam`: a structural model, a continuous frame beam (spans 1 m) on `m` frictional elastic
//!   bearings, each a vertical and a horizontal spring under a sole plate with a frictional
//!   contact pair to the beam; dead weight, a variable load from down to up along the beam and a
//!   sideways load (bearings lift and slide in turn: the long path), `solve --trace end`;
//! * `beam+out`: the same with `--csv` and `--report`, `beam+vtk` with `--vtk` (its default
//!   format, ascii), `beam+vtkb`, `beam+vtkz` and `beam+vtkl` with `--vtk-format binary`,
//!   `compressed` (zlib) and `lz4`, for
//!   sizes up to `UNILATERAL_BENCH_REPORT_MAX` (the path without tightening: its tables and
//!   charts read the path's breakpoints; every ParaView frame is a recovered structure), and
//!   `beam+bp` with `--json-breakpoints` (every pair at every breakpoint in the JSON, formed and
//!   written a block at a time). Each `--vtk` case is run twice: into a new directory (new
//!   files), then again into the same one (`…/w`: the files written over in place, a user's
//!   second run).
//!
//! `UNILATERAL_BENCH_CASES=beam` (a comma-separated list of the case names) runs only those.
//! `UNILATERAL_BENCH_KEEP=DIR` writes the input files into `DIR/m{m}/` and keeps them (to
//! profile one run by hand); otherwise they go to a temporary folder removed after each size.
//!
//! Every case writes `--json`; the column `solve s` is its `timings.solve`, the solve alone. A
//! case whose run takes less than a second is run seven times into the same directory (each
//! run after the first writing over the files of the one before) and the run of median wall
//! time is shown (its CPU, solve and peak memory with it). Each run starts after a `sync` (the
//! dirty pages of the runs before written out), so that it is not charged for another run's
//! writeback.
//!
//! The contact zone is `unilateral_oracle::fixtures::beam::beam_on_supports(m, 7)` (a continuous
//! beam on `m` frictional supports).
//!
//! ```sh
//! cargo bench -p unilateral --bench whole_process                       # m = 100, 300, 1000, 2000
//! UNILATERAL_BENCH_SIZES=100,300 cargo bench -p unilateral --bench whole_process
//! UNILATERAL_BENCH_CASES=beam cargo bench -p unilateral --bench whole_process
//! ```

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use faer::Mat;
use unilateral_contact::{ContactLcp, ContactZone};
use unilateral_oracle::fixtures::beam;
use unilateral_oracle::fixtures::bearings::beam_model;

const BIN: &str = env!("CARGO_BIN_EXE_unilateral");

fn sizes() -> Vec<usize> {
    std::env::var("UNILATERAL_BENCH_SIZES")
        .ok()
        .map(|s| s.split(',').filter_map(|w| w.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![100, 300, 1000, 2000])
}

/// Whether the case `name` is selected by `UNILATERAL_BENCH_CASES` (all when unset).
fn selected(name: &str) -> bool {
    std::env::var("UNILATERAL_BENCH_CASES")
        .map(|s| s.split(',').any(|w| w.trim() == name))
        .unwrap_or(true)
}

fn report_max() -> usize {
    std::env::var("UNILATERAL_BENCH_REPORT_MAX")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(300)
}

fn zone(m: usize) -> ContactZone {
    let b = beam::beam_on_supports(m, 7);
    let mat = |rows: &[Vec<f64>]| Mat::from_fn(m, m, |i, j| rows[i][j]);
    let mut z = ContactZone::new(mat(&b.rnn), mat(&b.rtt));
    z.friction = b.friction;
    z.constant.normal = b.constant_normal;
    z.variable.normal = b.variable_normal;
    z.variable.tangential = b.variable_tangential;
    z
}

fn list(v: &[f64]) -> String {
    let words: Vec<String> = v.iter().map(|x| format!("{x:e}")).collect();
    format!("[{}]", words.join(", "))
}

/// A dense matrix as a Matrix Market array file (column by column).
fn write_mtx(path: &Path, a: &Mat<f64>) {
    let mut s = format!(
        "%%MatrixMarket matrix array real general\n{} {}\n",
        a.nrows(),
        a.ncols()
    );
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            writeln!(s, "{:e}", a[(i, j)]).unwrap();
        }
    }
    std::fs::write(path, s).unwrap();
}

fn write_zone(dir: &Path, z: &ContactZone) -> PathBuf {
    write_mtx(&dir.join("rnn.mtx"), &z.rnn);
    write_mtx(&dir.join("rtt.mtx"), &z.rtt);
    let path = dir.join("zone.toml");
    let s = format!(
        "[contact_zone]\nfriction = {}\nRnn = \"rnn.mtx\"\nRtt = \"rtt.mtx\"\n\n[load.constant]\nnormal = {}\n\n[load.variable]\nnormal = {}\ntangential = {}\n",
        list(&z.friction),
        list(&z.constant.normal),
        list(&z.variable.normal),
        list(&z.variable.tangential)
    );
    std::fs::write(&path, s).unwrap();
    path
}

/// The zone's `3m` LCP at `p = 1` in Siconos `.dat` form (`M` column by column, then `q`).
fn write_dat(dir: &Path, z: &ContactZone) -> PathBuf {
    let lcp = ContactLcp::build(z);
    let p = &lcp.problem;
    let n = p.q0.len();
    let mut s = format!("{n}\n0\n{n}\n{n}\n{n} {n}\n");
    for j in 0..n {
        for i in 0..n {
            write!(s, "{:e} ", p.m[(i, j)]).unwrap();
        }
        s.push('\n');
    }
    for i in 0..n {
        write!(s, "{:e} ", p.q0[i] + p.d[i]).unwrap();
    }
    s.push('\n');
    let path = dir.join("lcp.dat");
    std::fs::write(&path, s).unwrap();
    path
}

/// The structural model: a frame deck (spans 1 m) on an elastomer layer 0.2 m thick meshed
/// with `m − 1` QM6 elements, whose `m` base nodes are frictional contact pairs with the ground;
/// dead load on the deck, a variable load varying along it from down to up and a horizontal
/// push at its end.
fn write_model(dir: &Path, m: usize) -> PathBuf {
    let l = m - 1;
    let s = format!(
        r#"title = "Continuous deck on {m} frictional elastic bearings (benchmark)"
units = "N, m"

[[sections]]
name = "deck"
E = 3.0e10
A = 0.5
I = 0.04

[[materials]]
name = "elastomer"
E = 2.0e7
nu = 0.45
thickness = 0.5

[[members]]
name = "deck"
start = [0.0, 0.2]
end = [{l}.0, 0.2]
divisions = {l}
section = "deck"

[[blocks]]
name = "pads"
origin = [0.0, 0.0]
width = {l}.0
height = 0.2
nx = {l}
ny = 1
material = "elastomer"
analysis = "plane_stress"
formulation = "QM6"
connect_to = "deck"

[[contact]]
name = "bearing"
from = "ground"
to = "pads.bottom"
normal = [0.0, 1.0]
friction = 0.3

[[loads.constant.distributed]]
elements = "deck"
q = [0.0, -1.0e4]

[[loads.variable.distributed]]
elements = "deck"
start = [2.0e3, -3.0e4]
end = [-1.0e3, 0.8e4]

[[loads.variable.nodal]]
nodes = "deck.end"
fx = 5.0e4

[solve]
target = 1.0
trace = "end"
"#
    );
    let path = dir.join(format!("deck{m}.toml"));
    std::fs::write(&path, s).unwrap();
    path
}

/// The structural model of the long path: a continuous beam (frame member, spans 1 m,
/// EI = 1.2e9 N·m²) on `m` frictional elastic bearings. Each bearing is a sole plate (a node of
/// the member `soles`, at the beam's node) on a vertical spring of 1e9 N/m and a horizontal one
/// of 2e6 N/m to the ground, with a contact pair (friction 0.3) from the sole into the beam:
/// the spring in series with the unilateral frictional contact. The model format makes nodes
/// only with elements, so the soles are joined by a light tie of bars (EA = 2e4 N, 1 % of a
/// bearing's horizontal stiffness per metre) that makes the file a few lines for any `m`.
/// Dead weight 10 kN/m; the variable load goes from 40 kN/m down at the left end to 10 kN/m up
/// at the right end, with 1 kN/m sideways: as `p` grows the bearings lift one after another
/// from the right and slide in turn, until the working scheme no longer changes (a ray).
fn write_beam(dir: &Path, m: usize) -> PathBuf {
    let s = beam_model(m);
    let path = dir.join(format!("beam{m}.toml"));
    std::fs::write(&path, s).unwrap();
    path
}

struct Run {
    wall: f64,
    cpu: f64,
    peak_mib: f64,
    status: String,
    /// The solve alone, from the JSON's `timings.solve` (when a JSON was written to `out.json`).
    solve: Option<f64>,
    /// The steps of the load path, from the JSON (when written).
    steps: Option<usize>,
    /// The size of `out.json` (0 when none was written).
    json_bytes: u64,
}

/// Runs the binary under `/usr/bin/time` and reads its figures.
/// A run of the binary: once when it takes a second or more, else the median (by wall time)
/// of [`SHORT_RUNS`] runs, so that a run of milliseconds is not one sample of the machine's
/// noise. The runs write into the same directory: from the second on (and from the first
/// when `UNILATERAL_BENCH_KEEP` keeps an earlier benchmark's files) a run's files are written
/// over an earlier run's, as when a user runs a model again.
fn run(args: &[&str], dir: &Path) -> Run {
    let first = run_once(args, dir);
    if first.wall >= 1.0 {
        return first;
    }
    let mut runs = vec![first];
    runs.extend((1..SHORT_RUNS).map(|_| run_once(args, dir)));
    runs.sort_by(|a, b| a.wall.total_cmp(&b.wall));
    runs.swap_remove(SHORT_RUNS / 2)
}

/// Runs of a case under a second ([`run`]).
const SHORT_RUNS: usize = 7;

fn run_once(args: &[&str], dir: &Path) -> Run {
    let times = dir.join("time.txt");
    // The files of the runs before (gigabytes of ParaView frames) are put on the disk first,
    // so that a run is not charged for the page cache's writeback of another's.
    let _ = Command::new("sync").status();
    let t = Instant::now();
    let out = Command::new("/usr/bin/time")
        .arg("-f")
        .arg("%U %S %M")
        .arg("-o")
        .arg(&times)
        .arg(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("/usr/bin/time runs the binary");
    let wall = t.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let status = stdout
        .lines()
        .find_map(|l| l.strip_prefix("status: "))
        .map(|s| s.split(' ').next().unwrap_or("").to_string())
        .unwrap_or_else(|| format!("exit {:?}", out.status.code()));
    let t = std::fs::read_to_string(&times).unwrap_or_default();
    let w: Vec<f64> = t
        .lines()
        .last()
        .unwrap_or("")
        .split_whitespace()
        .filter_map(|v| v.parse().ok())
        .collect();
    let (cpu, peak) = match w.as_slice() {
        [u, s, k] => (u + s, k / 1024.0),
        _ => (f64::NAN, f64::NAN),
    };
    let json = dir.join("out.json");
    let json_bytes = std::fs::metadata(&json).map_or(0, |m| m.len());
    let doc = std::fs::read_to_string(&json)
        .ok()
        .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok());
    let solve = doc.as_ref().and_then(|v| v["timings"]["solve"].as_f64());
    let steps = doc
        .as_ref()
        .and_then(|v| v["steps"].as_array().map(|a| a.len()));
    let _ = std::fs::remove_file(&json);
    Run {
        wall,
        cpu,
        peak_mib: peak,
        status,
        solve,
        steps,
        json_bytes,
    }
}

/// One dense LU of order `n`, best of three (seconds).
fn lu_seconds(n: usize) -> f64 {
    let a = Mat::<f64>::from_fn(n, n, |i, j| {
        let k = (i * 7919 + j * 104_729) % 1_000_003;
        k as f64 / 1_000_003.0 + if i == j { n as f64 } else { 0.0 }
    });
    (0..3)
        .map(|_| {
            let t = Instant::now();
            let lu = a.partial_piv_lu();
            std::hint::black_box(lu.U()[(0, 0)]);
            t.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

fn main() {
    // The yardstick is one dense LU on one thread (issue 11). This process runs nothing else
    // of faer; the program it starts uses faer's parallelism in its refactorisations.
    faer::set_global_parallelism(faer::Par::Seq);
    // `cargo bench` passes `--bench`; a filter argument other than that selects nothing here.
    if std::env::args().skip(1).any(|a| a != "--bench") {
        return;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "whole-process runs of {BIN}\ncores: {cores}; load average before: {}",
        load_average()
    );
    println!(
        "{:>5} {:>5} {:>9} {:>14} {:>6} {:>9} {:>9} {:>9} {:>9} {:>8} {:>10} {:>9}",
        "m",
        "n",
        "case",
        "status",
        "steps",
        "wall s",
        "CPU s",
        "solve s",
        "LU s",
        "wall/LU",
        "peak MiB",
        "peak/n²"
    );
    // Every size's directory is removed at the end, not when the next size starts: on a file
    // system without a journal (this machine's), ext4 passes over the inodes freed in the last
    // minutes when it makes a file, and a size's frames made just after the thousands of files
    // of the size before were removed cost the kernel seconds more (`docs/performance.md`,
    // round 43).
    let mut dirs = Vec::new();
    for m in sizes() {
        let dir = tempfile::tempdir().unwrap();
        let kept = std::env::var("UNILATERAL_BENCH_KEEP")
            .ok()
            .map(|k| Path::new(&k).join(format!("m{m}")));
        if let Some(k) = &kept {
            std::fs::create_dir_all(k).unwrap();
        }
        let d = kept.as_deref().unwrap_or(dir.path());
        let n = 3 * m;
        let lu = lu_seconds(n);
        let z = zone(m);
        let dat = write_dat(d, &z);
        let zone_file = write_zone(d, &z);
        let model = write_model(d, m);
        let beam = write_beam(d, m);
        let row = |case: &str, r: &Run| {
            let solve = r.solve.map_or("-".to_string(), |s| format!("{s:.3}"));
            let steps = r.steps.map_or("-".to_string(), |s| s.to_string());
            // peak memory in doubles per n² (the issue's goal: ≤ 3)
            let per_n2 = r.peak_mib * 1024.0 * 1024.0 / 8.0 / (n * n) as f64;
            println!(
                "{m:>5} {n:>5} {case:>9} {:>14} {steps:>6} {:>9.3} {:>9.2} {solve:>9} {lu:>9.3} {:>8.1} {:>10.0} {per_n2:>9.2}",
                r.status,
                r.wall,
                r.cpu,
                r.wall / lu,
                r.peak_mib
            );
        };
        let dat_s = dat.to_string_lossy().into_owned();
        let zone_s = zone_file.to_string_lossy().into_owned();
        let model_s = model.to_string_lossy().into_owned();
        let beam_s = beam.to_string_lossy().into_owned();
        if selected("lcp") {
            row("lcp", &run(&["lcp", &dat_s, "--json", "out.json"], d));
        }
        let zone_args = [
            "solve",
            &zone_s,
            "--trace",
            "end",
            "--tightening",
            "1",
            "--json",
            "out.json",
        ];
        if selected("zone") {
            row("zone", &run(&zone_args, d));
        }
        if m <= report_max() && selected("zone+out") {
            let mut a = zone_args.to_vec();
            a.extend(["--csv", "csv", "--report", "rep"]);
            row("zone+out", &run(&a, d));
            let html = std::fs::metadata(d.join("rep").join("report.html")).map_or(0, |m| m.len());
            println!("{:>5} report.html: {:.1} MB", m, html as f64 / 1e6);
        }
        if selected("model") {
            row("model", &run(&["solve", &model_s, "--json", "out.json"], d));
        }
        if selected("beam") {
            let args = ["solve", &beam_s, "--trace", "end", "--json", "out.json"];
            row("beam", &run(&args, d));
        }
        let beam_args = ["solve", &beam_s, "--trace", "end", "--json", "out.json"];
        if m <= report_max() && selected("beam+out") {
            let mut a = beam_args.to_vec();
            a.extend(["--csv", "bcsv", "--report", "brep"]);
            row("beam+out", &run(&a, d));
        }
        // `--vtk` in each of its formats: the default (ascii), binary, compressed (zlib) and lz4.
        for (case, dir, format) in [
            ("beam+vtk", "avtk", None),
            ("beam+vtkb", "bvtk", Some("binary")),
            ("beam+vtkz", "zvtk", Some("compressed")),
            ("beam+vtkl", "lvtk", Some("lz4")),
        ] {
            if m > report_max() || !selected(case) {
                continue;
            }
            let mut a = beam_args.to_vec();
            a.extend(["--vtk", dir]);
            if let Some(f) = format {
                a.extend(["--vtk-format", f]);
            }
            row(case, &run(&a, d));
            let (files, bytes) = std::fs::read_dir(d.join(dir)).map_or((0, 0), |r| {
                r.flatten().fold((0, 0u64), |(n, b), e| {
                    (n + 1, b + e.metadata().map_or(0, |m| m.len()))
                })
            });
            println!("{m:>5} {case}: {files} files, {:.0} MB", bytes as f64 / 1e6);
            // The same run again into the directory the first wrote: its files are written
            // over in place (a user's second run). The first run's files are new, and on this
            // virtual machine the first touch of the page cache's fresh pages costs the kernel
            // more than writing the bytes (`docs/performance.md`, rounds 39 and 43).
            row(&format!("{case}/w"), &run(&a, d));
        }
        if m <= report_max() && selected("beam+bp") {
            let mut a = beam_args.to_vec();
            a.push("--json-breakpoints");
            let r = run(&a, d);
            row("beam+bp", &r);
            println!(
                "{m:>5} beam+bp: out.json {:.0} MB",
                r.json_bytes as f64 / 1e6
            );
        }
        dirs.push(dir);
    }
    println!("load average after: {}", load_average());
    drop(dirs);
}
