//! A quick, deterministic fuzz run inside the normal tests: every good fixture of
//! `tests/data/good/` and every bundled example of `examples/` is mutated in fixed ways (byte
//! flips, truncations, duplicated and deleted lines, huge, tiny, NaN and infinite numbers,
//! deep nesting, very long names and strings) and each mutant is read, from a file, through
//! the public entry points, as the program reads a user's file.
//!
//! The reference is the readers' contract, not a value: no input makes a reader panic or
//! hang; every refusal names the file it refuses (its `Display` starts with the path); and
//! when a contact zone, a plain LCP or a small structural model is read and solved, the
//! writers (JSON, summary, CSV, VTK) find no non-finite number to refuse (`NonFiniteOutput`
//! is an internal failure: it must never happen).
//!
//! The longer, coverage-guided search is `fuzz/` (cargo-fuzz); the inputs it found that once
//! broke a reader are kept in `tests/data/fuzz/` and read here as well.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

use unilateral_io::{
    read_contact_zone, read_fc2d, read_gmsh, read_lcp, read_matrix_market, read_problem,
    read_siconos_lcp, InputError, Problem,
};
use unilateral_output::{
    contact_json, contact_summary, lcp_json, lcp_summary, structural_json, structural_summary,
    write_contact_csv, write_structural_csv, write_vtk_for,
};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Which reader a file goes to.
#[derive(Clone, Copy, Debug)]
enum Reader {
    /// `read_problem` (structural model or contact zone), `.toml` / `.json`.
    Problem,
    /// `read_contact_zone`.
    Zone,
    /// `read_lcp`, `.toml` / `.json` / `.dat`.
    Lcp,
    /// `read_fc2d`, `.dat`.
    Fc2d,
    /// `read_matrix_market`.
    Mtx,
    /// `read_gmsh`.
    Gmsh,
}

/// A seed: a file name (its extension chooses the format), its bytes and its reader.
struct Seed {
    name: String,
    bytes: Vec<u8>,
    reader: Reader,
}

/// A small dense LCP and a 2D frictional-contact problem in Siconos `.dat` form, written by
/// hand from the format description (there is no good `.dat` in `tests/data/good/`).
const LCP_DAT: &str = "2\n0\n2\n2\n2 2\n2 1\n1 2\n-5 -6\n";
const FC2D_DAT: &str = "2\n1\n0\n2\n2\n2 2\n1 0\n0 1\n-1 0.5\n0.3\n";

fn seeds() -> Vec<Seed> {
    let mut out = Vec::new();
    let mut add = |path: PathBuf, reader: Reader| {
        let bytes = std::fs::read(&path)
            .unwrap_or_else(|e| panic!("the fixture {} is missing: {e}", path.display()));
        out.push(Seed {
            name: path.file_name().unwrap().to_string_lossy().into_owned(),
            bytes,
            reader,
        });
    };
    let good = repo().join("tests/data/good");
    for name in ["example1.toml", "example1.json", "all_keys.toml"] {
        add(good.join(name), Reader::Zone);
    }
    for name in ["lcp_small.toml", "lcp_small.json"] {
        add(good.join(name), Reader::Lcp);
    }
    for name in ["example1_rnn.mtx", "example1_rtt.mtx"] {
        add(good.join(name), Reader::Mtx);
    }
    for name in ["disc_on_plate_41.msh", "disc_on_plate_22.msh"] {
        add(repo().join("tests/data/gmsh").join(name), Reader::Gmsh);
    }
    for name in [
        "example1-beam.toml",
        "example1-contact-zone.toml",
        "example2-cantilever.toml",
        "example3-sheet-pile.toml",
    ] {
        add(repo().join("examples").join(name), Reader::Problem);
    }
    out.push(Seed {
        name: "lcp.dat".into(),
        bytes: LCP_DAT.into(),
        reader: Reader::Lcp,
    });
    out.push(Seed {
        name: "fc2d.dat".into(),
        bytes: FC2D_DAT.into(),
        reader: Reader::Fc2d,
    });
    out
}

