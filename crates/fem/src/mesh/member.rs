//! The nodes along a member divided into equal elements.

/// The `n + 1` points dividing the segment from `a` to `b` into `n ≥ 1` equal parts, from `a`
/// to `b`: point `k` is `a + (k/n)·(b − a)`.
///
/// ```
/// use unilateral_fem::mesh::divide_segment;
/// assert_eq!(divide_segment([0.0, 0.0], [4.0, 2.0], 2), [[0.0, 0.0], [2.0, 1.0], [4.0, 2.0]]);
/// ```
pub fn divide_segment(a: [f64; 2], b: [f64; 2], n: usize) -> Vec<[f64; 2]> {
    (0..=n)
        .map(|k| {
            let s = k as f64 / n as f64;
            [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::divide_segment;

    /// Hand values: a sloping segment in four parts; the ends are the given points exactly.
    #[test]
    fn four_parts() {
        let p = divide_segment([1.0, -2.0], [3.0, 2.0], 4);
        assert_eq!(p.len(), 5);
        assert_eq!(
            p,
            [[1.0, -2.0], [1.5, -1.0], [2.0, 0.0], [2.5, 1.0], [3.0, 2.0]]
        );
        assert_eq!(
            divide_segment([0.0, 0.0], [1.0, 1.0], 1),
            [[0.0, 0.0], [1.0, 1.0]]
        );
    }
}
