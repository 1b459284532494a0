//! Reads a `.dat`, `.mtx` or `.msh` file given on the command line and prints the rate (MB/s)
//! and the peak memory of the process (from /proc/self/status), for docs/performance.md.
use std::path::Path;
use std::time::Instant;

fn peak_kib() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    s.lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse().ok())
}

fn main() {
    let file = std::env::args().nth(1).expect("usage: read_speed FILE");
    let path = Path::new(&file);
    let bytes = std::fs::metadata(path).expect("file").len() as f64;
    let t = Instant::now();
    if file.ends_with(".msh") {
        let m = unilateral_io::read_gmsh(path).expect("read");
        let s = t.elapsed().as_secs_f64();
        let peak = peak_kib().map_or(f64::NAN, |k| k as f64 * 1024.0);
        println!(
            "{file}: {} nodes, {} elements, {:.1} MB in {s:.3} s = {:.0} MB/s; peak memory {:.0} MB",
            m.nodes.len(),
            m.elements.len(),
            bytes / 1e6,
            bytes / 1e6 / s,
            peak / 1e6
        );
        return;
    }
    let n = if file.ends_with(".mtx") {
        unilateral_io::read_matrix_market(path)
            .expect("read")
            .nrows()
    } else {
        unilateral_io::read_siconos_lcp(path).expect("read").q.len()
    };
    let s = t.elapsed().as_secs_f64();
    let matrix = (n * n * 8) as f64;
    let peak = peak_kib().map_or(f64::NAN, |k| k as f64 * 1024.0);
    println!(
        "{file}: n = {n}, {:.1} MB in {s:.3} s = {:.0} MB/s; peak memory {:.0} MB = {:.2}x the matrix ({:.0} MB)",
        bytes / 1e6,
        bytes / 1e6 / s,
        peak / 1e6,
        peak / matrix,
        matrix / 1e6
    );
}
