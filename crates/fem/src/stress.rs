//! Scalar measures of a plane stress state `[σxx, σyy, τxy, σzz]` (tension positive), written
//! once for the results, the pictures and the ParaView files.

/// The von Mises equivalent stress `√(½((σx−σy)² + (σy−σz)² + (σz−σx)²) + 3τxy²)`.
pub fn von_mises([sx, sy, txy, sz]: [f64; 4]) -> f64 {
    (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2)) + 3.0 * txy * txy).sqrt()
}

/// The in-plane principal stresses `(σ1, σ2)`, `σ1 ≥ σ2`.
pub fn principal([sx, sy, txy, _]: [f64; 4]) -> (f64, f64) {
    let c = 0.5 * (sx + sy);
    let rad = (0.25 * (sx - sy).powi(2) + txy * txy).sqrt();
    (c + rad, c - rad)
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
}
