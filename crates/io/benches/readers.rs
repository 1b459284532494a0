//! Reading rates of the numeric readers: a dense LCP in Siconos `.dat` form and the same matrix
//! as a Matrix Market coordinate file, n = 800 (about 16 MB and 21 MB of text), written once
//! to a temporary folder. Criterion reports bytes per second of wall time.
//!
//! `cargo bench -p unilateral-io --bench readers`
//!
//! For the whole-process rate and the peak memory on a file of your own, see
//! `cargo run --release -p unilateral-io --example read_speed -- FILE`.

use std::fmt::Write as _;
use std::path::Path;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

const N: usize = 800;

/// A reproducible entry in (-1, 1) with 17 significant digits, as a program printing full
/// precision writes them.
fn entry(i: usize, j: usize) -> f64 {
    let k = (i * 7919 + j * 104_729) % 1_000_003;
    (k as f64 / 1_000_003.0) * 2.0 - 1.0 + 1e-9 * (i as f64)
}

fn write_dat(path: &Path) {
    let mut s = format!("{N}\n0\n{N}\n{N}\n{N} {N}\n");
    for j in 0..N {
        for i in 0..N {
            write!(s, "{:.17e} ", entry(i, j)).unwrap();
        }
        s.push('\n');
    }
    for i in 0..N {
        write!(s, "{:.17e} ", entry(i, N)).unwrap();
    }
    s.push('\n');
    std::fs::write(path, s).unwrap();
}

fn write_mtx(path: &Path) {
    let mut s = format!(
        "%%MatrixMarket matrix coordinate real general\n% written by the benchmark\n{N} {N} {}\n",
        N * N
    );
    for j in 0..N {
        for i in 0..N {
            writeln!(s, "{} {} {:.17e}", i + 1, j + 1, entry(i, j)).unwrap();
        }
    }
    std::fs::write(path, s).unwrap();
}

fn readers(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let dat = dir.path().join("m.dat");
    let mtx = dir.path().join("m.mtx");
    write_dat(&dat);
    write_mtx(&mtx);
    let mut g = c.benchmark_group("readers");
    g.sample_size(10);
    g.throughput(Throughput::Bytes(std::fs::metadata(&dat).unwrap().len()));
    g.bench_function("siconos_dat_n800", |b| {
        b.iter(|| unilateral_io::read_siconos_lcp(&dat).unwrap())
    });
    g.throughput(Throughput::Bytes(std::fs::metadata(&mtx).unwrap().len()));
    g.bench_function("matrix_market_n800", |b| {
        b.iter(|| unilateral_io::read_matrix_market(&mtx).unwrap())
    });
    g.finish();
}

criterion_group!(benches, readers);
criterion_main!(benches);
