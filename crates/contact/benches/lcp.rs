//! Contact-like LCPs of order `n = 3m` from `beam_on_supports(m, 7)` (the oracle's beam fixture), m = 100, 300,
//! 1000, against one dense LU of the same order:
//!
//! * `standard`: the standard LCP at `p = 1` (`q = q0 + d`) with `solve_lcp`,
//! * `path`: the whole load path, `follow_path` with `Follow::ToEnd`,
//! * `lu`: one `faer` `partial_piv_lu` of `M + s·I` (`n × n`, `s` makes it nonsingular).
//!
//! All three use the lexicographic order of `ContactLcp`. Before the criterion measurements a
//! report pass times one run of each and prints pivots, time per pivot, total time, the ratio
//! to the LU and the peak memory (VmHWM of `/proc/self/status`, reset before each run through
//! `/proc/self/clear_refs`, so it is the peak of that run; if the reset is refused it is the
//! process-wide high-water mark, and the sizes run in increasing order).
//!
//! ```text
//! cargo bench -p unilateral-contact --bench lcp                       # report + criterion
//! UNILATERAL_BENCH_MAX_M=300 cargo bench -p unilateral-contact --bench lcp   # skip m = 1000
//! UNILATERAL_BENCH_REPORT=0 cargo bench -p unilateral-contact --bench lcp    # criterion only
//! ```
//!
//! Runs of `m ≥ 1000` take seconds to tens of seconds, so criterion is configured with 10
//! samples and flat sampling (one run per sample for the large sizes). Under `cargo test`
//! (no `--bench` argument) only `m = 100` is run, once.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion, SamplingMode};
use faer::Mat;
#[path = "../tests/it/beam_zone.rs"]
mod beam_zone;
use beam_zone::beam_on_supports;
use unilateral_contact::ContactLcp;
use unilateral_lcp::{
    follow_path, solve_lcp, Follow, Lcp, LcpSolution, LoadPath, PathOptions, Settings,
};

mod common;
use common::one_thread;

const SEED: u64 = 7;

struct Problem {
    m: usize,
    contact: ContactLcp,
    standard: Lcp,
    settings: Settings,
    shifted: Mat<f64>,
}

impl Problem {
    fn new(m: usize) -> Self {
        let zone = beam_on_supports(m, SEED);
        let contact = ContactLcp::build(&zone);
        let pr = &contact.problem;
        let q = pr.q0.iter().zip(&pr.d).map(|(a, b)| a + b).collect();
        let standard = Lcp { m: pr.m.clone(), q };
        let settings = Settings {
            lexicographic_order: Some(contact.lexicographic_order.clone()),
            ..Default::default()
        };
        // M + s·I with s = ‖M‖∞: strictly diagonally dominant, so nonsingular.
        let n = pr.m.nrows();
        let s = (0..n)
            .map(|i| (0..n).map(|j| pr.m[(i, j)].abs()).sum::<f64>())
            .fold(0.0f64, f64::max);
        let shifted = Mat::from_fn(n, n, |i, j| pr.m[(i, j)] + if i == j { s } else { 0.0 });
        Self {
            m,
            contact,
            standard,
            settings,
            shifted,
        }
    }

    fn n(&self) -> usize {
        3 * self.m
    }

    fn solve_standard(&self) -> LcpSolution {
        solve_lcp(&self.standard, &self.settings).expect("valid standard LCP")
    }

    fn follow(&self) -> LoadPath {
        let options = PathOptions {
            target: 1.0,
            follow: Follow::ToEnd,
            tightening: None,
        };
        follow_path(&self.contact.problem, &options, &self.settings).expect("valid path")
    }

    fn lu(&self) -> f64 {
        let lu = one_thread(|| self.shifted.partial_piv_lu());
        // Something of the factors, so that nothing is optimised away.
        lu.U()[(0, 0)]
    }
}

/// VmHWM and VmRSS of this process in MiB.
fn memory_mib() -> (f64, f64) {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let field = |name: &str| {
        status
            .lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split_whitespace().nth(1))
            .and_then(|v| v.parse::<f64>().ok())
            .map_or(f64::NAN, |kib| kib / 1024.0)
    };
    (field("VmHWM:"), field("VmRSS:"))
}

/// CPU time of the whole process (all threads), from `/proc/self/stat`, in seconds.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name `(…)`: utime and stime are fields 14 and 15.
    let rest = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|v| v.parse().ok())
        .collect();
    f.iter().sum::<f64>() / 100.0 // USER_HZ = 100 on Linux
}

/// Resets VmHWM to the current RSS (Linux ≥ 4.0); false if refused.
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// One run of `f`: its result, wall time, CPU time (s, 10 ms resolution) and peak memory.
fn measured<T>(f: impl FnOnce() -> T) -> (T, Duration, f64, f64) {
    reset_peak();
    let c = cpu_seconds();
    let t = Instant::now();
    let out = black_box(f());
    let dt = t.elapsed();
    (out, dt, cpu_seconds() - c, memory_mib().0)
}

