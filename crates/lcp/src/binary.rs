//! Exact scaling by powers of two: the binary exponent of a number and multiplication by
//! `2^k`. Scaling data by powers of two changes no digit of it, which is how the engine and the
//! contact formulation keep the units of the data out of the answer; the exponents of products
//! are added as integers, so no scale overflows or underflows on the way.

/// The binary exponent `e` of `x` with `2^e ≤ |x| < 2^(e+1)` (`None` for zero or non-finite).
pub fn exponent(x: f64) -> Option<i32> {
    if x == 0.0 || !x.is_finite() {
        return None;
    }
    let bits = x.abs().to_bits();
    let biased = (bits >> 52) as i32;
    if biased > 0 {
        return Some(biased - 1023);
    }
    // Subnormal: the position of the leading mantissa bit.
    let mant = bits & ((1u64 << 52) - 1);
    Some(-1074 + (63 - mant.leading_zeros() as i32))
}

/// `x · 2^k`, exact unless the result leaves the normal range.
pub fn ldexp(mut x: f64, mut k: i32) -> f64 {
    let step = |k: i32| f64::from_bits(((k + 1023) as u64) << 52);
    while k > 1000 {
        x *= step(1000);
        k -= 1000;
    }
    while k < -1000 {
        x *= step(-1000);
        k += 1000;
    }
    x * step(k)
}

#[cfg(test)]
mod tests {
    use super::{exponent, ldexp};

    /// Hand values: 2^e ≤ |x| < 2^(e+1), down to the smallest subnormal 2^-1074.
    #[test]
    fn exponents_and_exact_scaling() {
        assert_eq!(exponent(1.0), Some(0));
        assert_eq!(exponent(-0.75), Some(-1));
        assert_eq!(exponent(1e308), Some(1023)); // 1e308 = 1.11·2^1023
        assert_eq!(exponent(f64::MIN_POSITIVE), Some(-1022));
        assert_eq!(exponent(5e-324), Some(-1074));
        assert_eq!(exponent(0.0), None);
        assert_eq!(exponent(f64::NAN), None);
        assert_eq!(ldexp(1.0, -1074), 5e-324);
        assert_eq!(ldexp(0.75, 1024), 0.75 * 2f64.powi(1000) * 2f64.powi(24));
        assert_eq!(ldexp(ldexp(1.2345, 1000), -1000), 1.2345);
        assert_eq!(ldexp(ldexp(1.2345, -1020), 1020), 1.2345);
        assert_eq!(ldexp(3.0, 2000), f64::INFINITY);
    }
}
