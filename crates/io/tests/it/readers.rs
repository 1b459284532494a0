//! The valid fixtures of `tests/data/good/` and the Siconos test problems of
//! `tests/data/siconos/`.

// Literals are written exactly as the .dat files print them, so they can be found there.
#![allow(clippy::excessive_precision)]

use crate::common;

use std::path::{Path, PathBuf};

use common::{siconos, siconos_files};

use faer::Mat;
use unilateral_contact::{ContactZone, Follow};
use unilateral_io::{read_contact_zone, read_fc2d, read_lcp, read_matrix_market};
use unilateral_oracle::fixtures::example1 as ex1;

fn good(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/good")
        .join(name)
}

fn mat(rows: &[&[f64]]) -> Mat<f64> {
    Mat::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
}

fn assert_mat_eq(a: &Mat<f64>, b: &Mat<f64>, what: &str) {
    assert_eq!(
        (a.nrows(), a.ncols()),
        (b.nrows(), b.ncols()),
        "{what}: shape"
    );
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            assert_eq!(a[(i, j)], b[(i, j)], "{what}[{}][{}]", i + 1, j + 1);
        }
    }
}

fn assert_zone_eq(a: &ContactZone, b: &ContactZone) {
    assert_mat_eq(&a.rnn, &b.rnn, "Rnn");
    assert_mat_eq(&a.rtt, &b.rtt, "Rtt");
    assert_mat_eq(&a.rnt, &b.rnt, "Rnt");
    assert_mat_eq(&a.rtn, &b.rtn, "Rtn");
    assert_eq!(a.friction, b.friction);
    assert_eq!(a.gap, b.gap);
    assert_eq!(a.constant, b.constant);
    assert_eq!(a.variable, b.variable);
    assert_eq!(a.pair_names, b.pair_names);
}

#[test]
fn example1_in_toml_json_and_matrix_market_reads_the_same() {
    let toml = read_contact_zone(&good("example1.toml")).unwrap();
    let json = read_contact_zone(&good("example1.json")).unwrap();
    let mtx = read_contact_zone(&good("example1_mtx.toml")).unwrap();

    let z = &toml.zone;
    assert_eq!(z.pairs(), 3);
    // The file holds the paper's Example 1 (formulation.md §5, the oracle's fixture).
    assert_mat_eq(&z.rnn, &Mat::from_fn(3, 3, |i, j| ex1::RNN[i][j]), "Rnn");
    assert_mat_eq(&z.rtt, &Mat::from_fn(3, 3, |i, j| ex1::RTT[i][j]), "Rtt");
    assert_mat_eq(&z.rnt, &Mat::zeros(3, 3), "Rnt");
    assert_eq!(z.friction, vec![ex1::FRICTION; 3]);
    assert_eq!(z.gap, vec![0.0; 3]);
    assert_eq!(z.variable.normal, ex1::RV_N.to_vec());
    assert_eq!(z.variable.tangential, vec![0.0; 3]);
    assert_eq!(z.constant.normal, vec![0.0; 3]);
    assert_eq!(z.pair_names, vec!["1", "2", "3"]);
    assert_eq!(toml.settings.tightening, 1.0);
    assert_eq!(toml.settings.target, 1.0);
    assert_eq!(toml.settings.follow, Follow::ToEnd);

    assert_zone_eq(&toml.zone, &json.zone);
    assert_zone_eq(&toml.zone, &mtx.zone);
    assert_eq!(toml.settings, json.settings);
    assert_eq!(toml.settings, mtx.settings);
}

#[test]
fn matrix_market_fixtures() {
    let rnn = read_matrix_market(&good("example1_rnn.mtx")).unwrap();
    assert_eq!(rnn[(0, 2)], ex1::RNN[0][2]);
    assert_eq!(rnn[(2, 0)], ex1::RNN[2][0]);
    let rtt = read_matrix_market(&good("example1_rtt.mtx")).unwrap();
    assert_eq!(rtt[(1, 2)], -1.0);
    assert_eq!(rtt[(0, 2)], 0.0);
}

#[test]
fn every_key_is_read() {
    let p = read_contact_zone(&good("all_keys.toml")).unwrap();
    let z = &p.zone;
    assert_eq!(z.pair_names, vec!["left", "middle", "right"]);
    assert_eq!(z.friction, vec![0.3, 0.5, 0.0]);
    assert_eq!(z.gap, vec![0.0, 0.001, 0.002]);
    assert_eq!(z.rnn[(0, 1)], -1.0);
    assert_eq!(z.rtt[(1, 2)], 0.5);
    assert_eq!(z.rnt[(2, 2)], 0.1);
    // Rtn[i][j]: first index the link whose force is read (row), as written.
    assert_eq!(z.rtn[(0, 1)], 0.2);
    assert_eq!(z.rtn[(2, 0)], 0.2);
    assert_eq!(z.rtn[(1, 0)], 0.0);
    assert_eq!(z.constant.normal, vec![1.0; 3]);
    assert_eq!(z.constant.tangential, vec![0.0, 0.1, 0.0]);
    assert_eq!(z.variable.normal, vec![0.0; 3]);
    assert_eq!(z.variable.tangential, vec![0.5, 0.0, -0.5]);
    let s = &p.settings;
    assert_eq!(s.tightening, 0.0);
    assert_eq!(s.target, 2.5);
    assert_eq!(s.follow, Follow::ToTarget);
    assert_eq!(s.engine.pivot_tolerance, Some(1e-10));
    assert_eq!(s.engine.max_pivots, Some(500));
}