/// xorshift64*: a fixed sequence, the same on every machine and every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next() % n as u64) as usize
        }
    }
}

/// Numbers that break naive readers and solvers.
const NUMBERS: &[&str] = &[
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e-308",
    "4.9e-324",
    "-0.0",
    "0",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "Infinity",
    "1e999",
    "99999999999999999999999",
    "-9223372036854775809",
    "1e20",
    "1e-20",
];

/// Byte ranges of the numbers written in a text (a digit, with signs, dots and exponents).
fn number_spans(b: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_digit() && (i == 0 || !b[i - 1].is_ascii_alphanumeric());
        if starts {
            let s = if i > 0 && b[i - 1] == b'-' { i - 1 } else { i };
            let mut e = i;
            while e < b.len() && (b[e].is_ascii_digit() || matches!(b[e], b'.' | b'e' | b'E')) {
                e += 1;
            }
            spans.push((s, e));
            i = e;
        } else {
            i += 1;
        }
    }
    spans
}

fn lines(b: &[u8]) -> Vec<&[u8]> {
    b.split_inclusive(|&c| c == b'\n').collect()
}

/// The mutants of one seed: each is (what was done, bytes).
fn mutants(seed: &Seed, rng: &mut Rng) -> Vec<(String, Vec<u8>)> {
    let b = &seed.bytes;
    let mut out: Vec<(String, Vec<u8>)> = Vec::new();
    // Byte flips: one to three random bytes set to random values.
    for k in 0..12 {
        let mut m = b.clone();
        for _ in 0..=(k % 3) {
            let at = rng.below(m.len());
            m[at] = rng.next() as u8;
        }
        out.push((format!("byte flips #{k}"), m));
    }
    // Truncations, at random places and at every tenth of the file.
    for k in 1..10 {
        out.push((format!("cut at {k}/10"), b[..b.len() * k / 10].to_vec()));
    }
    for k in 0..4 {
        let at = rng.below(b.len());
        out.push((format!("cut at byte {at} (#{k})"), b[..at].to_vec()));
    }
    // Duplicated and deleted lines.
    let ls = lines(b);
    for k in 0..6 {
        let i = rng.below(ls.len());
        let mut dup: Vec<u8> = Vec::new();
        let mut del: Vec<u8> = Vec::new();
        for (j, l) in ls.iter().enumerate() {
            dup.extend_from_slice(l);
            if j == i {
                dup.extend_from_slice(l);
            } else {
                del.extend_from_slice(l);
            }
        }
        out.push((format!("line {} doubled (#{k})", i + 1), dup));
        out.push((format!("line {} deleted (#{k})", i + 1), del));
    }
    // Every written number, in turn, replaced by a hostile one.
    for (k, (s, e)) in number_spans(b).into_iter().enumerate() {
        let word = NUMBERS[k % NUMBERS.len()];
        let mut m = b[..s].to_vec();
        m.extend_from_slice(word.as_bytes());
        m.extend_from_slice(&b[e..]);
        out.push((format!("number at byte {s} → {word}"), m));
    }
    // Deep nesting, at random places.
    for (k, open) in ["[", "{", "[[", "{\"a\": "].iter().enumerate() {
        let at = rng.below(b.len());
        let mut m = b[..at].to_vec();
        m.extend_from_slice(open.repeat(5_000).as_bytes());
        m.extend_from_slice(&b[at..]);
        out.push((format!("deep nesting `{open}` at byte {at} (#{k})"), m));
    }
    // Very long names and strings: a long key at the start of a random line, and every
    // quoted string in turn made very long.
    let long = "q".repeat(200_000);
    for k in 0..3 {
        let line = rng.below(ls.len());
        let mut m: Vec<u8> = Vec::new();
        for (j, l) in ls.iter().enumerate() {
            if j == line {
                m.extend_from_slice(long.as_bytes());
                m.extend_from_slice(b" = 1\n");
            }
            m.extend_from_slice(l);
        }
        out.push((format!("long key before line {} (#{k})", line + 1), m));
    }
    let quotes: Vec<usize> = b
        .iter()
        .enumerate()
        .filter(|&(_, &c)| c == b'"')
        .map(|(i, _)| i)
        .collect();
    for pair in quotes.chunks(2).take(8) {
        if let [s, _] = pair {
            let mut m = b[..=*s].to_vec();
            m.extend_from_slice(long.as_bytes());
            m.extend_from_slice(&b[s + 1..]);
            out.push((format!("long string at byte {s}"), m));
        }
    }
    // A long array of numbers on one line where the first number was.
    if let Some(&(s, e)) = number_spans(b).first() {
        let many = vec!["0.5"; 200_000].join(", ");
        let mut m = b[..s].to_vec();
        m.extend_from_slice(format!("[{many}]").as_bytes());
        m.extend_from_slice(&b[e..]);
        out.push(("200 000 numbers for the first number".into(), m));
    }
    out
}

