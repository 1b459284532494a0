//! The shortest decimal text of an `f64` that reads back as the same number, written straight
//! into a `String`: exactly the text of the standard library's `{x:e}` ([`push_exp`]), the
//! layout of the CSV tables.
//!
//! The long tables write millions of numbers; the standard library's formatting goes through
//! `core::fmt` and its slower shortest-digit search. The digits here come from `zmij` (the
//! shortest digits, as the standard library's, which differ only where the number lies exactly
//! halfway between two candidates: there the standard library's are taken); the layout is
//! this module's own, so the bytes do not depend on how `zmij` lays its text out. The tests
//! compare the text with the standard library's on millions of numbers (a review compared
//! them on 245 million, the hardest near-halfway case of every exponent among them). The ascii
//! arrays of the ParaView files, whose text no earlier file fixes, take `zmij`'s own text
//! (`vtk::num`).

/// The shortest digits of a finite nonzero `x`: `±0.d₁d₂…dₙ × 10^exp`, `d₁` and `dₙ` nonzero.
struct Digits {
    negative: bool,
    digits: [u8; 24],
    len: usize,
    exp: i32,
}

impl Digits {
    fn of(x: f64) -> Digits {
        debug_assert!(x.is_finite() && x != 0.0);
        let mut buffer = zmij::Buffer::new();
        let text = buffer.format_finite(x).as_bytes();
        let (negative, text) = match text.split_first() {
            Some((b'-', rest)) => (true, rest),
            _ => (false, text),
        };
        let (mantissa, e10) = match text.iter().position(|&c| c == b'e' || c == b'E') {
            Some(i) => (&text[..i], parse_exponent(&text[i + 1..])),
            None => (text, 0),
        };
        let (int, frac) = match mantissa.iter().position(|&c| c == b'.') {
            Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
            None => (mantissa, &[][..]),
        };
        let mut d = Digits {
            negative,
            digits: [0; 24],
            len: 0,
            exp: 0,
        };
        if int.iter().all(|&c| c == b'0') {
            // 0.000ddd: the digits start after the fraction's leading zeros.
            let zeros = frac.iter().take_while(|&&c| c == b'0').count();
            let rest = &frac[zeros..];
            d.digits[..rest.len()].copy_from_slice(rest);
            d.len = rest.len();
            d.exp = e10 - zeros as i32;
        } else {
            d.digits[..int.len()].copy_from_slice(int);
            d.digits[int.len()..int.len() + frac.len()].copy_from_slice(frac);
            d.len = int.len() + frac.len();
            d.exp = e10 + int.len() as i32;
        }
        while d.len > 1 && d.digits[d.len - 1] == b'0' {
            d.len -= 1;
        }
        d
    }

    /// Whether `x` may lie exactly halfway between two numbers of these digits' length (then
    /// the standard library takes the upper one where `zmij` may take the lower one): only if
    /// `2x / 10^(exp − len)` is an odd integer, which needs its power of two to be `2⁰`.
    fn may_be_a_tie(&self, x: f64) -> bool {
        let bits = x.to_bits();
        let (biased, fraction) = ((bits >> 52) & 0x7ff, bits & ((1u64 << 52) - 1));
        let (m, e) = if biased == 0 {
            (fraction, -1074)
        } else {
            (fraction | (1u64 << 52), biased as i32 - 1075)
        };
        let k = self.exp - self.len as i32;
        m.trailing_zeros() as i32 + e + 1 - k == 0
    }

    fn digits(&self) -> &str {
        // Only ASCII digits were copied in.
        std::str::from_utf8(&self.digits[..self.len]).unwrap_or("0")
    }
}

fn parse_exponent(t: &[u8]) -> i32 {
    let (sign, t) = match t.split_first() {
        Some((b'-', rest)) => (-1, rest),
        Some((b'+', rest)) => (1, rest),
        _ => (1, t),
    };
    sign * t
        .iter()
        .fold(0i32, |a, &c| a * 10 + i32::from(c.wrapping_sub(b'0')))
}

