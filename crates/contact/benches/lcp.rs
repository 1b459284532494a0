//! Contact-like LCPs of order `n = 3m` from `generate::beam_on_supports(m, 7)`, m = 100, 300,
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
use unilateral_contact::generate::beam_on_supports;
use unilateral_contact::ContactLcp;
use unilateral_lcp::{
    follow_path, solve_lcp, Follow, Lcp, LcpSolution, LoadPath, PathOptions, Settings,
};

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
        let lu = self.shifted.partial_piv_lu();
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

/// Resets VmHWM to the current RSS (Linux ≥ 4.0); false if refused.
fn reset_peak() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Runs `f` once; its time and the peak memory during it.
fn measured<T>(f: impl FnOnce() -> T) -> (T, Duration, f64) {
    reset_peak();
    let t = Instant::now();
    let out = black_box(f());
    let dt = t.elapsed();
    (out, dt, memory_mib().0)
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
        "{:>5} {:>5} {:>9} {:>20} {:>7} {:>9} {:>9} {:>9} {:>7} {:>9}",
        "m", "n", "what", "status", "pivots", "ms/pivot", "total s", "LU s", "×LU", "peak MiB"
    );
    for &m in sizes {
        let pb = Problem::new(m);
        let n = pb.n();
        // The LU first: the best of three (it is the yardstick).
        let mut lu_time = Duration::MAX;
        let mut lu_peak = 0.0f64;
        for _ in 0..3 {
            let (_, dt, peak) = measured(|| pb.lu());
            lu_time = lu_time.min(dt);
            lu_peak = lu_peak.max(peak);
        }
        let lu_s = lu_time.as_secs_f64();
        let row = |what: &str, status: String, pivots: usize, dt: Duration, peak: f64| {
            let s = dt.as_secs_f64();
            println!(
                "{m:>5} {n:>5} {what:>9} {status:>20} {pivots:>7} {:>9.3} {s:>9.3} {lu_s:>9.3} {:>7.1} {peak:>9.1}",
                1e3 * s / pivots.max(1) as f64,
                s / lu_s,
            );
        };
        row("lu", "-".into(), 0, lu_time, lu_peak);
        let (sol, dt, peak) = measured(|| pb.solve_standard());
        row(
            "standard",
            format!("{:?}", sol.status),
            sol.pivots,
            dt,
            peak,
        );
        let (path, dt, peak) = measured(|| pb.follow());
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
            peak,
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

fn diagnose(m: usize) {
    let pb = Problem::new(m);
    for (name, st) in [
        ("default order", Settings::default()),
        ("contact order", pb.settings.clone()),
        (
            "contact order, tol 1e-7",
            Settings {
                pivot_tolerance: Some(1e-7),
                ..pb.settings.clone()
            },
        ),
        (
            "contact order, tol 1e-12",
            Settings {
                pivot_tolerance: Some(1e-12),
                ..pb.settings.clone()
            },
        ),
        (
            "contact order, refactor 1",
            Settings {
                refactor_interval: 1,
                ..pb.settings.clone()
            },
        ),
    ] {
        let s = solve_lcp(&pb.standard, &st).unwrap();
        println!("{m} {name}: {:?} {:?}", s.status, s.attempts);
    }
    let qabs = pb.standard.q.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    let zeros: Vec<usize> = (0..pb.n())
        .filter(|&i| pb.standard.q[i].abs() <= 1e-12 * qabs)
        .collect();
    println!(
        "q entries ~0 at p = 1: {zeros:?}; negative: {}",
        pb.standard.q.iter().filter(|v| **v < 0.0).count()
    );
    for p in [0.5, 0.9, 0.99, 1.0, 1.01, 1.1, 2.0] {
        let pr = &pb.contact.problem;
        let q = pr.q0.iter().zip(&pr.d).map(|(a, b)| a + p * b).collect();
        let s = solve_lcp(&Lcp { m: pr.m.clone(), q }, &pb.settings).unwrap();
        println!("{m} p = {p}: {:?} {}", s.status, s.pivots);
    }
}

fn main() {
    if let Ok(m) = std::env::var("ONLY_PATH") {
        let pb = Problem::new(m.parse().unwrap());
        let t = Instant::now();
        let path = pb.follow();
        println!(
            "path: {} steps, {} refact., {:?}",
            path.steps.len(),
            path.refactorizations,
            t.elapsed()
        );
        return;
    }
    if let Ok(m) = std::env::var("DIAG") {
        diagnose(m.parse().unwrap());
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