/// A broken contract: of a reader (a panic, an error that does not name the file), or of the
/// solve-and-write chain (a writer met a non-finite number).
enum Broken {
    Reader(String),
    Output(String),
}

/// Reads one input; for a contact zone or an LCP that is read, solves it and runs the writers.
fn check_one(reader: Reader, path: &Path, out_dir: &Path) -> Result<(), Broken> {
    let refused = |e: InputError| -> Result<(), Broken> {
        let shown = e.to_string();
        if e.file() != path || !shown.starts_with(&path.display().to_string()) {
            return Err(Broken::Reader(format!(
                "the error does not name the file: {shown}"
            )));
        }
        Ok(())
    };
    let out = |e: &dyn std::fmt::Display| Broken::Output(e.to_string());
    let zone = |pb: unilateral_io::ContactZoneProblem| -> Result<(), Broken> {
        let mut settings = pb.settings.clone();
        settings.engine.max_pivots = Some(settings.engine.max_pivots.unwrap_or(500).min(500));
        // An error of the solver is the engine's answer to the data, not a reader's concern.
        if let Ok(sol) = unilateral_contact::solve(&pb.zone, &settings) {
            contact_json(&sol).map_err(|e| out(&e))?;
            contact_summary(&sol, "t").map_err(|e| out(&e))?;
            write_contact_csv(&sol, out_dir).map_err(|e| out(&e))?;
        }
        Ok(())
    };
    match reader {
        Reader::Problem => match read_problem(path) {
            Ok(Problem::ContactZone(pb)) => zone(pb),
            Ok(Problem::Structural(pb)) => {
                // Small models only (examples 1 and 2; example 3, with some 350 nodes and 39
                // events, is only read): the corpus must stay quick.
                if pb.model.nodes().len() > 200 {
                    return Ok(());
                }
                let mut settings = pb.settings.clone();
                settings.engine.max_pivots =
                    Some(settings.engine.max_pivots.unwrap_or(500).min(500));
                if let Ok(a) = unilateral_analysis::analyze(&pb.model, &settings) {
                    structural_json(&a).map_err(|e| out(&e))?;
                    structural_summary(&a, "t").map_err(|e| out(&e))?;
                    write_structural_csv(&a, out_dir).map_err(|e| out(&e))?;
                    write_vtk_for(&pb.model, &a, out_dir).map_err(|e| out(&e))?;
                }
                Ok(())
            }
            Err(e) => refused(e),
        },
        Reader::Zone => match read_contact_zone(path) {
            Ok(pb) => zone(pb),
            Err(e) => refused(e),
        },
        Reader::Lcp => match read_lcp(path) {
            Ok(lcp) => {
                if let Ok(sol) = unilateral_lcp::solve_lcp(&lcp, &Default::default()) {
                    lcp_json(&sol).map_err(|e| out(&e))?;
                    lcp_summary(&sol, "t").map_err(|e| out(&e))?;
                }
                Ok(())
            }
            Err(e) => refused(e),
        },
        Reader::Fc2d => match read_fc2d(path) {
            Ok(_) => Ok(()),
            Err(e) => refused(e),
        },
        Reader::Mtx => match read_matrix_market(path) {
            Ok(_) => Ok(()),
            Err(e) => refused(e),
        },
        Reader::Gmsh => match read_gmsh(path) {
            Ok(_) => Ok(()),
            Err(e) => refused(e),
        },
    }
}

