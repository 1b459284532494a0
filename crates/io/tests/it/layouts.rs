//! Unusual but valid layouts, and unusual bad input, written to temporary files.

use std::path::PathBuf;

use unilateral_io::{read_contact_zone, read_lcp, InputError, InputErrorKind};

fn write(dir: &tempfile::TempDir, name: &str, text: impl AsRef<[u8]>) -> PathBuf {
    let p = dir.path().join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn zone(name: &str, text: &str) -> Result<unilateral_io::ContactZoneProblem, InputError> {
    let dir = tempfile::tempdir().unwrap();
    read_contact_zone(&write(&dir, name, text))
}

const ONE_PAIR: &str = "[contact_zone]\nfriction = 0.5\nRnn = [[2.0]]\nRtt = [[3]]\n";

#[test]
fn dotted_keys_inline_tables_crlf_and_bom() {
    let p = zone(
        "dotted.toml",
        "contact_zone.friction = 0.5\ncontact_zone.Rnn = [[2.0]]\ncontact_zone.Rtt = [[3]]\nload.variable.normal = [1.0]\n",
    )
    .unwrap();
    assert_eq!(p.zone.variable.normal, vec![1.0]);

    let p = zone(
        "inline.toml",
        "contact_zone = { friction = 0.5, Rnn = [[2.0]], Rtt = [[3]] }\nload = { variable = { tangential = [-1] } }\n",
    )
    .unwrap();
    assert_eq!(p.zone.variable.tangential, vec![-1.0]);
    assert_eq!(p.zone.variable.normal, vec![0.0]);

    let crlf = format!("\u{feff}{ONE_PAIR}[load.variable]\nnormal = [1.0]\n").replace('\n', "\r\n");
    let p = zone("crlf.toml", &crlf).unwrap();
    assert_eq!(p.zone.rtt[(0, 0)], 3.0);

    let json = "\u{feff}{\"contact_zone\": {\"friction\": 0, \"Rnn\": [[2]], \"Rtt\": [[3]]},\r\n \"load\": {\"variable\": {\"normal\": [1e-3]}}}";
    let p = zone("bom.json", json).unwrap();
    assert_eq!(p.zone.variable.normal, vec![1e-3]);
}

#[test]
fn positions_count_characters_and_crlf_lines() {
    // The key path and the column of an entry after a multi-byte character.
    let e = zone(
        "utf8.toml",
        "# Контактная зона\r\n[contact_zone]\r\nnames = [\"опора\"]\r\nfriction = [-0.5]\r\nRnn = [[2.0]]\r\nRtt = [[3]]\r\n[load.variable]\r\nnormal = [1.0]\r\n",
    )
    .unwrap_err();
    assert_eq!(e.key.as_deref(), Some("contact_zone.friction[1]"));
    assert_eq!((e.location.line, e.location.column), (Some(4), Some(13)));
    let e = zone(
        "utf8_2.toml",
        "[contact_zone]\nnames = [\"опора\", 3]\nfriction = 0\nRnn = [[2.0, 0], [0, 1]]\nRtt = [[3, 0], [0, 1]]\n",
    )
    .unwrap_err();
    assert_eq!(e.key.as_deref(), Some("contact_zone.names[2]"));
    assert_eq!((e.location.line, e.location.column), (Some(2), Some(19)));
}

#[test]
fn deep_nesting_and_odd_types_are_errors_not_crashes() {
    let deep = format!("{ONE_PAIR}x = {}1{}\n", "[".repeat(5000), "]".repeat(5000));
    let e = zone("deep.toml", &deep).unwrap_err();
    assert_eq!(e.location.line, Some(5), "{e}");
    assert!(e.message.contains("recursion limit"), "{e}");

    let deep = format!("{{\"a\": {}1{}}}", "[".repeat(100_000), "]".repeat(100_000));
    let e = zone("deep.json", &deep).unwrap_err();
    assert!(e.message.contains("nesting"), "{e}");

    for (name, text, frag) in [
        (
            "date.toml",
            "[contact_zone]\nfriction = 1979-05-27\nRnn = [[1]]\nRtt = [[1]]\n",
            "found a date-time",
        ),
        (
            "aot.toml",
            &format!("{ONE_PAIR}[[load.variable]]\nnormal = [1.0]\n"),
            "expected a table, found an array",
        ),
        (
            "null.json",
            "{\"contact_zone\": {\"friction\": null, \"Rnn\": [[1]], \"Rtt\": [[1]]}}",
            "found null",
        ),
        (
            "bool.json",
            "{\"contact_zone\": {\"friction\": true, \"Rnn\": [[1]], \"Rtt\": [[1]]}}",
            "found a boolean (true)",
        ),
        (
            "one_d.toml",
            "[contact_zone]\nfriction = 0\nRnn = [2.0]\nRtt = [[1]]\n",
            "for one pair write [[x]]",
        ),
        (
            "empty_rnn.toml",
            "[contact_zone]\nfriction = 0\nRnn = []\nRtt = []\n",
            "Rnn is empty",
        ),
        (
            "big.json",
            "{\"contact_zone\": {\"friction\": 1e999}}",
            "too large",
        ),
        ("ws.json", "   \n\t ", "empty"),
        (
            "zero_pivots.toml",
            &format!("{ONE_PAIR}[load.variable]\nnormal = [1.0]\n[solve]\nmax_pivots = 0\n"),
            "≥ 1",
        ),
        (
            "trace_case.toml",
            &format!("{ONE_PAIR}[load.variable]\nnormal = [1.0]\n[solve]\ntrace = \"End\"\n"),
            "did you mean \"end\"",
        ),
        (
            "load_scalar.toml",
            &format!("{ONE_PAIR}[load.variable]\nnormal = 1.0\n"),
            "expected an array of 1 numbers",
        ),
        (
            "unknown_load.toml",
            &format!("{ONE_PAIR}[load.variable]\nnormals = [1.0]\n"),
            "did you mean `normal`",
        ),
        (
            "abs_dir.toml",
            "[contact_zone]\nfriction = 0\nRnn = \"/\"\nRtt = [[1]]\n",
            "cannot read the Matrix Market file",
        ),
    ] {
        let e = zone(name, text).unwrap_err();
        assert!(e.to_string().contains(frag), "{name}: {e}");
        assert!(e.to_string().contains(name), "{name}: {e}");
    }
}

#[test]
fn mtx_symmetry_error_points_into_the_mtx_file() {
    let dir = tempfile::tempdir().unwrap();
    write(
        &dir,
        "rnn.mtx",
        "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 2\n1 2 -1\n2 2 2\n",
    );
    let p = write(
        &dir,
        "p.toml",
        "[contact_zone]\nfriction = 0\nRnn = \"rnn.mtx\"\nRtt = [[1, 0], [0, 1]]\n[load.variable]\nnormal = [1, 1]\n",
    );
    let e = read_contact_zone(&p).unwrap_err();
    assert_eq!(e.kind, InputErrorKind::Invalid);
    assert!(e.file().ends_with("rnn.mtx"), "{e}");
    assert_eq!(e.location.line, Some(4));
    assert_eq!(e.key.as_deref(), Some("contact_zone.Rnn[1][2]"));
    let from = e.referenced_from.as_ref().unwrap();
    assert_eq!((from.line, from.column), (Some(3), Some(7)));
    assert!(e.to_string().contains("p.toml:3:7"), "{e}");
}

#[test]
fn lcp_extensions() {
    let dir = tempfile::tempdir().unwrap();
    let e = read_lcp(&write(&dir, "x.csv", "1,2")).unwrap_err();
    assert_eq!(e.kind, InputErrorKind::Unsupported);
    let e = read_lcp(&write(&dir, "x.toml", "M = [[1]]\nq = [1]\nw = 3\n")).unwrap_err();
    assert!(e.message.contains("unknown key `w`"), "{e}");
    let l = read_lcp(&write(&dir, "UPPER.DAT", "1 0 1 1 1 1 4 -2 trailing words")).unwrap();
    assert_eq!((l.m[(0, 0)], l.q[0]), (4.0, -2.0));
    let e = read_lcp(&dir.path().join("missing.dat")).unwrap_err();
    assert_eq!(e.kind, InputErrorKind::Io);
    let e = read_lcp(dir.path()).unwrap_err();
    assert!(e.to_string().contains("must be"), "{e}");
}