fn report(sizes: &[usize]) {
    let resettable = reset_peak();
    println!(
        "peak memory: {}",
        if resettable {
            "VmHWM reset before each run (peak of that run, including the problem data)"
        } else {
            "process-wide VmHWM high-water mark (clear_refs refused), sizes in increasing order"
        }
    );
    println!(
        "{:>5} {:>5} {:>9} {:>20} {:>7} {:>9} {:>9} {:>9} {:>9} {:>7} {:>9}",
        "m",
        "n",
        "what",
        "status",
        "pivots",
        "ms/pivot",
        "total s",
        "cpu s",
        "LU s",
        "×LU",
        "peak MiB"
    );
    for &m in sizes {
        let pb = Problem::new(m);
        let n = pb.n();
        // The LU first: the best of three (it is the yardstick).
        let mut lu_time = Duration::MAX;
        let mut lu_peak = 0.0f64;
        let mut lu_cpu = f64::MAX;
        for _ in 0..3 {
            let (_, dt, cpu, peak) = measured(|| pb.lu());
            lu_time = lu_time.min(dt);
            lu_cpu = lu_cpu.min(cpu);
            lu_peak = lu_peak.max(peak);
        }
        let lu_s = lu_time.as_secs_f64();
        let row = |what: &str, status: String, pivots: usize, dt: Duration, cpu: f64, peak: f64| {
            let s = dt.as_secs_f64();
            println!(
                "{m:>5} {n:>5} {what:>9} {status:>20} {pivots:>7} {:>9.3} {s:>9.3} {cpu:>9.2} {lu_s:>9.3} {:>7.1} {peak:>9.1}",
                1e3 * s / pivots.max(1) as f64,
                s / lu_s,
            );
        };
        row("lu", "-".into(), 0, lu_time, lu_cpu, lu_peak);
        let (sol, dt, cpu, peak) = measured(|| pb.solve_standard());
        row(
            "standard",
            format!("{:?}", sol.status),
            sol.pivots,
            dt,
            cpu,
            peak,
        );
        let (path, dt, cpu, peak) = measured(|| pb.follow());
        let pivots = path.steps.len() + path.start_pivots;
        row(
            "path",
            format!(
                "{} ({} refact.)",
                path.status.as_str(),
                path.refactorizations
            ),
            pivots,
            dt,
            cpu,
            peak,
        );
        // Non-zero z along the path: a lower bound of the kernel size k of the revised basis.
        let nz: Vec<usize> = path.breakpoints.iter().map(|b| b.z.len()).collect();
        println!(
            "      path: non-zero z per breakpoint (≈ kernel size k): mean {:.0}, max {} (n = {n})",
            nz.iter().sum::<usize>() as f64 / nz.len().max(1) as f64,
            nz.iter().max().copied().unwrap_or(0)
        );
        println!(
            "      standard: {:.2}·m pivots ({:?}); path: {} steps + {} start pivots = {:.2}·m, p_max = {:.4}",
            sol.pivots as f64 / m as f64,
            sol.strategy,
            path.steps.len(),
            path.start_pivots,
            pivots as f64 / m as f64,
            path.p_max
        );
        if sol.status != unilateral_lcp::LcpStatus::Solved {
            println!("      standard LCP not solved: {:?}", sol.attempts);
        }
        if let Some(pt) = &path.solution {
            println!(
                "      path solution at p = {} (target segment {:?}): residual {:.1e}, fallback {}",
                pt.p,
                path.target_segment,
                pt.residual.max(),
                pt.fallback
            );
        }
    }
}

fn benches(c: &mut Criterion, sizes: &[usize]) {
    let mut group = c.benchmark_group("contact_lcp");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    group.warm_up_time(Duration::from_millis(500));
    for &m in sizes {
        let pb = Problem::new(m);
        // Large sizes: a few seconds per run; the budget only fixes the iterations per sample.
        group.measurement_time(Duration::from_secs(if m >= 1000 { 20 } else { 5 }));
        group.bench_function(BenchmarkId::new("lu", m), |b| b.iter(|| pb.lu()));
        group.bench_function(BenchmarkId::new("standard", m), |b| {
            b.iter(|| pb.solve_standard().pivots)
        });
        group.bench_function(BenchmarkId::new("path", m), |b| {
            b.iter(|| pb.follow().steps.len())
        });
    }
    group.finish();
}

fn main() {
    // One run of one size, for `perf record`: UNILATERAL_BENCH_PROFILE=path:1000 (or standard:m).
    if let Ok(spec) = std::env::var("UNILATERAL_BENCH_PROFILE") {
        let (what, m) = spec.split_once(':').expect("what:m");
        let pb = Problem::new(m.parse().expect("m"));
        let t = Instant::now();
        let pivots = match what {
            "path" => pb.follow().steps.len(),
            "standard" => pb.solve_standard().pivots,
            _ => panic!("UNILATERAL_BENCH_PROFILE=path:m or standard:m"),
        };
        println!("{what} m = {m}: {pivots} pivots in {:?}", t.elapsed());
        return;
    }
    let bench_mode = std::env::args().any(|a| a == "--bench");
    let max_m: usize = std::env::var("UNILATERAL_BENCH_MAX_M")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(usize::MAX);
    let sizes: Vec<usize> = if bench_mode {
        [100, 300, 1000]
            .into_iter()
            .filter(|&m| m <= max_m)
            .collect()
    } else {
        vec![100]
    };
    if std::env::var("UNILATERAL_BENCH_REPORT").map_or(true, |v| v != "0") {
        report(&sizes);
    }
    let mut c = Criterion::default().configure_from_args();
    benches(&mut c, &sizes);
    c.final_summary();
}