/// The reader of a kept fuzz finding, from its name: `<reader>-<anything>.<ext>`.
fn reader_of_finding(name: &str) -> Option<Reader> {
    let prefix = name.split('-').next()?;
    Some(match prefix {
        "problem" => Reader::Problem,
        "zone" => Reader::Zone,
        "lcp" => Reader::Lcp,
        "fc2d" => Reader::Fc2d,
        "mtx" => Reader::Mtx,
        "gmsh" => Reader::Gmsh,
        _ => return None,
    })
}

/// What the corpus run found: the number of inputs, the broken reader contracts and the
/// broken output contracts.
struct Run {
    inputs: usize,
    readers: Vec<String>,
    outputs: Vec<String>,
}

/// The corpus is run once for both tests below.
fn run() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(run_corpus)
}

fn run_corpus() -> Run {
    let mut cases: Vec<(String, String, Vec<u8>, Reader)> = Vec::new();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for seed in seeds() {
        let ext = Path::new(&seed.name)
            .extension()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        for (what, bytes) in mutants(&seed, &mut rng) {
            cases.push((
                format!("{}: {what}", seed.name),
                ext.clone(),
                bytes,
                seed.reader,
            ));
        }
    }
    let findings = repo().join("tests/data/fuzz");
    let mut kept: Vec<_> = std::fs::read_dir(&findings)
        .unwrap_or_else(|e| panic!("{} is missing: {e}", findings.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "md"))
        .collect();
    kept.sort();
    for path in kept {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let reader = reader_of_finding(&name)
            .unwrap_or_else(|| panic!("tests/data/fuzz/{name}: name it <reader>-….<ext>"));
        let ext = path.extension().unwrap().to_string_lossy().into_owned();
        cases.push((
            format!("tests/data/fuzz/{name}"),
            ext,
            std::fs::read(&path).unwrap(),
            reader,
        ));
    }
    assert!(cases.len() > 300, "only {} cases", cases.len());

    // The cases run on a worker thread; a case that hangs is named by the watchdog below.
    let current = Arc::new(Mutex::new(String::new()));
    let (done_tx, done_rx) = mpsc::channel();
    let worker_current = Arc::clone(&current);
    std::thread::spawn(move || {
        let dir = tempfile::tempdir().unwrap();
        let (mut readers, mut outputs) = (Vec::new(), Vec::new());
        for (k, (what, ext, bytes, reader)) in cases.iter().enumerate() {
            *worker_current.lock().unwrap() = what.clone();
            let path = dir.path().join(format!("case{k}.{ext}"));
            std::fs::write(&path, bytes).unwrap();
            let out_dir = dir.path().join(format!("out{k}"));
            match catch_unwind(AssertUnwindSafe(|| check_one(*reader, &path, &out_dir))) {
                Ok(Ok(())) => {}
                Ok(Err(Broken::Reader(msg))) => readers.push(format!("{what}: {msg}")),
                Ok(Err(Broken::Output(msg))) => outputs.push(format!("{what}: {msg}")),
                Err(_) => readers.push(format!("{what}: PANIC")),
            }
            let _ = std::fs::remove_file(&path);
            let _ = std::fs::remove_dir_all(&out_dir);
        }
        let _ = done_tx.send(Run {
            inputs: cases.len(),
            readers,
            outputs,
        });
    });
    // Generous: the whole corpus reads in a few seconds in release mode.
    match done_rx.recv_timeout(Duration::from_secs(300)) {
        Ok(run) => run,
        Err(_) => panic!(
            "no answer after 300 s: the reader hangs on {}",
            current.lock().unwrap()
        ),
    }
}

