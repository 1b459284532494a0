//! The zlib encoder of the compressed `.vtu` files (`unilateral_output::deflate::zlib`)
//! against `zlib-rs` at its fastest level, a compressor made once and reset for each stream
//! (what the writer used until round 36), on the kinds of arrays a path's frames hold: each
//! array its own stream, as VTK reads them. Prints each encoder's compressed size too.
//!
//! `cargo bench -p unilateral-output --bench deflate`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use flate2::{Compress, Compression, FlushCompress, Status};
use std::hint::black_box;
use unilateral_output::deflate;

/// A frame of a beam on `m` bearings, as its arrays' bytes: a displacement field (three
/// components, the third zero), the pairs' forces (zero where a pair is open), state codes
/// and pair indices.
fn frame(m: usize) -> Vec<Vec<u8>> {
    let f64s = |v: &mut Vec<u8>, x: f64| v.extend_from_slice(&x.to_le_bytes());
    let (mut u, mut force, mut state, mut index) = (vec![], vec![], vec![], vec![]);
    for k in 0..m {
        let s = k as f64 / m as f64;
        f64s(&mut u, 1e-3 * (7.0 * s).sin());
        f64s(&mut u, -2e-2 * (3.0 * s).cos() * s);
        f64s(&mut u, 0.0);
        let open = (k / 17) % 3 == 0;
        f64s(&mut force, if open { 0.0 } else { 1.5e4 * s * (1.0 - s) });
        f64s(&mut force, if open { 0.0 } else { -3.0e3 * s });
        f64s(&mut force, 0.0);
        state.extend_from_slice(&(if open { 0i32 } else { 1 + (k % 2) as i32 }).to_le_bytes());
        index.extend_from_slice(&(k as i64).to_le_bytes());
    }
    vec![u, force, state, index]
}

/// One stream by `zlib-rs` at its fastest level.
fn zlib_rs(c: &mut Compress, bytes: &[u8]) -> Vec<u8> {
    c.reset();
    let mut out = Vec::with_capacity(bytes.len() + bytes.len() / 1024 + 64);
    loop {
        let done = c.total_in() as usize;
        match c.compress_vec(&bytes[done..], &mut out, FlushCompress::Finish) {
            Ok(Status::StreamEnd) => return out,
            Ok(_) => out.reserve(out.capacity().max(64)),
            Err(e) => panic!("{e}"),
        }
    }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("deflate");
    for m in [300, 1000] {
        // Blocks of at most 32 KB, as the writer cuts them.
        let blocks: Vec<Vec<u8>> = frame(m)
            .iter()
            .flat_map(|a| a.chunks(32_768).map(<[u8]>::to_vec).collect::<Vec<_>>())
            .collect();
        let total: usize = blocks.iter().map(Vec::len).sum();
        let mut z = Compress::new(Compression::fast(), true);
        let ours: usize = blocks.iter().map(|b| deflate::zlib(b).len()).sum();
        let theirs: usize = blocks.iter().map(|b| zlib_rs(&mut z, b).len()).sum();
        println!(
            "m = {m}: {} blocks, {total} bytes; this encoder {ours} bytes, zlib-rs fastest {theirs}",
            blocks.len()
        );
        group.throughput(Throughput::Bytes(total as u64));
        group.bench_function(format!("this encoder, m = {m}"), |b| {
            b.iter(|| {
                for x in &blocks {
                    black_box(deflate::zlib(black_box(x)));
                }
            })
        });
        group.bench_function(format!("zlib-rs fastest, m = {m}"), |b| {
            b.iter(|| {
                for x in &blocks {
                    black_box(zlib_rs(&mut z, black_box(x)));
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