#[test]
fn small_lcp_in_toml_json_and_dat() {
    let t = read_lcp(&good("lcp_small.toml")).unwrap();
    let j = read_lcp(&good("lcp_small.json")).unwrap();
    assert_mat_eq(&t.m, &mat(&[&[2.0, 1.0], &[1.0, 2.0]]), "M");
    assert_eq!(t.q, vec![-5.0, -6.0]);
    assert_mat_eq(&t.m, &j.m, "M");
    assert_eq!(t.q, j.q);
    // The same problem as Siconos' `lcp_deudeu.dat`, written by hand in TOML and JSON.
    let d = read_lcp(&siconos("lcp").join("lcp_deudeu.dat")).unwrap();
    assert_mat_eq(&t.m, &d.m, "M");
    assert_eq!(t.q, d.q);
}

#[test]
fn siconos_lcp_files() {
    let dir = siconos("lcp");
    let names = siconos_files("lcp");
    assert_eq!(names.len(), 10, "{names:?}");
    for p in &names {
        let lcp = read_lcp(p).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(lcp.m.nrows(), lcp.q.len(), "{}", p.display());
        assert_eq!(lcp.m.ncols(), lcp.q.len(), "{}", p.display());
    }
    let read = |name: &str| read_lcp(&dir.join(name)).unwrap();

    // CPS_1: M = [[1, 1], [1, 1]], q = -e; solutions z1 + z2 = 1.
    let l = read("lcp_CPS_1.dat");
    assert_mat_eq(&l.m, &mat(&[&[1.0, 1.0], &[1.0, 1.0]]), "M");
    assert_eq!(l.q, vec![-1.0, -1.0]);

    // CPS_2: each printed line is a column. Lines "0 2 -1", "-1 0 1", "2 -2 0".
    let l = read("lcp_CPS_2.dat");
    assert_mat_eq(
        &l.m,
        &mat(&[&[0.0, -1.0, 2.0], &[2.0, 0.0, -2.0], &[-1.0, 1.0, 0.0]]),
        "M",
    );
    assert_eq!(l.q, vec![-3.0, 6.0, -1.0]);

    // CPS_3 (a bimatrix game): the off-diagonal blocks are A and Bᵀ, not their transposes.
    let l = read("lcp_CPS_3.dat");
    assert_eq!((l.m[(2, 0)], l.m[(3, 0)], l.m[(2, 1)]), (10.0, 30.0, 20.0));
    assert_eq!((l.m[(0, 2)], l.m[(1, 2)], l.m[(0, 3)]), (10.0, 30.0, 20.0));
    assert_eq!(l.m[(0, 0)], 0.0);

    // Murty's example: upper triangular, 1 on the diagonal and 2 above it.
    let l = read("lcp_exp_murty.dat");
    assert_eq!(l.m.nrows(), 6);
    for i in 0..6 {
        for j in 0..6 {
            let want = match i.cmp(&j) {
                std::cmp::Ordering::Equal => 1.0,
                std::cmp::Ordering::Less => 2.0,
                std::cmp::Ordering::Greater => 0.0,
            };
            assert_eq!(l.m[(i, j)], want, "M[{}][{}]", i + 1, j + 1);
        }
    }
    assert_eq!(l.q, vec![-1.0; 6]);

    let l = read("lcp_ortiz.dat");
    assert_eq!(l.m[(1, 0)], -1.0); // first line = first column: 3 -1 0 0
    assert_eq!(l.m[(0, 1)], 1.0); // second line = second column: 1 2 1 0
    assert_eq!(l.m[(3, 3)], 2.0);
    assert_eq!(l.q, vec![-2.0, 1.0, -1.0, 1.0]);

    let l = read("lcp_Pang_isolated_sol.dat");
    assert_eq!(l.m.nrows(), 3);
    assert_eq!(l.q, vec![0.0, -1.0, 1.0]);

    let l = read("lcp_mmc.dat");
    assert_eq!(l.m.nrows(), 26);
    assert_eq!(l.m[(0, 0)], 1.488865599999999976716936e+05);
    assert_eq!(l.m[(1, 0)], -9.278025599999999394640326e+04);
    assert_eq!(l.q[25], 6.053916799999999875936396e-01);

    let l = read("lcp_enum_fails.dat");
    assert_eq!(l.m.nrows(), 9);
    assert_eq!(l.m[(0, 0)], 5.033710181702543806636641e+00);
    assert_eq!(l.m[(1, 0)], -5.224563268131394710991344e-01);
    assert_eq!(l.m[(0, 1)], -2.202221595301195322669230e-01);

    let l = read("lcp_trivial.dat");
    assert_eq!(l.m.nrows(), 9);
    assert_eq!(l.m[(0, 0)], 1.0);
}

#[test]
fn siconos_fc2d_file() {
    let p = read_fc2d(&siconos("fc2d").join("FC2D_SliderCrankLagrangian00000.dat")).unwrap();
    assert_eq!(p.contacts(), 2);
    assert_eq!((p.w.nrows(), p.w.ncols()), (4, 4));
    assert_eq!(p.w[(0, 0)], 9.365610022253570150496671e+02);
    // The first printed line is the first column, the second line the second column.
    assert_eq!(p.w[(1, 0)], -4.642665883420582986218506e+02);
    assert_eq!(p.w[(0, 1)], -4.642662921766745967033785e+02);
    assert_eq!(p.w[(2, 1)], 4.616596337492514976474922e+02);
    assert_eq!(
        p.q,
        vec![
            -1.179087309965789476251530e+00,
            -8.407368208001527065675873e+00,
            -1.179087309965789476251530e+00,
            -8.407368208001527065675873e+00
        ]
    );
    assert_eq!(p.mu, vec![0.01, 0.01]);
}
