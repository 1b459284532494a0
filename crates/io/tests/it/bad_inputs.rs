//! Every file of `tests/data/bad/` must be refused with an `InputError` that names the file,
//! the place (line:column and/or key) and contains the fragment listed in
//! `tests/data/bad/EXPECTED.txt`; nothing may panic.

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use unilateral_io::{read_contact_zone, read_fc2d, read_lcp, read_matrix_market, InputError};

fn data_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data")
}

/// Reads a file with the reader its name asks for.
fn read_any(path: &Path) -> Result<(), InputError> {
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    let ext = path.extension().map(|e| e.to_string_lossy().to_string());
    match ext.as_deref() {
        Some("mtx") => read_matrix_market(path).map(drop),
        Some("dat") if name.starts_with("fc2d_") => read_fc2d(path).map(drop),
        _ if name.starts_with("lcp_") => read_lcp(path).map(drop),
        _ => read_contact_zone(path).map(drop),
    }
}

struct Expected {
    location: Option<String>,
    key: Option<String>,
    fragment: String,
}

fn expected_table() -> BTreeMap<String, Expected> {
    let text = std::fs::read_to_string(data_dir().join("bad/EXPECTED.txt")).unwrap();
    let mut out = BTreeMap::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cols: Vec<&str> = line.splitn(4, " | ").map(str::trim).collect();
        assert_eq!(cols.len(), 4, "EXPECTED.txt: bad row {line:?}");
        let opt = |s: &str| (s != "-").then(|| s.to_string());
        let prev = out.insert(
            cols[0].to_string(),
            Expected {
                location: opt(cols[1]),
                key: opt(cols[2]),
                fragment: cols[3].to_string(),
            },
        );
        assert!(prev.is_none(), "EXPECTED.txt lists {} twice", cols[0]);
    }
    out
}

#[test]
fn every_bad_file_gives_a_located_error() {
    let dir = data_dir().join("bad");
    let table = expected_table();
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| e.file_name().to_string_lossy().to_string())
        .filter(|n| n != "EXPECTED.txt")
        .collect();
    files.sort();
    assert!(files.len() >= 22, "only {} bad files", files.len());
    let mut failures = Vec::new();
    for name in &files {
        let path = dir.join(name);
        let result = catch_unwind(AssertUnwindSafe(|| read_any(&path)));
        let Ok(result) = result else {
            failures.push(format!("{name}: PANICKED"));
            continue;
        };
        let Err(err) = result else {
            failures.push(format!("{name}: was read without an error"));
            continue;
        };
        let msg = err.to_string();
        println!("{msg}");
        let Some(exp) = table.get(name) else {
            failures.push(format!(
                "{name}: not listed in EXPECTED.txt (message: {msg})"
            ));
            continue;
        };
        if !msg.contains(name.as_str()) {
            failures.push(format!("{name}: the message does not name the file: {msg}"));
        }
        if let Some(loc) = &exp.location {
            if !msg.contains(&format!("{loc}: ")) {
                failures.push(format!("{name}: expected the place `{loc}` in: {msg}"));
            }
        }
        if let Some(key) = &exp.key {
            if !msg.contains(&format!(": {key}: ")) || err.key.as_deref() != Some(key.as_str()) {
                failures.push(format!("{name}: expected the key `{key}` in: {msg}"));
            }
        }
        if !msg.contains(&exp.fragment) {
            failures.push(format!("{name}: expected `{}` in: {msg}", exp.fragment));
        }
    }
    for name in table.keys() {
        if !files.contains(name) {
            failures.push(format!("EXPECTED.txt lists {name}, which does not exist"));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

/// Every prefix of every valid fixture and test file, and a few byte flips: an error or a
/// value, never a panic.
#[test]
fn truncated_and_corrupted_files_never_panic() {
    let mut sources: Vec<PathBuf> = std::fs::read_dir(data_dir().join("good"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    sources.sort();
    let tmp = tempfile::tempdir().unwrap();
    // Matrix Market files named by the fixtures must be found next to the copies.
    for src in &sources {
        if src.extension().is_some_and(|e| e == "mtx") {
            std::fs::copy(src, tmp.path().join(src.file_name().unwrap())).unwrap();
        }
    }
    let mut reads = 0;
    for src in &sources {
        let bytes = std::fs::read(src).unwrap();
        let name = src.file_name().unwrap().to_string_lossy().to_string();
        let target = tmp.path().join(format!("cut_{name}"));
        let mut variants: Vec<Vec<u8>> = (0..bytes.len()).map(|k| bytes[..k].to_vec()).collect();
        for k in (0..bytes.len()).step_by(7) {
            let mut v = bytes.clone();
            v[k] = match k % 3 {
                0 => b'[',
                1 => b'"',
                _ => 0xff,
            };
            variants.push(v);
        }
        for v in variants {
            std::fs::write(&target, &v).unwrap();
            let r = catch_unwind(AssertUnwindSafe(|| {
                if name.starts_with("lcp_") {
                    read_lcp(&target).map(drop)
                } else if name.ends_with(".mtx") {
                    read_matrix_market(&target).map(drop)
                } else {
                    read_contact_zone(&target).map(drop)
                }
            }));
            assert!(
                r.is_ok(),
                "panic on a variant of {name}: {:?}",
                String::from_utf8_lossy(&v)
            );
            reads += 1;
        }
    }
    assert!(reads > 1000);
}
