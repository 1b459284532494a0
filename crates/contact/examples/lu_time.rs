fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(3000);
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        ((i * 7 + j * 13) % 17) as f64 + if i == j { n as f64 } else { 0.0 }
    });
    let t = std::time::Instant::now();
    let lu = a.partial_piv_lu();
    println!(
        "LU {n}: {:.3} s ({})",
        t.elapsed().as_secs_f64(),
        lu.U()[(0, 0)]
    );
}