fn report(failures: &[String]) -> String {
    let cut: Vec<String> = failures
        .iter()
        .map(|f| f.chars().take(400).collect())
        .collect();
    cut.join("\n")
}

/// No panic, no hang, and every refusal names the file.
#[test]
fn mutated_inputs_never_break_a_reader() {
    let run = run();
    assert!(
        run.readers.is_empty(),
        "{} of {} inputs broke a reader:\n{}",
        run.readers.len(),
        run.inputs,
        report(&run.readers)
    );
}

/// When a mutant is read and solved, every number the writers print is finite: the readers
/// accept only finite data, so a NaN or an infinity in a result would be the program's
/// fault (the writers refuse it as an internal failure; this test says it never happens).
#[test]
fn solved_mutants_have_finite_results() {
    let run = run();
    assert!(
        run.outputs.is_empty(),
        "{} of {} inputs were read and solved to a non-finite result:\n{}",
        run.outputs.len(),
        run.inputs,
        report(&run.outputs)
    );
}

/// The case: one JSON array of 160 000 numbers on one line was rejected only after
/// 14 s (each value's column was counted from the start of the line). Reading it must now
/// complete with the error about its length; with the quadratic step back this test takes
/// minutes instead of well under a second.
#[test]
fn a_long_one_line_array_is_read_to_its_error() {
    let dir = tempfile::tempdir().unwrap();
    let many = vec!["0.25"; 160_000].join(", ");
    for (name, text) in [
        (
            "long.json",
            format!(
                "{{\"contact_zone\": {{\"friction\": 0.5, \"Rnn\": [[1]], \"Rtt\": [[1]], \"gap\": [{many}]}}, \"load\": {{\"variable\": {{\"normal\": [1]}}}}}}"
            ),
        ),
        (
            "long.toml",
            format!("[contact_zone]\nfriction = 0.5\nRnn = [[1]]\nRtt = [[1]]\ngap = [{many}]\n[load.variable]\nnormal = [1]\n"),
        ),
    ] {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let e = read_contact_zone(&path).unwrap_err();
        assert!(
            e.to_string().contains("has 160000 entries, but the contact zone has 1 pairs"),
            "{e}"
        );
    }
    let path = dir.path().join("dat.dat");
    std::fs::write(
        &path,
        format!("2\n0\n2\n2\n2 2\n{}", many.replace(", ", " ")),
    )
    .unwrap();
    read_siconos_lcp(&path).unwrap();
}

/// An object of 160 000 keys: each key was compared with every earlier one to find
/// duplicates (quadratic: over a minute). The reference is the first key, which is unknown.
#[test]
fn an_object_of_many_keys_is_read_to_its_error() {
    let dir = tempfile::tempdir().unwrap();
    let keys: Vec<String> = (0..160_000).map(|i| format!("\"k{i}\": 1")).collect();
    let path = dir.path().join("keys.json");
    std::fs::write(
        &path,
        format!("{{\"contact_zone\": {{{}}}}}", keys.join(", ")),
    )
    .unwrap();
    let e = read_contact_zone(&path).unwrap_err();
    assert!(e.to_string().contains("unknown key `k0`"), "{e}");
}

/// A 1 MB unknown key: no "did you mean" search over it (it took seconds against many
/// candidates), and the message shows its start and its length, not the megabyte.
#[test]
fn a_huge_unknown_key_gives_a_short_message() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("long.toml");
    let key = "R".repeat(1_000_000);
    std::fs::write(&path, format!("[contact_zone]\n{key} = 1\n")).unwrap();
    let e = read_contact_zone(&path).unwrap_err().to_string();
    assert!(
        e.contains("unknown key") && e.contains("(1000000 characters)"),
        "{e}"
    );
    assert!(e.len() < 1_000, "a message of {} bytes", e.len());
}
