//! Scalar measures of a plane stress state `[σxx, σyy, τxy, σzz]` (tension positive), written
//! once for the results, the pictures and the ParaView files.

/// The von Mises equivalent stress `√(½((σx−σy)² + (σy−σz)² + (σz−σx)²) + 3τxy²)`.
///
/// Computed on the components divided by the largest of them, so that a stress whose squares
/// leave double precision (above about 1e154 in any units) still has its value.
pub fn von_mises(s: [f64; 4]) -> f64 {
    let (k, [sx, sy, txy, sz]) = scaled(s);
    k * (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2)) + 3.0 * txy * txy).sqrt()
}

/// The in-plane principal stresses `(σ1, σ2)`, `σ1 ≥ σ2` (scaled as [`von_mises`] is).
pub fn principal(s: [f64; 4]) -> (f64, f64) {
    let (k, [sx, sy, txy, _]) = scaled(s);
    let c = 0.5 * (sx + sy);
    let rad = (0.25 * (sx - sy).powi(2) + txy * txy).sqrt();
    (k * (c + rad), k * (c - rad))
}

/// The largest magnitude `k` of the components (1 when all are zero or one is not finite) and
/// the components divided by it.
fn scaled(s: [f64; 4]) -> (f64, [f64; 4]) {
    let k = s.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    if k > 0.0 && k.is_finite() {
        (k, s.map(|v| v / k))
    } else {
        (1.0, s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand values: uniaxial σ gives von Mises σ; pure shear τ gives √3·τ and principal ±τ;
    /// plane strain σz = ν(σx + σy) enters von Mises.
    #[test]
    fn hand_values() {
        assert_eq!(von_mises([5.0, 0.0, 0.0, 0.0]), 5.0);
        assert!((von_mises([0.0, 0.0, 2.0, 0.0]) - 2.0 * 3f64.sqrt()).abs() < 1e-15);
        assert_eq!(principal([0.0, 0.0, 2.0, 0.0]), (2.0, -2.0));
        assert_eq!(principal([3.0, 1.0, 0.0, 7.0]), (3.0, 1.0));
        // σ = (1, 1, 0, 0.6): ½(0 + 0.16 + 0.16) = 0.16 → 0.4
        assert!((von_mises([1.0, 1.0, 0.0, 0.6]) - 0.4).abs() < 1e-15);
    }

    /// Stresses whose squares overflow (a model in units where stresses are near 1e200) keep
    /// their von Mises and principal values: the hand values above times the scale.
    #[test]
    fn stresses_whose_squares_overflow() {
        let k = 1e200;
        let rel = |a: f64, b: f64| ((a - b) / b).abs();
        assert!(rel(von_mises([0.0, 0.0, 2.0 * k, 0.0]), 2.0 * 3f64.sqrt() * k) < 1e-15);
        assert!(rel(von_mises([k, k, 0.0, 0.6 * k]), 0.4 * k) < 1e-15);
        assert_eq!(principal([0.0, 0.0, 2.0 * k, 0.0]), (2.0 * k, -2.0 * k));
        let (s1, s2) = principal([3.0 * k, k, 0.0, 7.0 * k]);
        assert!(rel(s1, 3.0 * k) < 1e-15 && rel(s2, k) < 1e-15);
        // and ones near the bottom of the range keep their digits
        let t = 1e-300;
        assert!(rel(von_mises([0.0, 0.0, 2.0 * t, 0.0]), 2.0 * 3f64.sqrt() * t) < 1e-15);
    }
}