/// Appends the text of `format!("{x:e}")`: `1.5e-3`, `-2e7`, `0e0`. A zero, a non-finite
/// number or a halfway case is written by the standard library; every other number here.
pub(crate) fn push_exp(s: &mut String, x: f64) {
    let own = (x.is_finite() && x != 0.0)
        .then(|| Digits::of(x))
        .filter(|d| !d.may_be_a_tie(x));
    let Some(d) = own else {
        use std::fmt::Write as _;
        let _ = write!(s, "{x:e}");
        return;
    };
    let digits = d.digits();
    if d.negative {
        s.push('-');
    }
    s.push_str(&digits[..1]);
    if d.len > 1 {
        s.push('.');
        s.push_str(&digits[1..]);
    }
    s.push('e');
    push_int(s, i64::from(d.exp - 1));
}

/// Appends the decimal text of an integer (`format!("{v}")`).
pub(crate) fn push_int(s: &mut String, v: i64) {
    let mut b = itoa::Buffer::new();
    s.push_str(b.format(v));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn both(x: f64) {
        let mut e = String::new();
        push_exp(&mut e, x);
        assert_eq!(e, format!("{x:e}"), "{{:e}} of {:#018x}", x.to_bits());
    }

    /// A fixed sequence of 64-bit words (splitmix64), so that a failure can be replayed.
    fn words(seed: u64, count: usize) -> impl Iterator<Item = u64> {
        let mut next = crate::replay::bits(seed);
        (0..count).map(move |_| next())
    }

    #[test]
    fn the_text_is_the_standard_librarys_for_numbers_of_every_kind() {
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            0.1,
            0.2,
            0.1 + 0.2,
            1.0 / 3.0,
            2.0 / 3.0,
            1.0,
            -1.0,
            10.0,
            100.0,
            1e15,
            1e16,
            1e17,
            1e21,
            1e22,
            1e23,
            9007199254740992.0,
            9007199254740993.0,
            123456789012345680.0,
            1e-4,
            1e-5,
            1e-7,
            0.00015,
            1.5e-3,
            -2e7,
            299792458.0,
            6.02214076e23,
            1.602176634e-19,
            // Exactly halfway between two 17-digit numbers: the standard library's is the
            // upper one (…763), zmij's the lower one (…762); and the one such case among the
            // powers of two, 2⁻²⁵ (…313 against …312).
            f64::from_bits(0x430e_fd89_f990_4ce2),
            f64::from_bits(0x3e60_0000_0000_0000),
        ];
        for x in special {
            both(x);
        }
        // Powers of ten and their neighbours, integers and halves of every size.
        for k in -325..=308 {
            let x = 10f64.powi(k);
            for y in [
                x,
                -x,
                f64::from_bits(x.to_bits() + 1),
                // 10^-325 is 0: its lower neighbour wraps to the bits of -NaN, which `both`
                // compares as the standard library writes it.
                f64::from_bits(x.to_bits().wrapping_sub(1)),
            ] {
                both(y);
            }
        }
        // Dyadic fractions of every size, where halfway cases live.
        for (w, v) in words(14, 200_000).zip(words(15, 200_000)) {
            let x = (w >> 11) as f64 * 2f64.powi((v % 120) as i32 - 100);
            both(x);
        }
        for i in 0..20_000 {
            both(i as f64);
            both(i as f64 / 2.0);
            both(-(i as f64) * 0.001);
        }
    }

    #[test]
    fn the_text_is_the_standard_librarys_for_random_bits() {
        // Every exponent and mantissa alike (most of them huge or tiny).
        for w in words(11, 400_000) {
            both(f64::from_bits(w));
        }
        // Numbers of the sizes results have: a mantissa in [1, 10) times 10^−12…10^12, with
        // few and with many digits.
        for (w, v) in words(12, 400_000).zip(words(13, 400_000)) {
            let mantissa = 1.0 + 9.0 * (w >> 11) as f64 / (1u64 << 53) as f64;
            let exp = (v % 25) as i32 - 12;
            let x = mantissa * 10f64.powi(exp);
            both(x);
            both(-x);
            let short = (mantissa * 1000.0).round() / 1000.0 * 10f64.powi(exp);
            both(short);
        }
    }

    #[test]
    fn integers_are_the_standard_librarys() {
        for v in [0, 1, -1, 9, 10, -10, 12345, i64::MAX, i64::MIN, 1 << 40] {
            let mut s = String::new();
            push_int(&mut s, v);
            assert_eq!(s, v.to_string());
        }
    }
}
